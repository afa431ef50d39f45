"""reach: move the fingertips to the goal. One stage: ``(hand-at gripper target)``.

Threshold: the fingertip centre within ``AT_GOAL`` = 5 cm of the goal, MetaWorld's success test
for this task. ``planshape/MetaWorld-reach-v4`` observes the fingertip centre (MetaWorld's
``tcp_center``, in ``obs[11:14]``, see :mod:`~.observation`), so the plan's last subgoal holds
on the very step ``info["success"]`` does (:func:`stages`). ``-v3``, kept for its stored runs,
estimates it as a fixed offset from the hand and holds 2–5 steps late (:func:`stages_v3`).

Example:
    >>> import numpy as np
    >>> from planshape.tasks.metaworld import observation as o
    >>> obs = np.zeros(o.OBS_DIM); obs[o.TCP] = (0.0, 0.8, 0.24); obs[o.GOAL] = (0.0, 0.8, 0.2)
    >>> bool(hand_at(obs, "gripper", "target"))
    True
"""

from __future__ import annotations

import numpy as np

from planshape.shaping.registration import AbstractModel
from planshape.tasks.common import pddl_file
from planshape.tasks.displacement import DisplacementGeometry
from planshape.tasks.metaworld.observation import distance, goal, observed_tcp, tcp

AT_GOAL = 0.05


def hand_at(obs: np.ndarray, _hand: str, _location: str) -> np.ndarray:
    """``(hand-at ?h ?l)``: the observed fingertip centre is within ``AT_GOAL`` of the goal
    (MetaWorld's success)."""
    return distance(observed_tcp(obs), goal(obs)) <= AT_GOAL


def hand_to_goal(obs: np.ndarray) -> np.ndarray:
    """Fingertips minus goal."""
    return observed_tcp(obs) - goal(obs)


def hand_at_estimated(obs: np.ndarray, _hand: str, _location: str) -> np.ndarray:
    """reach-v3's ``(hand-at ?h ?l)``: the fingertips, estimated from the hand, within
    ``AT_GOAL`` of the goal."""
    return distance(tcp(obs), goal(obs)) <= AT_GOAL


def hand_to_goal_estimated(obs: np.ndarray) -> np.ndarray:
    """reach-v3's fingertips (estimated) minus goal."""
    return tcp(obs) - goal(obs)


def _stages(hand_at_goal, displacement) -> AbstractModel:
    return AbstractModel(
        domain=pddl_file("metaworld", "reach", "domain.pddl"),
        problem=pddl_file("metaworld", "reach", "stages.pddl"),
        classifiers={"hand-at": hand_at_goal},
        geometry=DisplacementGeometry(
            displacements={"hand-to-goal": displacement},
            targets={"hand-at": ("hand-to-goal", (0.0, 0.0, 0.0))},
        ),
    )


def stages() -> AbstractModel:
    """The one-stage model, ``(move-hand gripper target)``, on the observed fingertip centre
    (reach-v4)."""
    return _stages(hand_at, hand_to_goal)


def stages_v3() -> AbstractModel:
    """The one-stage model on the fingertip centre estimated from the hand (reach-v3)."""
    return _stages(hand_at_estimated, hand_to_goal_estimated)
