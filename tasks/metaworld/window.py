"""window-open-v3 and window-close-v3: get the gripper to the window's handle, slide the window
open or shut.

``obs[4:7]`` is MetaWorld's ``handleOpenStart`` (open) or ``handleCloseStart`` (close) site,
which sits above and beside the point where the gripper pushes the handle; the push point is
the site plus ``OPEN_PUSH_POINT`` = (−3, −3, −8) cm or ``CLOSE_PUSH_POINT`` = (+3, −3, −8) cm
(the points MetaWorld's scripted experts aim for). Stages: ``(hand-at gripper handle)`` →
``(open window)`` or ``(closed window)``. Thresholds:

* ``HAND_AT`` = 5 cm, hand to the push point;
* ``AT_GOAL_X`` = 5 cm, the handle's x-distance to the goal: MetaWorld's success test for both.

Example:
    >>> import numpy as np
    >>> from planshape.tasks.metaworld import observation as o
    >>> obs = np.zeros(o.OBS_DIM)
    >>> obs[o.OBJECT] = (0.1, 0.75, 0.16); obs[o.HAND] = (0.07, 0.72, 0.08)
    >>> bool(hand_at_open_push_point(obs, "gripper", "handle"))
    True
"""

from __future__ import annotations

import numpy as np

from planshape.shaping.abstraction import Classifier
from planshape.shaping.registration import AbstractModel
from planshape.tasks.common import pddl_file
from planshape.tasks.displacement import Displacement, DisplacementGeometry
from planshape.tasks.metaworld.observation import goal, hand, main_object

OPEN_PUSH_POINT = np.array([-0.03, -0.03, -0.08])
CLOSE_PUSH_POINT = np.array([0.03, -0.03, -0.08])
HAND_AT = 0.05
AT_GOAL_X = 0.05


def hand_to_open_push_point(obs: np.ndarray) -> np.ndarray:
    """Hand minus the point that pushes the window open."""
    return hand(obs) - (main_object(obs) + OPEN_PUSH_POINT)


def hand_to_close_push_point(obs: np.ndarray) -> np.ndarray:
    """Hand minus the point that pushes the window shut."""
    return hand(obs) - (main_object(obs) + CLOSE_PUSH_POINT)


def hand_at_open_push_point(obs: np.ndarray, _hand: str, _handle: str) -> np.ndarray:
    """window-open ``(hand-at ?h ?k)``: the hand is within ``HAND_AT`` of the push point."""
    return np.linalg.norm(hand_to_open_push_point(obs), axis=-1) <= HAND_AT


def hand_at_close_push_point(obs: np.ndarray, _hand: str, _handle: str) -> np.ndarray:
    """window-close ``(hand-at ?h ?k)``: the hand is within ``HAND_AT`` of the push point."""
    return np.linalg.norm(hand_to_close_push_point(obs), axis=-1) <= HAND_AT


def handle_at_goal(obs: np.ndarray, _window: str) -> np.ndarray:
    """``(open ?w)`` / ``(closed ?w)``: the handle's x is within ``AT_GOAL_X`` of the goal's
    (MetaWorld's success)."""
    return np.abs(handle_to_goal(obs)[..., 0]) <= AT_GOAL_X


def handle_to_goal(obs: np.ndarray) -> np.ndarray:
    """The handle's x minus the goal's x (a 1-vector: only x decides success)."""
    return main_object(obs)[..., :1] - goal(obs)[..., :1]


def _model(
    task: str, hand_at: Classifier, to_push_point: Displacement, window_predicate: str
) -> AbstractModel:
    return AbstractModel(
        domain=pddl_file("metaworld", task, "domain.pddl"),
        problem=pddl_file("metaworld", task, "stages.pddl"),
        classifiers={"hand-at": hand_at, window_predicate: handle_at_goal},
        geometry=DisplacementGeometry(
            displacements={"hand-to-handle": to_push_point, "handle-to-goal": handle_to_goal},
            targets={
                "hand-at": ("hand-to-handle", (0.0, 0.0, 0.0)),
                window_predicate: ("handle-to-goal", (0.0,)),
            },
        ),
    )


def open_stages() -> AbstractModel:
    """window-open: reach the handle, slide the window open."""
    return _model("window-open", hand_at_open_push_point, hand_to_open_push_point, "open")


def close_stages() -> AbstractModel:
    """window-close: reach the handle, slide the window shut."""
    return _model("window-close", hand_at_close_push_point, hand_to_close_push_point, "closed")
