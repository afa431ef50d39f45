"""Abstract models of the ``-v1`` planar tasks: the source paper's subgoals around its
obstacles, and the grids of :mod:`planshape.tasks.planar.abstract` on the paper's geometry.

* reach and maze-reach, ``single``: one subgoal that holds at either of two points, the paper's
  ``_subgoal2_pos`` (reach: either end of the wall, (0.23, 0.15) or (0.76, 0.15); maze-reach:
  above either side wall, (0.40, 0.23) or (0.60, 0.23)); ``multi``: the paper's three,
  ``_subgoal1_pos``, ``_subgoal2_pos`` and ``_subgoal3_pos``, in that order, each a pair. A
  subgoal is a disc of the success radius (0.05 m, the paper's ``_dist_threshold``) around
  either point; the distance potentials measure to the first point of each pair, as the paper's
  distance potential does (``_subgoal*_pos[0]``).
* ``grid``: 0.05 m cells aligned on the goal, without the edges whose segment touches a wall
  (reach: the paper's wall; maze-reach: its three walls).
* push, ``single`` and ``multi``: the places of the v0 models, behind the cylinder at its contact
  distance (0.07 m); ``grid`` and ``grid-diagonal``: the Sokoban-like grids with cells of
  :data:`PUSH_CELL` (0.075 m), just wider than the contact distance, so that the end effector
  in the cell behind the object does not touch it until it pushes, and the paper's object start
  is a cell centre (it is 2 and 4 cells from the goal). In ``grid-diagonal`` the end effector
  moves between 8-adjacent cells, but not diagonally past the cylinder, and pushes it from its
  4 neighbours only, straight on (v0's box may also slide sideways along a pushed face).

Every model is built for one instance (start, goal and, in push, the object's start): the
registered factories build the paper's fixed instance; the randomized tasks build each of
their instances the same way.

Example:
    >>> model = reach_single()
    >>> table = model.geometry.places[0]
    >>> table.containing(0.76, 0.15) == table.containing(0.23, 0.15) == [1]  # "subgoal"
    True
    >>> target = model.geometry.locate(frozenset({("robot_at", "subgoal")}))["ee"]
    >>> [round(float(v), 2) for v in target]
    [0.23, 0.15]
"""

from __future__ import annotations

from planshape.shaping.registration import AbstractModel
from planshape.tasks.common import pddl_file
from planshape.tasks.planar.abstract import (
    EE_ENTITY,
    PUSH_ENTITIES,
    navigation_grid,
    planar_model,
    push_grid,
    push_places,
    waypoint_tables,
)
from planshape.tasks.planar.geometry import PAPER_GEOMETRY, Point

PG = PAPER_GEOMETRY

#: The paper's subgoal points (``_subgoal1_pos``, ``_subgoal2_pos``, ``_subgoal3_pos`` of
#: ``reaching_task.py`` and ``complex_reaching_task.py``): each subgoal holds at either point.
PAPER_SUBGOALS: dict[str, dict[str, tuple[Point, ...]]] = {
    "reach": {
        "subgoal1": ((0.36, 0.0), (0.64, 0.0)),
        "subgoal2": PG.reach_detour,
        "subgoal3": ((0.36, 0.26), (0.64, 0.26)),
    },
    "maze-reach": {
        "subgoal1": ((0.28, -0.08), (0.73, -0.08)),
        "subgoal2": PG.maze_detour,
        "subgoal3": ((0.45, 0.10), (0.55, 0.10)),
    },
}

#: PDDL place -> the paper's subgoal, per granularity of the reaching tasks
_SUBGOAL_PLACES = {
    "single": {"subgoal": "subgoal2"},
    "multi": {"subgoal1": "subgoal1", "subgoal2": "subgoal2", "subgoal3": "subgoal3"},
}

#: the walls each reaching task's grid avoids
_WALLS = {"reach": PG.reach_walls, "maze-reach": PG.maze_walls}

#: side of push's grid cells (m): the cylinder's contact distance is 0.07 m, and the paper's
#: object start (0.35, -0.10) is (2, 4) cells of 0.075 m from its goal (0.50, 0.20)
PUSH_CELL = 0.075

#: granularities of the v1 models, per task
GRANULARITIES = {
    "reach": ("single", "multi", "grid"),
    "maze-reach": ("single", "multi", "grid"),
    "push": ("single", "multi", "grid", "grid-diagonal"),
}


def reaching_model(task: str, granularity: str, start: Point, goal: Point) -> AbstractModel:
    """The ``granularity`` model of reach or maze-reach (v1) from ``start`` to ``goal``."""
    if granularity == "grid":
        return navigation_grid(task, start, goal, _WALLS[task], PG.ee_radius)
    subgoals = PAPER_SUBGOALS[task]
    names = _SUBGOAL_PLACES[granularity]
    centres = {"start": start, **{n: subgoals[k][0] for n, k in names.items()}, "goal": goal}
    alternatives = {n: subgoals[k][1:] for n, k in names.items()}
    problem = pddl_file(task, f"{granularity}-v1.pddl")
    return planar_model(task, problem, waypoint_tables(centres, alternatives), EE_ENTITY)


def push_model(granularity: str, ee_start: Point, box_start: Point, goal: Point) -> AbstractModel:
    """The ``granularity`` model of push (v1) for one start of the end effector and the object
    and one goal."""
    contact = PG.contact_distance
    if granularity in ("grid", "grid-diagonal"):
        return push_grid(
            PUSH_CELL,
            diagonal=granularity == "grid-diagonal",
            ee_start=ee_start,
            box_start=box_start,
            goal=goal,
            round_object=True,
        )
    places = push_places(ee_start, box_start, goal, contact)
    return planar_model(
        "push", pddl_file("push", f"{granularity}.pddl"), waypoint_tables(places), PUSH_ENTITIES
    )


# ---- the registered factories: the paper's fixed instance ------------------------------------


def reach_single() -> AbstractModel:
    return reaching_model("reach", "single", PG.ee_start, PG.reach_goal)


def reach_multi() -> AbstractModel:
    return reaching_model("reach", "multi", PG.ee_start, PG.reach_goal)


def reach_grid() -> AbstractModel:
    return reaching_model("reach", "grid", PG.ee_start, PG.reach_goal)


def maze_reach_single() -> AbstractModel:
    return reaching_model("maze-reach", "single", PG.ee_start, PG.maze_goal)


def maze_reach_multi() -> AbstractModel:
    return reaching_model("maze-reach", "multi", PG.ee_start, PG.maze_goal)


def maze_reach_grid() -> AbstractModel:
    return reaching_model("maze-reach", "grid", PG.ee_start, PG.maze_goal)


def push_single() -> AbstractModel:
    return push_model("single", PG.ee_start, PG.box_start, PG.box_goal)


def push_multi() -> AbstractModel:
    return push_model("multi", PG.ee_start, PG.box_start, PG.box_goal)


def push_grid_model() -> AbstractModel:
    return push_model("grid", PG.ee_start, PG.box_start, PG.box_goal)


def push_grid_diagonal() -> AbstractModel:
    return push_model("grid-diagonal", PG.ee_start, PG.box_start, PG.box_goal)
