"""Fetch (Reach, Push) of gymnasium-robotics, with their stage models and classifiers.

``gripper-at`` (FetchReach) and ``at-goal`` (FetchPush) are the environment's own success
test, distance below 5 cm; ``touching`` holds when the gripper is within ``FETCH_TOUCHING`` =
7 cm of the block's centre (pushing contact is at 4–6 cm) and level with it (heights within
``FETCH_LEVEL`` = 2 cm; a gripper passing over the block does not count).

Example:
    >>> import gymnasium, planshape
    >>> env = gymnasium.make("planshape/FetchReach-v4")  # doctest: +SKIP
"""

from __future__ import annotations

from typing import Any

import gymnasium
import numpy as np

from planshape.shaping.registration import AbstractModel
from planshape.tasks.common import distance, pddl_file
from planshape.tasks.displacement import DisplacementGeometry
from planshape.tasks.goal_env import (
    GoalTask,
    achieved_goal,
    check_reward,
    desired_goal,
    goal_observation,
)

#: FetchPush's ``touching``: gripper to block centre, and their height difference
FETCH_TOUCHING = 0.07
FETCH_LEVEL = 0.02


def fetch(env_id: str = "FetchReach-v4", reward: str = "sparse", **kwargs: Any) -> GoalTask:
    """A Fetch task with its own sparse (−1/0) or dense (−distance) reward.

    Args:
        env_id: the gymnasium-robotics id, ``"FetchReach-v4"`` or ``"FetchPush-v4"``.
        reward: gymnasium-robotics' ``reward_type``.
        **kwargs: further keyword arguments of the Fetch environment (``render_mode``, …).
    """
    check_reward(reward, env_id)
    return GoalTask(gymnasium.make(env_id, reward_type=reward, **kwargs).unwrapped)


def _success(obs: Any) -> np.ndarray:
    # Fetch's own test: distance strictly below distance_threshold (0.05 for Reach and Push).
    return distance(achieved_goal(obs), desired_goal(obs)) < 0.05


def gripper_at(obs: Any, _gripper: str, _location: str) -> np.ndarray:
    """FetchReach ``(gripper-at ?g ?l)``: the environment's success test."""
    return _success(obs)


def block_at_goal(obs: Any, _block: str) -> np.ndarray:
    """FetchPush ``(at-goal ?b)``: the environment's success test."""
    return _success(obs)


def touching(obs: Any, _gripper: str, _block: str) -> np.ndarray:
    """FetchPush ``(touching ?g ?b)``: the gripper within ``FETCH_TOUCHING`` of the block and
    level with it (within ``FETCH_LEVEL``)."""
    offset = gripper_to_block(obs)
    near = distance(offset, 0.0) <= FETCH_TOUCHING
    return near & (np.abs(offset[..., 2]) <= FETCH_LEVEL)


def achieved_to_goal(obs: Any) -> np.ndarray:
    """``achieved_goal − desired_goal``: the gripper (Reach) or the block (Push) to the goal."""
    return achieved_goal(obs) - desired_goal(obs)


def gripper_to_block(obs: Any) -> np.ndarray:
    """Gripper minus block, from ``observation[0:3]`` and ``observation[3:6]``."""
    observation = np.asarray(goal_observation(obs)["observation"], dtype=float)
    return observation[..., 0:3] - observation[..., 3:6]


def fetch_reach_stages() -> AbstractModel:
    """FetchReach: ``(move-gripper gripper target)``."""
    return AbstractModel(
        domain=pddl_file("fetch", "reach", "domain.pddl"),
        problem=pddl_file("fetch", "reach", "stages.pddl"),
        classifiers={"gripper-at": gripper_at},
        geometry=DisplacementGeometry(
            displacements={"gripper-to-goal": achieved_to_goal},
            targets={"gripper-at": ("gripper-to-goal", (0.0, 0.0, 0.0))},
        ),
    )


def fetch_push_stages() -> AbstractModel:
    """FetchPush: reach the block, push it to the goal."""
    return AbstractModel(
        domain=pddl_file("fetch", "push", "domain.pddl"),
        problem=pddl_file("fetch", "push", "stages.pddl"),
        classifiers={"touching": touching, "at-goal": block_at_goal},
        geometry=DisplacementGeometry(
            displacements={"gripper-to-block": gripper_to_block, "block-to-goal": achieved_to_goal},
            targets={
                "touching": ("gripper-to-block", (0.0, 0.0, 0.0)),
                "at-goal": ("block-to-goal", (0.0, 0.0, 0.0)),
            },
        ),
    )
