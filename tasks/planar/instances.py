"""Task-instance distributions of the planar tasks: every episode is one *instance* — the end
effector's start, the goal and, in push, the object's start — drawn from a fixed, seeded
training set, and a learner is scored on a disjoint held-out evaluation set.

Each distribution is one that needs what its fixed task needs, so that the planner, not a
person, has to reshape the reward for every goal:

* reach: the start below the paper's wall, the goal behind it, and the straight way between
  them blocked by the wall;
* maze-reach: the goal inside the U, the start outside it, the straight way blocked by a wall;
* for both, the instance's grid model connects the start's cell to the goal's (a start cell
  whose centre touches a wall is redrawn);
* push: the goal anywhere in the goal region; the object a whole number of push-grid cells
  (:data:`~planshape.tasks.planar.paper_models.PUSH_CELL`) from it and at least two away, so
  that it must travel and the grid models' cells hold it; the end effector anywhere clear of
  it and in a grid cell.

The sets are drawn once, from fixed seeds (:data:`TRAIN_SEED`, :data:`EVAL_SEED`), and are the
same on every machine; their sizes are :data:`TRAIN_SIZE` and :data:`EVAL_SIZE`. Each
instance's PDDL problem is generated from the task's domain and planned by Fast Downward
through the plan cache, once per instance and model.

Example:
    >>> sets = instance_set("reach")
    >>> len(sets.train), len(sets.eval), sets.train[0] in sets.eval
    (100, 50, False)
    >>> wall = PAPER_GEOMETRY.reach_walls[0]
    >>> all(i.ee_start[1] < wall.low[1] < wall.high[1] < i.goal[1] for i in sets.eval)
    True
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from planshape.errors import UnknownIdError
from planshape.shaping.registration import AbstractModel
from planshape.tasks.planar.abstract import Grid
from planshape.tasks.planar.geometry import PAPER_GEOMETRY, Point, Rect
from planshape.tasks.planar.oracle import segment_clear
from planshape.tasks.planar.paper_models import PUSH_CELL, push_model, reaching_model

G = PAPER_GEOMETRY
TRAIN_SEED, EVAL_SEED = 0, 1
TRAIN_SIZE, EVAL_SIZE = 100, 50
#: coordinates are rounded to 0.1 mm, so that instances print and hash exactly
_DECIMALS = 4


@dataclass(frozen=True)
class Instance:
    """One instance of a planar task (metres). ``box_start`` is None for the reaching tasks."""

    ee_start: Point
    goal: Point
    box_start: Point | None = None


@dataclass(frozen=True)
class InstanceSet:
    """A task's training and held-out evaluation instances (disjoint)."""

    train: tuple[Instance, ...]
    eval: tuple[Instance, ...]

    def split(self, name: str) -> tuple[Instance, ...]:
        """``"train"`` or ``"eval"``."""
        if name not in ("train", "eval"):
            raise UnknownIdError("instance split", name, ("train", "eval"))
        return self.train if name == "train" else self.eval

    def sizes(self) -> dict[str, int]:
        return {"train": len(self.train), "eval": len(self.eval)}


def _point(rng: np.random.Generator, region: Rect) -> Point:
    x, y = region.sample(rng)
    return (round(float(x), _DECIMALS), round(float(y), _DECIMALS))


def _needs_detour(start: Point, goal: Point, walls: tuple[Rect, ...]) -> bool:
    return not segment_clear(start, goal, walls, G.ee_radius)


def _on_grid(grid: Grid, point: Point) -> bool:
    """Whether ``point`` lies in one of the grid's cells (a point near the workspace's edge may
    lie beyond the last cell centre by more than half a cell)."""
    rows, cols = grid.shape
    r, c = grid.cell_of(point)
    return 0 <= r < rows and 0 <= c < cols


def _grid_connects(start: Point, goal: Point, walls: tuple[Rect, ...]) -> bool:
    """Whether the grid model of the instance has a way from the start's cell to the goal's:
    the start cell's centre is clear of the walls and the free edges connect the two cells."""
    grid = Grid(goal)
    rows, cols = grid.shape
    first, last = grid.cell_of(start), grid.cell_of(goal)
    if not _on_grid(grid, start):
        return False
    if any(w.distance(grid.centre(first)) < G.ee_radius + 0.002 for w in walls):
        return False
    blocked = {frozenset(e) for e in grid.blocked_edges(G.ee_radius, walls)}
    seen, frontier = {first}, [first]
    while frontier:
        r, c = frontier.pop()
        for nxt in ((r + 1, c), (r - 1, c), (r, c + 1), (r, c - 1)):
            inside = 0 <= nxt[0] < rows and 0 <= nxt[1] < cols
            if inside and nxt not in seen and frozenset(((r, c), nxt)) not in blocked:
                seen.add(nxt)
                frontier.append(nxt)
    return last in seen


def _reach(rng: np.random.Generator) -> Instance:
    wall = G.reach_walls[0]
    clear = G.ee_radius + 0.01
    below = Rect((G.ee_start_region.low[0], G.ee_start_region.low[1]), (0.76, wall.low[1] - 0.08))
    behind = Rect((wall.low[0] + 0.02, wall.high[1] + clear), (wall.high[0] - 0.02, 0.28))
    while True:
        start, goal = _point(rng, below), _point(rng, behind)
        walls = G.reach_walls
        if _needs_detour(start, goal, walls) and _grid_connects(start, goal, walls):
            return Instance(start, goal)


def _maze_reach(rng: np.random.Generator) -> Instance:
    walls = G.maze_walls
    left, right = walls[1], walls[2]
    while True:
        start, goal = _point(rng, G.ee_start_region), _point(rng, G.maze_goal_region)
        inside_u = left.high[0] < start[0] < right.low[0] and start[1] > walls[0].high[1]
        clear = all(w.distance(start) > G.ee_radius + 0.01 for w in walls)
        needs_detour = clear and not inside_u and _needs_detour(start, goal, walls)
        if needs_detour and _grid_connects(start, goal, walls):
            return Instance(start, goal)


def _push(rng: np.random.Generator) -> Instance:
    contact = G.contact_distance
    ws = G.workspace
    margin = contact + 0.03  # room for the end effector behind the object at every edge
    room = Rect(
        (ws.low[0] + margin, ws.low[1] + margin), (ws.high[0] - margin, ws.high[1] - margin)
    )
    while True:
        goal = _point(rng, G.goal_region)
        cells = (int(rng.integers(-3, 4)), int(rng.integers(-5, 6)))
        if math.hypot(*cells) < 2:
            continue
        box = (
            round(goal[0] - cells[0] * PUSH_CELL, _DECIMALS),
            round(goal[1] - cells[1] * PUSH_CELL, _DECIMALS),
        )
        if not room.contains(box):
            continue
        ee = _point(rng, G.ee_start_region)
        if math.dist(ee, box) > contact + 0.03 and _on_grid(Grid(goal, PUSH_CELL), ee):
            return Instance(ee, goal, box)


_DRAW: dict[str, Callable[[np.random.Generator], Instance]] = {
    "reach": _reach,
    "maze-reach": _maze_reach,
    "push": _push,
}


def _draw(task: str, seed: int, size: int, exclude: frozenset[Instance] = frozenset()) -> tuple:
    rng = np.random.default_rng(seed)
    drawn: list[Instance] = []
    while len(drawn) < size:
        instance = _DRAW[task](rng)
        if instance not in exclude and instance not in drawn:
            drawn.append(instance)
    return tuple(drawn)


@functools.cache
def instance_set(task: str) -> InstanceSet:
    """The training and evaluation instances of a planar task (``"reach"``, ``"push"``,
    ``"maze-reach"``); the evaluation set never repeats a training instance."""
    if task not in _DRAW:
        raise UnknownIdError("planar task with instances", task, _DRAW)
    train = _draw(task, TRAIN_SEED, TRAIN_SIZE)
    return InstanceSet(train, _draw(task, EVAL_SEED, EVAL_SIZE, frozenset(train)))


def reach_instances() -> InstanceSet:
    return instance_set("reach")


def push_instances() -> InstanceSet:
    return instance_set("push")


def maze_reach_instances() -> InstanceSet:
    return instance_set("maze-reach")


# ---- the models of one instance (the registered factories of the randomized tasks) ---------


def reach_single(instance: Instance) -> AbstractModel:
    return reaching_model("reach", "single", instance.ee_start, instance.goal)


def reach_multi(instance: Instance) -> AbstractModel:
    return reaching_model("reach", "multi", instance.ee_start, instance.goal)


def reach_grid(instance: Instance) -> AbstractModel:
    return reaching_model("reach", "grid", instance.ee_start, instance.goal)


def maze_reach_single(instance: Instance) -> AbstractModel:
    return reaching_model("maze-reach", "single", instance.ee_start, instance.goal)


def maze_reach_multi(instance: Instance) -> AbstractModel:
    return reaching_model("maze-reach", "multi", instance.ee_start, instance.goal)


def maze_reach_grid(instance: Instance) -> AbstractModel:
    return reaching_model("maze-reach", "grid", instance.ee_start, instance.goal)


def _push_model(granularity: str, instance: Instance) -> AbstractModel:
    assert instance.box_start is not None, "a push instance places the object"
    return push_model(granularity, instance.ee_start, instance.box_start, instance.goal)


def push_single(instance: Instance) -> AbstractModel:
    return _push_model("single", instance)


def push_multi(instance: Instance) -> AbstractModel:
    return _push_model("multi", instance)


def push_grid(instance: Instance) -> AbstractModel:
    return _push_model("grid", instance)


def push_grid_diagonal(instance: Instance) -> AbstractModel:
    return _push_model("grid-diagonal", instance)
