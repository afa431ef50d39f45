"""drawer-open-v3 and drawer-close-v3: get the gripper to the drawer's handle, then pull the
drawer open or push it shut.

``obs[4:7]`` is the handle's position; the goal is where the handle must end up. Stages:
``(hand-at gripper handle)`` → ``(open drawer)`` or ``(closed drawer)``. Thresholds:

* ``HAND_AT`` = 5 cm, hand to handle;
* ``OPEN_RADIUS`` = 3 cm, handle to goal: drawer-open's success test;
* ``CLOSED_RADIUS`` = 6.5 cm, handle to goal: drawer-close's success test
  (``TARGET_RADIUS + 0.015``; MetaWorld puts that goal 4 cm below the handle's height, so the
  test amounts to "within about 5 cm of closed").

Example:
    >>> import numpy as np
    >>> from planshape.tasks.metaworld import observation as o
    >>> obs = np.zeros(o.OBS_DIM)
    >>> obs[o.OBJECT] = (0.0, 0.55, 0.09); obs[o.GOAL] = (0.0, 0.54, 0.09)
    >>> bool(is_open(obs, "drawer")), bool(is_closed(obs, "drawer"))
    (True, True)
"""

from __future__ import annotations

import numpy as np

from planshape.shaping.registration import AbstractModel
from planshape.tasks.common import pddl_file
from planshape.tasks.displacement import DisplacementGeometry
from planshape.tasks.metaworld.observation import distance, goal, hand, main_object

HAND_AT = 0.05
OPEN_RADIUS = 0.03
CLOSED_RADIUS = 0.065


def hand_at(obs: np.ndarray, _hand: str, _handle: str) -> np.ndarray:
    """``(hand-at ?h ?k)``: the hand is within ``HAND_AT`` of the handle."""
    return distance(hand(obs), main_object(obs)) <= HAND_AT


def is_open(obs: np.ndarray, _drawer: str) -> np.ndarray:
    """``(open ?d)``: the handle is within ``OPEN_RADIUS`` of the goal (drawer-open's success)."""
    return distance(main_object(obs), goal(obs)) <= OPEN_RADIUS


def is_closed(obs: np.ndarray, _drawer: str) -> np.ndarray:
    """``(closed ?d)``: the handle is within ``CLOSED_RADIUS`` of the goal (drawer-close's
    success)."""
    return distance(main_object(obs), goal(obs)) <= CLOSED_RADIUS


def hand_to_handle(obs: np.ndarray) -> np.ndarray:
    """Hand minus handle."""
    return hand(obs) - main_object(obs)


def handle_to_goal(obs: np.ndarray) -> np.ndarray:
    """Handle minus goal."""
    return main_object(obs) - goal(obs)


def _geometry(drawer_predicate: str) -> DisplacementGeometry:
    return DisplacementGeometry(
        displacements={"hand-to-handle": hand_to_handle, "handle-to-goal": handle_to_goal},
        targets={
            "hand-at": ("hand-to-handle", (0.0, 0.0, 0.0)),
            drawer_predicate: ("handle-to-goal", (0.0, 0.0, 0.0)),
        },
    )


def open_stages() -> AbstractModel:
    """drawer-open: reach the handle, pull the drawer open."""
    return AbstractModel(
        domain=pddl_file("metaworld", "drawer-open", "domain.pddl"),
        problem=pddl_file("metaworld", "drawer-open", "stages.pddl"),
        classifiers={"hand-at": hand_at, "open": is_open},
        geometry=_geometry("open"),
    )


def close_stages() -> AbstractModel:
    """drawer-close: reach the handle, push the drawer shut."""
    return AbstractModel(
        domain=pddl_file("metaworld", "drawer-close", "domain.pddl"),
        problem=pddl_file("metaworld", "drawer-close", "stages.pddl"),
        classifiers={"hand-at": hand_at, "closed": is_closed},
        geometry=_geometry("closed"),
    )
