"""handle-press-v3: put the hand on the end of the lever, press the lever down.

``obs[4:7]`` is MetaWorld's ``handleStart`` site, the lever's free end; the goal is the
``goalPress`` site, the height that end must be pressed down to. Stages: ``(hand-at gripper
handle)`` → ``(pressed handle)``. Thresholds (``sawyer_handle_press_v3.py`` and its scripted
expert):

* ``hand-at``: the hand within ``HAND_AT`` = 3 cm of the handle plus ``PRESS_POINT`` =
  (0, −3, −1.5) cm, where the scripted expert's hand rests on the lever while it presses it
  down (hand minus handle (0.00, −0.03, −0.003 … −0.018) m over the press, seeds 0 and 1; the hand
  starts 3.7 cm or more above that point, so the predicate never holds at reset);
* ``pressed``: the handle's height within ``PRESS_DEPTH`` = 2 cm of the goal's:
  MetaWorld's success test (``target_to_obj <= TARGET_RADIUS``, where ``target_to_obj`` is
  ``|handle_z − goal_z|``; it reads the same ``handleStart`` site and ``_target_pos`` as the
  observation, so the classifier holds exactly when ``info["success"]`` does).

MetaWorld's ``obj_to_target`` is that height difference, so ``info["distance"]`` needs no entry
in :data:`~.env.DISTANCES`.

Example:
    >>> import numpy as np
    >>> from planshape.tasks.metaworld import observation as o
    >>> obs = np.zeros(o.OBS_DIM)
    >>> obs[o.OBJECT] = (0.0, 0.65, 0.09); obs[o.GOAL] = (0.0, 0.65, 0.075)
    >>> obs[o.HAND] = obs[o.OBJECT] + PRESS_POINT
    >>> bool(hand_at(obs, "gripper", "handle")), bool(is_pressed(obs, "handle"))
    (True, True)
    >>> handle_to_goal(obs).round(3).tolist()
    [0.015]
"""

from __future__ import annotations

import numpy as np

from planshape.shaping.registration import AbstractModel
from planshape.tasks.common import pddl_file
from planshape.tasks.displacement import DisplacementGeometry
from planshape.tasks.metaworld.observation import goal, hand, main_object

PRESS_POINT = np.array([0.0, -0.03, -0.015])
HAND_AT = 0.03
PRESS_DEPTH = 0.02


def hand_to_handle(obs: np.ndarray) -> np.ndarray:
    """Hand minus the point where it presses the lever (the handle plus ``PRESS_POINT``)."""
    return hand(obs) - (main_object(obs) + PRESS_POINT)


def handle_to_goal(obs: np.ndarray) -> np.ndarray:
    """The handle's height minus the goal's (a 1-vector: only the height decides success)."""
    return main_object(obs)[..., 2:] - goal(obs)[..., 2:]


def hand_at(obs: np.ndarray, _hand: str, _handle: str) -> np.ndarray:
    """``(hand-at ?h ?k)``: the hand is within ``HAND_AT`` of the press point."""
    return np.linalg.norm(hand_to_handle(obs), axis=-1) <= HAND_AT


def is_pressed(obs: np.ndarray, _handle: str) -> np.ndarray:
    """``(pressed ?k)``: the handle's height is within ``PRESS_DEPTH`` of the goal's
    (MetaWorld's success)."""
    return np.abs(handle_to_goal(obs)[..., 0]) <= PRESS_DEPTH


def stages() -> AbstractModel:
    """Put the hand on the lever, press it down."""
    return AbstractModel(
        domain=pddl_file("metaworld", "handle-press", "domain.pddl"),
        problem=pddl_file("metaworld", "handle-press", "stages.pddl"),
        classifiers={"hand-at": hand_at, "pressed": is_pressed},
        geometry=DisplacementGeometry(
            displacements={"hand-to-handle": hand_to_handle, "handle-to-goal": handle_to_goal},
            targets={
                "hand-at": ("hand-to-handle", (0.0, 0.0, 0.0)),
                "pressed": ("handle-to-goal", (0.0,)),
            },
        ),
    )
