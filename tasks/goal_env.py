"""The goal environments of gymnasium-robotics as planshape tasks: one wrapper, the observation
readers, the reward variants.

Every gymnasium-robotics task (:mod:`planshape.tasks.point_maze`, :mod:`planshape.tasks.fetch`)
is a :class:`GoalTask`: the gymnasium-robotics environment with its own reward
(``reward="sparse"`` or ``"dense"`` selects its ``reward_type``), ``info["success"]`` (its
``is_success``/``success`` flag) and ``info["distance"]`` (``‖achieved_goal − desired_goal‖``)
after ``reset`` and every step. Observations are its dictionaries
``{"observation", "achieved_goal", "desired_goal"}``.

Example:
    >>> achieved_goal({"achieved_goal": [1.0, 2.0], "desired_goal": [0.0, 0.0]})
    array([1., 2.])
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, SupportsFloat

import gymnasium
import gymnasium_robotics
import numpy as np

from planshape.errors import BadInputError, UnknownIdError

__all__ = [
    "REWARDS",
    "GoalTask",
    "achieved_goal",
    "check_reward",
    "desired_goal",
    "goal_observation",
]

REWARDS = ("sparse", "dense")

gymnasium.register_envs(gymnasium_robotics)


class GoalTask(gymnasium.Env):
    """A gymnasium-robotics goal environment with ``success`` and ``distance`` in ``info``.

    The environment is held in :attr:`sim`, not wrapped: its ``compute_reward`` would make
    checkers (stable-baselines3's among them) take this task for a goal-conditioned ``GoalEnv``,
    whose reward ``compute_reward(achieved, desired)`` must reproduce; a shaped reward cannot.

    Args:
        sim: the unwrapped gymnasium-robotics environment.
    """

    def __init__(self, sim: gymnasium.Env):
        self.sim = sim
        self.observation_space = sim.observation_space
        self.action_space = sim.action_space
        self.metadata = dict(sim.metadata)
        self.render_mode = sim.render_mode

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        super().reset(seed=seed)
        obs, info = self.sim.reset(seed=seed, options=options)
        if "success" not in info:  # Fetch reports success only after a step
            info["success"] = self.sim._is_success(obs["achieved_goal"], obs["desired_goal"])
        return obs, self._metrics(obs, info)

    def step(
        self, action: Any
    ) -> tuple[dict[str, np.ndarray], SupportsFloat, bool, bool, dict[str, Any]]:
        obs, reward, terminated, truncated, info = self.sim.step(action)
        if "is_success" in info:
            info["success"] = info["is_success"]
        return obs, float(reward), bool(terminated), bool(truncated), self._metrics(obs, info)

    @staticmethod
    def _metrics(obs: Mapping[str, np.ndarray], info: dict[str, Any]) -> dict[str, Any]:
        info["success"] = bool(info["success"])
        info["distance"] = float(np.linalg.norm(obs["achieved_goal"] - obs["desired_goal"]))
        return info

    def render(self) -> Any:
        return self.sim.render()

    def close(self) -> None:
        self.sim.close()


def check_reward(reward: str, where: str) -> None:
    """Refuse a reward variant gymnasium-robotics does not have."""
    if reward not in REWARDS:
        raise UnknownIdError("reward variant", reward, REWARDS, hint=f"for {where}")


def achieved_goal(obs: Any) -> np.ndarray:
    """``obs["achieved_goal"]`` of a goal-environment observation.

    The abstraction layer hands classifiers ``np.asarray(obs)``, which turns a dictionary into a
    0-dimensional object array; this unwraps it.
    """
    return np.asarray(goal_observation(obs)["achieved_goal"], dtype=float)


def desired_goal(obs: Any) -> np.ndarray:
    """``obs["desired_goal"]`` (see :func:`achieved_goal`)."""
    return np.asarray(goal_observation(obs)["desired_goal"], dtype=float)


def goal_observation(obs: Any) -> Mapping[str, Any]:
    """One goal-environment observation as its dictionary (see :func:`achieved_goal`)."""
    if isinstance(obs, Mapping):
        return obs
    if isinstance(obs, np.ndarray) and obs.dtype == object and obs.ndim == 0:
        return obs.item()
    raise BadInputError(
        f"expected one goal-environment observation (a dict with 'achieved_goal'), got "
        f"{type(obs).__name__}{getattr(obs, 'shape', '')}; batches of dict observations are "
        "not supported"
    )
