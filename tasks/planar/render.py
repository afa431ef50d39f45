"""A top-down picture of a planar task as an RGB array, drawn with numpy (no OpenGL needed).

Example:
    >>> from planshape.tasks.planar import PushEnv
    >>> env = PushEnv(render_mode="rgb_array")
    >>> _ = env.reset(seed=0)
    >>> env.render().shape
    (260, 220, 3)
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from planshape.tasks.planar.geometry import PlanarGeometry, Rect

PIXELS_PER_METRE = 400
BACKGROUND = (245, 245, 240)
WALL = (90, 90, 90)
GOAL = (60, 170, 80)
BOX = (200, 120, 40)
END_EFFECTOR = (40, 90, 200)
MARK = (200, 60, 160)


class TopDownCanvas:
    """Pixels of the workspace: x to the right, y upwards (row 0 is the top edge)."""

    def __init__(self, geometry: PlanarGeometry, scale: int = PIXELS_PER_METRE):
        self.low = np.array(geometry.workspace.low)
        high = np.array(geometry.workspace.high)
        self.scale = scale
        # rounded first: a 0.55 m side is 220.00000000000003 pixels, which is 220, not 221
        width, height = np.ceil(np.round((high - self.low) * scale, 6)).astype(int)
        self.image = np.empty((height, width, 3), dtype=np.uint8)
        self.image[:] = BACKGROUND
        cols, rows = np.meshgrid(np.arange(width), np.arange(height))
        self.x = self.low[0] + (cols + 0.5) / scale
        self.y = high[1] - (rows + 0.5) / scale

    def rect(self, rect: Rect, colour: Sequence[int]) -> None:
        inside = (
            (self.x >= rect.low[0])
            & (self.x <= rect.high[0])
            & (self.y >= rect.low[1])
            & (self.y <= rect.high[1])
        )
        self.image[inside] = colour

    def disc(self, centre: Sequence[float], radius: float, colour: Sequence[int], ring=False):
        d2 = (self.x - centre[0]) ** 2 + (self.y - centre[1]) ** 2
        inside = d2 <= radius**2
        if ring:
            inside &= d2 >= (radius - 2.0 / self.scale) ** 2
        self.image[inside] = colour


def draw(
    geometry: PlanarGeometry,
    ee: Sequence[float],
    goal: Sequence[float],
    walls: Sequence[Rect] = (),
    box: Sequence[float] | None = None,
    marks: Sequence[Sequence[float]] = (),
) -> np.ndarray:
    """The picture: walls, the success region around the goal, ``marks`` (e.g. where the
    plan's subgoals put the end effector and the box), the box and the end effector."""
    canvas = TopDownCanvas(geometry)
    for wall in walls:
        canvas.rect(wall, WALL)
    canvas.disc(goal, geometry.success_threshold, GOAL, ring=True)
    for mark in marks:
        canvas.disc(mark, 0.008, MARK)
    if box is not None and geometry.object_radius is not None:
        canvas.disc(box, geometry.object_radius, BOX)
    elif box is not None:
        h = geometry.box_half_size
        canvas.rect(Rect.from_center((box[0], box[1]), (h, h)), BOX)
    canvas.disc(ee, geometry.ee_radius, END_EFFECTOR)
    return canvas.image
