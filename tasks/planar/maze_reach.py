"""Maze-reach: reach a goal inside a U of three walls that blocks the straight line from the
start; the way in is over the top (the source paper's maze-reach task).

Observation ``(x_e, y_e)`` (float32, bounded by the workspace); action ``(Δx, Δy) ∈ [-1, 1]²``,
a move of ``0.02 · action`` metres; goal ``(0.50, 0.00)``; start ``(0.45, -0.32)``, below the
bottom wall. Walls (centre, half-extents): ``(0.50, -0.20), (0.10, 0.01)``;
``(0.40, -0.03), (0.01, 0.18)``; ``(0.60, -0.03), (0.01, 0.18)`` — see
:attr:`PlanarGeometry.maze_walls`. They are MuJoCo contacts: the end effector stops at a wall
and slides along it (frictionless).

Example:
    >>> import numpy as np
    >>> env = MazeReachEnv()
    >>> obs, info = env.reset(seed=0)
    >>> for _ in range(10):
    ...     obs, reward, terminated, truncated, info = env.step(np.array([0.0, 1.0], np.float32))
    >>> bool(obs[1] < -0.21), reward   # blocked under the bottom wall
    (True, 0.0)
"""

from __future__ import annotations

import math

from planshape.tasks.planar.base import PlanarEnv
from planshape.tasks.planar.geometry import Rect


class MazeReachEnv(PlanarEnv):
    """Reach the goal inside the U-shaped maze with the end effector and stay there.

    Success: the end effector's centre is strictly within 0.05 m of the goal;
    ``info["distance"]`` is the straight-line distance to the goal (the paper's metric).
    Dense reward: in v0 ``-distance``, the straight-line distance through the walls, which is
    deceptive here: it pulls the end effector against the bottom wall. In v1 the paper's
    ``_get_reward_with_subgoal``: first to the nearer of the points above the side walls,
    (0.40, 0.23) and (0.60, 0.23), then to the goal (see :meth:`PlanarEnv._detour_reward`).
    ``randomize_start`` draws starts clear of the walls, anywhere in the workspace (inside the U
    included); ``randomize_goal`` draws goals inside the U. See :class:`PlanarEnv` for the
    rest.
    """

    task = "maze-reach"

    @property
    def walls(self) -> tuple[Rect, ...]:
        return self.geometry.maze_walls

    def _default_goal(self) -> tuple[float, float]:
        return self.geometry.maze_goal

    def _goal_region(self) -> Rect:
        return self.geometry.maze_goal_region

    def _task_distance(self, q: list[float]) -> float:
        return math.hypot(q[0] - self._gx, q[1] - self._gy)

    def _dense_reward(self, q: list[float], distance: float) -> float:
        return self._detour_reward(q, distance, self.geometry.maze_detour)
