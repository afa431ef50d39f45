"""Reach: move the end effector to a goal and stay there (the source paper's reaching task).

Observation ``(x_e, y_e)`` (float32, bounded by the workspace); action ``(Δx, Δy) ∈ [-1, 1]²``,
a move of ``0.02 · action`` metres; goal ``(0.50, 0.26)``; start ``(0.45, -0.32)``.
In version ``v1`` (the paper's ``with_obstacle=True``) a wall, centre ``(0.50, 0.15)`` and
half-extents ``(0.18, 0.01)``, lies between start and goal; a move that would touch it is not
made (the paper's code undoes it), so the way to the goal passes either end of the wall.

Example:
    >>> import numpy as np
    >>> env = ReachEnv(reward="dense")
    >>> obs, info = env.reset(seed=0)
    >>> bool(np.allclose(obs, (0.45, -0.32))), info["success"]
    (True, False)
    >>> obs, reward, terminated, truncated, info = env.step(np.array([0.0, 1.0], np.float32))
    >>> round(float(obs[1]), 3), round(reward, 3) == -round(info["distance"], 3), terminated
    (-0.3, True, False)
"""

from __future__ import annotations

import math

from planshape.tasks.planar.base import PlanarEnv
from planshape.tasks.planar.geometry import Rect


class ReachEnv(PlanarEnv):
    """Reach the goal with the end effector and stay there.

    Success: the end effector's centre is strictly within ``success_threshold`` (0.05 m) of the
    goal; ``info["distance"]`` is that distance. Dense reward: in v0 (no wall) ``-distance``;
    in v1 the paper's ``_get_reward_with_subgoal``, which leads to the nearer end of the wall
    first (see :meth:`PlanarEnv._detour_reward`). See :class:`PlanarEnv` for the constructor
    arguments, the workspace rule and the ``info`` keys.
    """

    task = "reach"
    wall_contact = "reject"

    @property
    def walls(self) -> tuple[Rect, ...]:
        return self.geometry.reach_walls

    def _default_goal(self) -> tuple[float, float]:
        return self.geometry.reach_goal

    def _goal_region(self) -> Rect:
        return self.geometry.goal_region

    def _task_distance(self, q: list[float]) -> float:
        return math.hypot(q[0] - self._gx, q[1] - self._gy)

    def _dense_reward(self, q: list[float], distance: float) -> float:
        return self._detour_reward(q, distance, self.geometry.reach_detour)
