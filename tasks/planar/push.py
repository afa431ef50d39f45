"""Push: push a box to a goal with the end effector (the source paper's pushing task).

Observation ``(x_e, y_e, x_o, y_o)``: end effector then box (float32; the end effector bounded
by the workspace, the box by the workspace grown by ``box_margin``); action
``(Δx, Δy) ∈ [-1, 1]²``, a move of ``0.02 · action`` metres. The object — in v0 a square box of
half side 0.03 m, in v1 the paper's cylinder of radius 0.05 m (1 kg, friction 0.9) — starts
at ``(0.35, -0.10)``, its goal is ``(0.50, 0.20)``; the end effector starts at ``(0.45, -0.32)``.
The box slides on the plane without rotating, follows the end effector while pushed (also
sideways along the pushed face, by friction) and stops within about 2.5 mm when it is no
longer pushed.

Example:
    >>> env = PushEnv()
    >>> obs, info = env.reset(seed=0)
    >>> [round(float(v), 2) for v in obs], info["success"], round(info["distance"], 3)
    ([0.45, -0.32, 0.35, -0.1], False, 0.335)
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import ClassVar

import numpy as np

from planshape.errors import BadInputError
from planshape.tasks.planar.base import _MAX_DRAWS, PlanarEnv
from planshape.tasks.planar.geometry import Rect


class PushEnv(PlanarEnv):
    """Push the box to its goal and leave it there.

    Success: the box's centre is strictly within 0.05 m of the goal; ``info["distance"]`` is
    the box-to-goal distance (the paper's metric), and ``info["box_position"]`` is added to the
    common keys. Dense reward in v0: ``-(|ee - box| + |box - goal|)``: approach the box, then
    bring it to the goal. In v1 the paper's (``pushing_task.py``): ``-2|ee-box|² - |box-goal|³``
    when the end effector is within 0.05 m of the object's centre, else
    ``-|box-goal|² + (previous - current box-goal distance)``; the cylinder's contact distance
    is 0.07 m, so its first branch never fires, as in the paper.
    ``randomize_start`` draws the box from ``box_start_region`` and the end effector from the
    workspace, apart from each other; ``randomize_goal`` draws the box goal from
    ``goal_region``. See :class:`PlanarEnv` for the rest.
    """

    task = "push"
    has_box = True
    entities: ClassVar[Mapping[str, slice]] = {"ee": slice(0, 2), "box": slice(2, 4)}

    def _default_goal(self) -> tuple[float, float]:
        return self.geometry.box_goal

    def _goal_region(self) -> Rect:
        return self.geometry.goal_region

    def _set_default_start(self) -> None:
        self._data.qpos[0:2] = self.geometry.ee_start
        self._data.qpos[2:4] = self.geometry.box_start

    def _sample_start(self) -> None:
        g = self.geometry
        apart = g.contact_distance + 0.01
        ee_region, box_region = g.ee_start_region, g.box_start_region
        for _ in range(_MAX_DRAWS):
            ee, box = ee_region.sample(self.np_random), box_region.sample(self.np_random)
            overlapping = abs(ee[0] - box[0]) < apart and abs(ee[1] - box[1]) < apart
            solved = math.hypot(box[0] - self._gx, box[1] - self._gy) < 2 * self._threshold
            if not (overlapping or solved):
                self._data.qpos[0:2] = ee
                self._data.qpos[2:4] = box
                return
        raise BadInputError(f"{self.task}: found no valid random start in {_MAX_DRAWS} draws")

    @property
    def box_position(self) -> np.ndarray:
        """The box's current (x, y); a copy."""
        return self._data.qpos[2:4].copy()

    def _task_distance(self, q: list[float]) -> float:
        return math.hypot(q[2] - self._gx, q[3] - self._gy)

    def _dense_reward(self, q: list[float], distance: float) -> float:
        to_box = math.hypot(q[0] - q[2], q[1] - q[3])
        if self.version == "v0":
            return -(to_box + distance)
        if to_box < self._threshold:
            return -2.0 * to_box**2 - distance**3
        return -(distance**2) + (self._previous_distance - distance)
