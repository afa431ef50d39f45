"""door-open-v3: hook the door's handle, then swing the door open.

``obs[4:7]`` is the handle's position. Stages: ``(hand-at gripper handle)`` → ``(open door)``.
Thresholds:

* ``HAND_AT`` = 6 cm, hand to handle (the hand stays within about 5 cm of the handle while it
  pulls the door round);
* ``OPEN_X`` = 8 cm, the handle's x-distance to the goal: MetaWorld's success test.

Example:
    >>> import numpy as np
    >>> from planshape.tasks.metaworld import observation as o
    >>> obs = np.zeros(o.OBS_DIM)
    >>> obs[o.OBJECT] = (-0.25, 0.45, 0.15); obs[o.GOAL] = (-0.3, 0.45, 0.15)
    >>> bool(is_open(obs, "door"))
    True
"""

from __future__ import annotations

import numpy as np

from planshape.shaping.registration import AbstractModel
from planshape.tasks.common import pddl_file
from planshape.tasks.displacement import DisplacementGeometry
from planshape.tasks.metaworld.observation import distance, goal, hand, main_object

HAND_AT = 0.06
OPEN_X = 0.08


def hand_at(obs: np.ndarray, _hand: str, _handle: str) -> np.ndarray:
    """``(hand-at ?h ?k)``: the hand is within ``HAND_AT`` of the handle."""
    return distance(hand(obs), main_object(obs)) <= HAND_AT


def is_open(obs: np.ndarray, _door: str) -> np.ndarray:
    """``(open ?d)``: the handle's x is within ``OPEN_X`` of the goal's (MetaWorld's success)."""
    return np.abs(handle_to_goal(obs)[..., 0]) <= OPEN_X


def hand_to_handle(obs: np.ndarray) -> np.ndarray:
    """Hand minus handle."""
    return hand(obs) - main_object(obs)


def handle_to_goal(obs: np.ndarray) -> np.ndarray:
    """The handle's x minus the goal's x (a 1-vector: only x decides success)."""
    return main_object(obs)[..., :1] - goal(obs)[..., :1]


def stages() -> AbstractModel:
    """Reach the handle, pull the door open."""
    return AbstractModel(
        domain=pddl_file("metaworld", "door-open", "domain.pddl"),
        problem=pddl_file("metaworld", "door-open", "stages.pddl"),
        classifiers={"hand-at": hand_at, "open": is_open},
        geometry=DisplacementGeometry(
            displacements={"hand-to-handle": hand_to_handle, "handle-to-goal": handle_to_goal},
            targets={
                "hand-at": ("hand-to-handle", (0.0, 0.0, 0.0)),
                "open": ("handle-to-goal", (0.0,)),
            },
        ),
    )
