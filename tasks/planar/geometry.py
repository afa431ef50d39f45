"""Geometry of the planar tasks, in metres: one frozen object that environments, PDDL models,
classifiers and oracles all read, so that a wall or a goal is defined in exactly one place.

The numbers are those of the source paper's released code (the AIRobot/HW4 UR5e testbed): the
workspace ``x ∈ [0.23, 0.78]``, ``y ∈ [−0.35, 0.30]``, the end-effector start ``(0.45, −0.32)``,
steps of ``0.02`` per unit action, success within ``0.05`` of the goal.

Two versions exist. :data:`GEOMETRY` is that of the ``-v0`` tasks: reach without a wall and a
square box in push. :data:`PAPER_GEOMETRY` is that of the ``-v1`` tasks, the paper's code as
its ``main.py`` ran it: reach behind a wall (``with_obstacle=True``), push with a cylinder of
radius 0.05, and the detour points the paper's dense rewards and subgoals use.

Example:
    >>> from planshape.tasks.planar.geometry import GEOMETRY
    >>> GEOMETRY.in_workspace((0.45, -0.32)), GEOMETRY.in_workspace((0.20, 0.0))
    (True, False)
    >>> [w.center for w in GEOMETRY.maze_walls]
    [(0.5, -0.2), (0.4, -0.03), (0.6, -0.03)]
    >>> GEOMETRY.maze_walls[0].contains((0.5, -0.22), margin=GEOMETRY.ee_radius)
    True
    >>> [(w.center, w.half_extents) for w in PAPER_GEOMETRY.reach_walls]
    [((0.5, 0.15), (0.18, 0.01))]
    >>> PAPER_GEOMETRY.object_radius, PAPER_GEOMETRY.contact_distance
    (0.05, 0.07)
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

Point = tuple[float, float]


@dataclass(frozen=True)
class Rect:
    """An axis-aligned rectangle ``[low, high]`` in the plane (a wall or a region).

    Bounds are stored exactly as given (the workspace test compares against them); walls are
    usually written with :meth:`from_center`.
    """

    low: Point
    high: Point

    @classmethod
    def from_center(cls, center: Point, half_extents: Point) -> Rect:
        """The rectangle with this centre and these half-extents."""
        (cx, cy), (hx, hy) = center, half_extents
        return cls((cx - hx, cy - hy), (cx + hx, cy + hy))

    @property
    def center(self) -> Point:
        """Centre (rounded to 1e-12, so that walls read back as written)."""
        return (
            round((self.low[0] + self.high[0]) / 2, 12),
            round((self.low[1] + self.high[1]) / 2, 12),
        )

    @property
    def half_extents(self) -> Point:
        """Half-extents (rounded to 1e-12)."""
        return (
            round((self.high[0] - self.low[0]) / 2, 12),
            round((self.high[1] - self.low[1]) / 2, 12),
        )

    def contains(self, point: Sequence[float], margin: float = 0.0) -> bool:
        """Whether ``point`` lies in the rectangle grown by ``margin`` on every side.

        With ``margin`` equal to a disc's radius this is a conservative overlap test for a disc
        centred at ``point`` (exact except near the corners).
        """
        x, y = float(point[0]), float(point[1])
        return (
            self.low[0] - margin <= x <= self.high[0] + margin
            and self.low[1] - margin <= y <= self.high[1] + margin
        )

    def distance(self, point: Sequence[float]) -> float:
        """Euclidean distance from ``point`` to the rectangle (0 inside)."""
        x, y = float(point[0]), float(point[1])
        dx = max(self.low[0] - x, 0.0, x - self.high[0])
        dy = max(self.low[1] - y, 0.0, y - self.high[1])
        return float(np.hypot(dx, dy))

    def sample(self, rng: np.random.Generator) -> np.ndarray:
        """A point drawn uniformly from the rectangle."""
        return rng.uniform(self.low, self.high)


@dataclass(frozen=True)
class Disc:
    """A disc in the plane (push's cylinder seen from above), with the :meth:`Rect.distance`
    of a rectangle, so that either can be an obstacle."""

    center: Point
    radius: float

    def distance(self, point: Sequence[float]) -> float:
        """Euclidean distance from ``point`` to the disc (0 inside)."""
        gap = math.hypot(float(point[0]) - self.center[0], float(point[1]) - self.center[1])
        return max(gap - self.radius, 0.0)


@dataclass(frozen=True)
class PlanarGeometry:
    """Every coordinate of the reach, push and maze-reach tasks (metres).

    Attributes:
        workspace: where the end effector's centre may go; a move whose target leaves it is
            rejected (the end effector stays where it is), as in the paper's code.
        step_size: displacement per unit action along each axis (target = position +
            ``step_size`` · clip(action, −1, 1)).
        success_threshold: success is a task distance strictly below this.
        ee_radius: radius of the spherical end effector.
        ee_start: the end effector's start position in all three tasks.
        reach_goal: goal of the end effector in reach.
        box_half_size: half side of the square box in push (when ``object_radius`` is None).
        object_radius: radius of push's object when it is a cylinder (the paper's), or None for
            the square box of ``box_half_size``.
        box_start: the box's start position in push.
        box_goal: goal of the box in push.
        maze_goal: goal of the end effector in maze-reach.
        maze_walls: the three walls of maze-reach (bottom, left, right), a U open at the top.
        reach_walls: the walls of reach: none (v0), or the paper's wall between start and goal.
        reach_detour: the points beside reach's wall that the way to the goal passes (the
            paper's ``_subgoal2_pos``: either end of the wall); its dense reward and its
            ``single`` subgoal use them. Empty without a wall.
        maze_detour: the same for maze-reach: the points above the U's side walls (the paper's
            ``_subgoal2_pos`` of its maze task). Empty in v0, whose dense reward is the straight
            distance.
        goal_region: where ``randomize_goal`` draws reach and push goals (the goal bounds of the
            paper's released code).
        box_start_region: where ``randomize_start`` draws the box in push.
        maze_goal_region: where ``randomize_goal`` draws maze-reach goals (inside the U, clear of
            the walls by the end effector's radius).
        box_margin: how far beyond the workspace the box's coordinates may be observed (the end
            effector can push the box past the workspace edge by at most about its radius plus
            the box's half diagonal).
    """

    workspace: Rect = Rect((0.23, -0.35), (0.78, 0.30))
    step_size: float = 0.02
    success_threshold: float = 0.05
    ee_radius: float = 0.02
    ee_start: Point = (0.45, -0.32)
    reach_goal: Point = (0.50, 0.26)
    box_half_size: float = 0.03
    box_start: Point = (0.35, -0.10)
    box_goal: Point = (0.50, 0.20)
    maze_goal: Point = (0.50, 0.00)
    maze_walls: tuple[Rect, ...] = (
        Rect.from_center((0.50, -0.20), (0.10, 0.01)),
        Rect.from_center((0.40, -0.03), (0.01, 0.18)),
        Rect.from_center((0.60, -0.03), (0.01, 0.18)),
    )
    goal_region: Rect = Rect((0.30, 0.00), (0.65, 0.25))
    box_start_region: Rect = Rect((0.30, -0.20), (0.65, 0.05))
    maze_goal_region: Rect = Rect((0.44, -0.15), (0.56, 0.10))
    box_margin: float = 0.10
    object_radius: float | None = None
    reach_walls: tuple[Rect, ...] = ()
    reach_detour: tuple[Point, ...] = ()
    maze_detour: tuple[Point, ...] = ()

    @property
    def object_extent(self) -> float:
        """How far push's object reaches from its centre along a face normal: the cylinder's
        radius, or the box's half side."""
        return self.box_half_size if self.object_radius is None else self.object_radius

    @property
    def contact_distance(self) -> float:
        """Centre-to-centre distance of the end effector and push's object when they touch
        (along a face normal of the box; in every direction for the cylinder)."""
        return round(self.object_extent + self.ee_radius, 12)

    def in_workspace(self, point: Sequence[float]) -> bool:
        """Whether a target for the end effector's centre is inside the workspace."""
        return self.workspace.contains(point)

    @property
    def ee_start_region(self) -> Rect:
        """Where ``randomize_start`` draws the end effector: the workspace shrunk by its radius."""
        r = self.ee_radius
        (lx, ly), (hx, hy) = self.workspace.low, self.workspace.high
        return Rect((lx + r, ly + r), (hx - r, hy - r))

    @property
    def box_bounds(self) -> Rect:
        """Observation bounds of the box's centre: the workspace grown by ``box_margin``."""
        m = self.box_margin
        (lx, ly), (hx, hy) = self.workspace.low, self.workspace.high
        return Rect((lx - m, ly - m), (hx + m, hy + m))


GEOMETRY = PlanarGeometry()
"""The geometry of the ``-v0`` planar tasks (reach without its wall, push with a square box);
the default of every planar environment."""

PAPER_GEOMETRY = replace(
    GEOMETRY,
    object_radius=0.05,
    reach_walls=(Rect.from_center((0.50, 0.15), (0.18, 0.01)),),
    reach_detour=((0.23, 0.15), (0.76, 0.15)),
    maze_detour=((0.40, 0.23), (0.60, 0.23)),
)
"""The geometry of the ``-v1`` planar tasks, as the paper's ``main.py`` built them: reach with
the wall of ``envs/reaching_env/reaching_task.py`` (centre (0.5, 0.15), half-extents
(0.18, 0.01)), push with the cylinder of ``envs/pushing_env/pushing_task.py`` (radius 0.05),
and the detour points of both reaching tasks' dense rewards."""
