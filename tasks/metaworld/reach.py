"""reach-v3: move the fingertips to the goal. One stage: ``(hand-at gripper target)``.

Threshold: fingertips (hand + :data:`~.observation.TCP_OFFSET`) within ``AT_GOAL`` = 5 cm of the
goal, MetaWorld's success radius for this task.

Example:
    >>> import numpy as np
    >>> from planshape.tasks.metaworld import observation as o
    >>> obs = np.zeros(o.OBS_DIM); obs[o.HAND] = (0.0, 0.8, 0.245); obs[o.GOAL] = (0.0, 0.8, 0.2)
    >>> bool(hand_at(obs, "gripper", "target"))
    True
"""

from __future__ import annotations

import numpy as np

from planshape.registration import AbstractModel
from planshape.tasks.common import pddl_file
from planshape.tasks.displacement import DisplacementGeometry
from planshape.tasks.metaworld.observation import distance, goal, tcp

AT_GOAL = 0.05


def hand_at(obs: np.ndarray, _hand: str, _location: str) -> np.ndarray:
    """``(hand-at ?h ?l)``: the fingertips are within ``AT_GOAL`` of the goal."""
    return distance(tcp(obs), goal(obs)) <= AT_GOAL


def hand_to_goal(obs: np.ndarray) -> np.ndarray:
    """Fingertips minus goal."""
    return tcp(obs) - goal(obs)


def stages() -> AbstractModel:
    """The one-stage model: ``(move-hand gripper target)``."""
    return AbstractModel(
        domain=pddl_file("metaworld", "reach", "domain.pddl"),
        problem=pddl_file("metaworld", "reach", "stages.pddl"),
        classifiers={"hand-at": hand_at},
        geometry=DisplacementGeometry(
            displacements={"hand-to-goal": hand_to_goal},
            targets={"hand-at": ("hand-to-goal", (0.0, 0.0, 0.0))},
        ),
    )
