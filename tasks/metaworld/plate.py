"""plate-slide-v3: get the hand behind the plate, slide it across the table into the goal.

``obs[4:7]`` is the plate (MetaWorld's ``puck`` geom); the goal is the centre of the net it
must slide into. Stages: ``(hand-at gripper plate)`` → ``(at-goal plate)``. Thresholds
(``sawyer_plate_slide_v3.py`` and its scripted expert):

* ``hand-at``: the hand within ``HAND_AT`` = 3 cm of the plate plus ``PUSH_POINT`` =
  (0, −5, 5.5) cm, where the scripted expert's hand rides behind the plate while it pushes it
  (hand minus plate (−0.01 … 0.00, −0.05, 0.053 … 0.058) m over the push, seeds 0 and 1; the
  plate starts at a fixed place 18 cm below the hand, so the predicate never holds at reset);
* ``at-goal``: the plate within ``AT_GOAL`` = 7 cm of the goal: MetaWorld's success test
  (``obj_to_target <= 0.07``, the distance from ``obs[4:7]`` to ``_target_pos``; the
  classifier holds exactly when ``info["success"]`` does).

Example:
    >>> import numpy as np
    >>> from planshape.tasks.metaworld import observation as o
    >>> obs = np.zeros(o.OBS_DIM)
    >>> obs[o.OBJECT] = (0.0, 0.83, 0.015); obs[o.GOAL] = (0.0, 0.88, 0.0)
    >>> obs[o.HAND] = obs[o.OBJECT] + PUSH_POINT
    >>> bool(hand_at(obs, "gripper", "plate")), bool(at_goal(obs, "plate"))
    (True, True)
"""

from __future__ import annotations

import numpy as np

from planshape.shaping.registration import AbstractModel
from planshape.tasks.common import pddl_file
from planshape.tasks.displacement import DisplacementGeometry
from planshape.tasks.metaworld.observation import distance, goal, hand, main_object

PUSH_POINT = np.array([0.0, -0.05, 0.055])
HAND_AT = 0.03
AT_GOAL = 0.07


def hand_to_plate(obs: np.ndarray) -> np.ndarray:
    """Hand minus the point it pushes the plate from (the plate plus ``PUSH_POINT``)."""
    return hand(obs) - (main_object(obs) + PUSH_POINT)


def plate_to_goal(obs: np.ndarray) -> np.ndarray:
    """Plate minus goal."""
    return main_object(obs) - goal(obs)


def hand_at(obs: np.ndarray, _hand: str, _plate: str) -> np.ndarray:
    """``(hand-at ?h ?p)``: the hand is within ``HAND_AT`` of the push point."""
    return np.linalg.norm(hand_to_plate(obs), axis=-1) <= HAND_AT


def at_goal(obs: np.ndarray, _plate: str) -> np.ndarray:
    """``(at-goal ?p)``: the plate is within ``AT_GOAL`` of the goal (MetaWorld's success)."""
    return distance(main_object(obs), goal(obs)) <= AT_GOAL


def stages() -> AbstractModel:
    """Get behind the plate, slide it into the goal."""
    return AbstractModel(
        domain=pddl_file("metaworld", "plate-slide", "domain.pddl"),
        problem=pddl_file("metaworld", "plate-slide", "stages.pddl"),
        classifiers={"hand-at": hand_at, "at-goal": at_goal},
        geometry=DisplacementGeometry(
            displacements={"hand-to-plate": hand_to_plate, "plate-to-goal": plate_to_goal},
            targets={
                "hand-at": ("hand-to-plate", (0.0, 0.0, 0.0)),
                "at-goal": ("plate-to-goal", (0.0, 0.0, 0.0)),
            },
        ),
    )
