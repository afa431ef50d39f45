"""push-v3: bring the fingertips to the puck, then move the puck to the goal.

Stages: ``(hand-at gripper puck)`` → ``(at-goal puck)``. Thresholds:

* ``HAND_AT`` = 3 cm, fingertips to puck centre (MetaWorld's own ``near_object`` radius here);
* ``AT_GOAL`` = 5 cm, puck to goal (MetaWorld's success radius).

Example:
    >>> import numpy as np
    >>> from planshape.tasks.metaworld import observation as o
    >>> obs = np.zeros(o.OBS_DIM); obs[o.OBJECT] = (0.0, 0.85, 0.02); obs[o.GOAL] = (0.0, 0.8, 0.02)
    >>> bool(at_goal(obs, "puck")), bool(hand_at(obs, "gripper", "puck"))
    (True, False)
"""

from __future__ import annotations

import numpy as np

from planshape.shaping.registration import AbstractModel
from planshape.tasks.common import pddl_file
from planshape.tasks.displacement import DisplacementGeometry
from planshape.tasks.metaworld.observation import distance, goal, main_object, tcp

HAND_AT = 0.03
AT_GOAL = 0.05


def hand_at(obs: np.ndarray, _hand: str, _puck: str) -> np.ndarray:
    """``(hand-at ?h ?p)``: the fingertips are within ``HAND_AT`` of the puck."""
    return distance(tcp(obs), main_object(obs)) <= HAND_AT


def at_goal(obs: np.ndarray, _puck: str) -> np.ndarray:
    """``(at-goal ?p)``: the puck is within ``AT_GOAL`` of the goal (MetaWorld's success)."""
    return distance(main_object(obs), goal(obs)) <= AT_GOAL


def hand_to_puck(obs: np.ndarray) -> np.ndarray:
    """Fingertips minus puck."""
    return tcp(obs) - main_object(obs)


def puck_to_goal(obs: np.ndarray) -> np.ndarray:
    """Puck minus goal."""
    return main_object(obs) - goal(obs)


def stages() -> AbstractModel:
    """Reach the puck, push it to the goal."""
    return AbstractModel(
        domain=pddl_file("metaworld", "push", "domain.pddl"),
        problem=pddl_file("metaworld", "push", "stages.pddl"),
        classifiers={"hand-at": hand_at, "at-goal": at_goal},
        geometry=DisplacementGeometry(
            displacements={"hand-to-puck": hand_to_puck, "puck-to-goal": puck_to_goal},
            targets={
                "hand-at": ("hand-to-puck", (0.0, 0.0, 0.0)),
                "at-goal": ("puck-to-goal", (0.0, 0.0, 0.0)),
            },
        ),
    )
