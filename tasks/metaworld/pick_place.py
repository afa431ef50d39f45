"""pick-place-v3: reach the puck, grasp it, lift it, carry it to the goal (often in the air).

Stages: ``(hand-at gripper puck)`` → ``(holding gripper puck)`` → ``(lifted puck)`` →
``(at-goal puck)``. Thresholds:

* ``HAND_AT`` = 3 cm, fingertips to puck centre (MetaWorld's ``near_object`` radius);
* ``holding``: the fingertips are at the puck and the gripper opening lies in
  ``HOLDING_OPENING`` = (0.35, 0.8): closing (open is 1.0) but stopped by the puck (fingers
  closed on nothing read about 0.30; on the puck about 0.45);
* ``LIFTED_Z`` = 0.025: the puck's centre is 5 mm above its resting height (0.02); the
  goal can be as low as 5 cm, so a low lift is all the task asks for;
* ``AT_GOAL`` = 7 cm, puck to goal (MetaWorld's success radius for this task).

Example:
    >>> import numpy as np
    >>> from planshape.tasks.metaworld import observation as o
    >>> obs = np.zeros(o.OBS_DIM); obs[o.HAND] = (0.0, 0.7, 0.1); obs[o.GRIPPER] = 0.45
    >>> obs[o.OBJECT] = (0.0, 0.7, 0.06)
    >>> bool(holding(obs, "gripper", "puck")), bool(lifted(obs, "puck"))
    (True, True)
"""

from __future__ import annotations

import numpy as np

from planshape.shaping.registration import AbstractModel
from planshape.tasks.common import pddl_file
from planshape.tasks.displacement import DisplacementGeometry
from planshape.tasks.metaworld.observation import (
    distance,
    goal,
    gripper_opening,
    main_object,
    tcp,
)
from planshape.tasks.metaworld.push import hand_to_puck, puck_to_goal

HAND_AT = 0.03
HOLDING_OPENING = (0.35, 0.8)
LIFTED_Z = 0.025
AT_GOAL = 0.07


def hand_at(obs: np.ndarray, _hand: str, _puck: str) -> np.ndarray:
    """``(hand-at ?h ?p)``: the fingertips are within ``HAND_AT`` of the puck."""
    return distance(tcp(obs), main_object(obs)) <= HAND_AT


def holding(obs: np.ndarray, hand: str, puck: str) -> np.ndarray:
    """``(holding ?h ?p)``: at the puck, with the fingers closed on it."""
    opening = gripper_opening(obs)
    low, high = HOLDING_OPENING
    return hand_at(obs, hand, puck) & (opening > low) & (opening < high)


def lifted(obs: np.ndarray, _puck: str) -> np.ndarray:
    """``(lifted ?p)``: the puck's centre is at least ``LIFTED_Z`` high."""
    return main_object(obs)[..., 2] >= LIFTED_Z


def at_goal(obs: np.ndarray, _puck: str) -> np.ndarray:
    """``(at-goal ?p)``: the puck is within ``AT_GOAL`` of the goal (MetaWorld's success)."""
    return distance(main_object(obs), goal(obs)) <= AT_GOAL


def stages() -> AbstractModel:
    """Reach, grasp, lift, carry."""
    return AbstractModel(
        domain=pddl_file("metaworld", "pick-place", "domain.pddl"),
        problem=pddl_file("metaworld", "pick-place", "stages.pddl"),
        classifiers={"hand-at": hand_at, "holding": holding, "lifted": lifted, "at-goal": at_goal},
        geometry=DisplacementGeometry(
            displacements={"hand-to-puck": hand_to_puck, "puck-to-goal": puck_to_goal},
            targets={
                "hand-at": ("hand-to-puck", (0.0, 0.0, 0.0)),
                "at-goal": ("puck-to-goal", (0.0, 0.0, 0.0)),
            },
        ),
    )
