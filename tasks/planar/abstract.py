"""Abstract models of reach, push and maze-reach: PDDL places, classifiers and coordinates.

Three granularities per task, following the source paper:

* ``single``: one intermediate subgoal (reach and maze-reach: a via point; push: the end
  effector behind the box, then one push to the goal);
* ``multi``: three waypoints (push: the end effector behind the box, then the box through two
  waypoints to the goal);
* ``grid``: the workspace cut into square cells of :data:`CELL` metres aligned on the goal, with
  ``neighbors`` between 4-adjacent cells; in maze-reach, a move whose straight segment would
  touch a wall (grown by the end effector's radius) is not a neighbour, so the plan goes around.
  Push's grid model is Sokoban-like: the end effector pushes the box one cell from the cell
  opposite, and ends in the cell the box left.
* ``grid-diagonal`` (push only): the same cells, with ``neighbors`` between 8-adjacent cells
  and pushes that may also slide the box one cell sideways, as the box follows the end
  effector along the pushed face by friction (about 85 % of its sideways motion); the end
  effector ends behind the box's new cell. The plan pushes the box 6 times, diagonally
  towards the goal, instead of 9 times with a walk around the box.

Predicates are ``(robot_at ?p)`` — the end effector's centre is in place ``p`` — and, in push,
``(object_at ?b ?p)`` — the box's centre is in place ``p``. Waypoints are discs (radius
:data:`PLACE_RADIUS`, the success radius, except the places behind the box); grid cells are the
squares that tile the workspace. The shipped problems name the places; :data:`PLACES` gives
their coordinates.

Example:
    >>> model = reach_multi()
    >>> sorted(model.classifiers)
    ['robot_at']
    >>> targets = model.geometry.locate(frozenset({("robot_at", "w2")}))
    >>> [round(float(v), 3) for v in targets["ee"]]
    [0.475, -0.03]
"""

from __future__ import annotations

import math
from collections.abc import Callable, Hashable, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from planshape.planning.grid import GridNames, cell_name, grid_pddl
from planshape.planning.model import AbstractState
from planshape.shaping.abstraction import Vectorized
from planshape.shaping.registration import AbstractModel
from planshape.tasks.common import generated_file, pddl_file
from planshape.tasks.planar.geometry import GEOMETRY, Point, Rect
from planshape.tasks.regions import Lattice, MembershipCells, RegionIndex

#: side of a grid cell (m): 2.5 steps of the end effector, and the box's contact distance.
CELL = 0.05
#: radius of a waypoint place: the success radius, so reaching the goal place is success.
PLACE_RADIUS = GEOMETRY.success_threshold
#: radius of the places where the end effector waits behind the box before a push.
BEHIND_RADIUS = 0.03
#: distance between the box's centre and the end effector's centre when they touch
CONTACT = GEOMETRY.box_half_size + GEOMETRY.ee_radius


@dataclass(frozen=True)
class Places:
    """Named regions of the plane: discs of one radius, or squares of one half side.

    ``grid=True`` makes the squares (of side ``2 · size``) the cells of a grid that tiles the
    plane: every point is in exactly one cell (see :class:`planshape.tasks.regions.Lattice`).
    ``alternatives`` gives a place more discs than its centre: the place holds in any of them
    (the paper's reaching subgoals are "either end of the wall"); its centre, the first disc,
    is where the distance potentials measure to, as the paper's distance potential does.

    Example:
        >>> places = Places({"a": (0.0, 0.0), "b": (1.0, 0.0)}, size=0.1)
        >>> places.contains(np.array([[0.05, 0.0], [0.5, 0.0]]), places.index(["a", "b"])).tolist()
        [[True, False], [False, False]]
        >>> cells = Places({"a": (0.0, 0.0), "b": (0.1, 0.0)}, 0.05, square=True, grid=True)
        >>> cells.contains(np.array([[0.05, 0.0], [0.15, 0.0]]), cells.index(["a", "b"])).tolist()
        [[True, False], [False, True]]
        >>> ends = Places({"end": (0.0, 0.0)}, 0.1, alternatives={"end": ((1.0, 0.0),)})
        >>> ends.containing(1.05, 0.0), ends.contains(np.array([1.05, 0.0]), ends.index(["end"]))
        ([0], array([ True]))
    """

    centres: Mapping[str, Point]
    size: float
    square: bool = False
    grid: bool = False
    alternatives: Mapping[str, tuple[Point, ...]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if self.grid and not self.square:
            raise ValueError("grid places are square cells; pass square=True")
        if self.grid and self.alternatives:
            raise ValueError("grid cells tile the plane; they have no alternative discs")
        names = tuple(self.centres)
        object.__setattr__(self, "_names", {n: i for i, n in enumerate(names)})
        object.__setattr__(self, "_xy", np.array([self.centres[n] for n in names], float))
        # every region of the table: each place's centre, then the alternatives, with the
        # position of the place each one belongs to
        owners = list(range(len(names)))
        extra = [(self._names[n], p) for n, ps in self.alternatives.items() for p in ps]  # type: ignore[attr-defined]
        owners += [i for i, _ in extra]
        object.__setattr__(self, "_owners", owners)
        object.__setattr__(self, "_alt_xy", np.array([p for _, p in extra], float).reshape(-1, 2))
        object.__setattr__(self, "_alt_owner", np.array([i for i, _ in extra], np.intp))
        xy = self._xy.tolist() + [list(p) for _, p in extra]  # type: ignore[attr-defined]
        finder = (
            Lattice(xy, 2 * self.size) if self.grid else RegionIndex(xy, self.size, self.square)
        )
        object.__setattr__(self, "_finder", finder)

    def index(self, names: Sequence[str]) -> np.ndarray:
        lookup: dict[str, int] = self._names  # type: ignore[attr-defined]
        return np.array([lookup[n] for n in names], dtype=np.intp)

    def centre(self, name: str) -> np.ndarray:
        return self._xy[self._names[name]]  # type: ignore[attr-defined]

    def contains(self, points: np.ndarray, index: np.ndarray) -> np.ndarray:
        """``points`` (..., 2) against places ``index``: shape (..., len(index))."""
        inside = self.contains_centres(points, self._xy[index])  # type: ignore[attr-defined]
        if len(self._alt_owner):  # type: ignore[attr-defined]
            belongs = self._alt_owner[:, None] == np.asarray(index)[None, :]  # type: ignore[attr-defined]
            in_alt = self.contains_centres(points, self._alt_xy)  # type: ignore[attr-defined]
            inside = inside | ((in_alt.astype(np.intp) @ belongs) > 0)
        return inside

    def containing(self, x: float, y: float) -> list[int]:
        """Positions (in ``centres``' order) of the places that contain the point ``(x, y)``:
        the one-observation form of :meth:`contains`."""
        regions = self._finder.containing(x, y)  # type: ignore[attr-defined]
        if not self.alternatives:
            return regions
        owners: list[int] = self._owners  # type: ignore[attr-defined]
        return sorted({owners[r] for r in regions})

    @property
    def region_index(self) -> RegionIndex:
        """A region table's index of every region (each place's disc or square, then the
        alternatives), of which :meth:`containing` is a function."""
        if self.grid:
            raise ValueError("grid places are found by rounding, not in a region index")
        return self._finder  # type: ignore[attr-defined]

    @property
    def cell(self) -> Callable[[float, float], tuple[int, int]]:
        """A grid table's ``cell(x, y)``: the lattice index of the cell containing the point,
        of which :meth:`containing` is a function (the lattice's own method, so that a
        shaping step pays one call)."""
        if not self.grid:
            raise ValueError("only grid places have cells")
        return self._finder.cell  # type: ignore[attr-defined]

    def contains_centres(self, points: np.ndarray, centres: np.ndarray) -> np.ndarray:
        """``points`` (..., 2) against regions of this table centred at ``centres`` (k, 2)."""
        if self.grid:
            return self._finder.contains(points, centres)  # type: ignore[attr-defined]
        offset = points[..., None, :] - centres
        if self.square:
            return np.abs(offset).max(axis=-1) < self.size
        return np.einsum("...i,...i->...", offset, offset) < self.size**2


#: a route: the groundings list it was built for, (table, columns, places) per place table,
#: whether one table answers every grounding in order, per table the grounding positions of
#: each of its places, and (for the one-observation path, when no table is a grid) one
#: RegionIndex over every region the groundings name with each region's grounding positions
#: and whether a place has several regions (positions may then repeat)
Route = tuple[
    object,
    list[tuple["Places", np.ndarray, np.ndarray]],
    bool,
    list[dict[int, list[int]]],
    "tuple[RegionIndex, list[tuple[int, ...]], bool] | None",
]


class InPlace:
    """Vectorized classifier: the entity at ``obs[position]`` is in the place named by argument
    ``place_arg`` of each grounding (``robot_at ?p`` -> 0, ``object_at ?b ?p`` -> 1)."""

    #: the waypoint models' key remembers the regions per square cell of this fraction of the
    #: smallest region's radius (or half side)
    MEMBERSHIP_CELL_FRACTION = 1 / 8

    def __init__(self, places: Sequence[Places], position: slice, place_arg: int):
        self.places = places
        self.position = position
        self.place_arg = place_arg
        # routes per list of groundings: each evaluator (progress tracking, full abstract
        # states) passes its own fixed list, so one route is built per list, once
        self._routes: dict[int, Route] = {}
        self._membership: MembershipCells | None = None

    def _route(self, groundings: Sequence[tuple[str, ...]]) -> Route:
        """Which place table answers which grounding, and whether one table answers all."""
        plan = []
        names = [g[self.place_arg] for g in groundings]
        for table in self.places:
            columns = [i for i, n in enumerate(names) if n in table.centres]
            if columns:
                plan.append((table, np.array(columns), table.index([names[i] for i in columns])))
        whole = len(plan) == 1 and len(plan[0][1]) == len(names)
        positions: list[dict[int, list[int]]] = []
        for table in self.places:
            where: dict[int, list[int]] = {}
            for column, name in enumerate(names):
                if name in table.centres:
                    where.setdefault(int(table.index([name])[0]), []).append(column)
            positions.append(where)
        return groundings, plan, whole, positions, self._merged(positions)

    def _merged(
        self, positions: list[dict[int, list[int]]]
    ) -> tuple[RegionIndex, list[tuple[int, ...]], bool] | None:
        """Every region of every table that a grounding names (centres and alternatives), in
        one :class:`planshape.tasks.regions.RegionIndex`, with the grounding positions of
        each: one bucket lookup per observation instead of one per table. None when a table is
        a grid (a grid cell is found by rounding, :class:`planshape.tasks.regions.Lattice`)."""
        if any(table.grid for table in self.places):
            return None
        centres, sizes, squares, owners = [], [], [], []
        for table, where in zip(self.places, positions, strict=True):
            names: dict[str, int] = table._names  # type: ignore[attr-defined]
            regions = [(names[n], p) for n, p in table.centres.items()]
            regions += [(names[n], p) for n, ps in table.alternatives.items() for p in ps]
            for place, centre in regions:
                if where.get(place):  # a place no grounding names holds nothing here
                    centres.append(centre)
                    sizes.append(table.size)
                    squares.append(table.square)
                    owners.append(tuple(where[place]))
        repeats = any(table.alternatives for table in self.places)
        return RegionIndex(centres, sizes, squares), owners, repeats

    def _route_for(self, groundings: Sequence[tuple[str, ...]]) -> Route:
        route = self._routes.get(id(groundings))
        if route is None or route[0] is not groundings:
            route = self._routes[id(groundings)] = self._route(groundings)
        return route

    def _point_key(self) -> Callable[[float, float], Hashable] | None:
        """What holds is a function of this (:class:`planshape.shaping.abstraction.Vectorized`'s
        ``key``): the grid cell of the entity, when the only place table is a grid; the regions
        of every table that contain it, remembered per small cell where no region's rim
        crosses it (:class:`planshape.tasks.regions.MembershipCells`), when no table is a grid;
        else None."""
        if len(self.places) == 1 and self.places[0].grid:
            return self.places[0].cell
        if any(table.grid for table in self.places):
            return None
        if self._membership is None:
            index = RegionIndex.union([table.region_index for table in self.places])
            smallest = min(table.size for table in self.places)
            self._membership = MembershipCells(index, smallest * self.MEMBERSHIP_CELL_FRACTION)
        return self._membership.containing

    @property
    def key(self):
        """The key of one observation (see :meth:`_point_key`), or None."""
        point_key = self._point_key()
        if point_key is None:
            return None
        position = self.position
        return lambda obs: point_key(*obs[position].tolist())

    @property
    def key_of_values(self):
        """:attr:`key` from a flat observation's ``tolist()`` (the same floats, so the same
        key), or None where there is no key."""
        point_key = self._point_key()
        if point_key is None:
            return None
        position = self.position
        x = position.start or 0
        if position.step in (None, 1) and position.stop == x + 2 and x >= 0:  # (x, y) at x, x+1
            return lambda values: point_key(values[x], values[x + 1])
        return lambda values: point_key(*values[position])

    def holding(self, obs: np.ndarray, groundings: Sequence[tuple[str, ...]]) -> list[int]:
        """The positions in ``groundings`` that hold in one observation (see
        :class:`planshape.shaping.abstraction.Vectorized`)."""
        x, y = obs[self.position].tolist()
        route = self._route_for(groundings)
        if route[4] is not None:  # discs and squares only: one lookup for every table
            index, owners, repeats = route[4]
            found = [column for region in index.containing(x, y) for column in owners[region]]
            return list(dict.fromkeys(found)) if repeats else found
        found = []
        for table, where in zip(self.places, route[3], strict=True):
            for place in table.containing(x, y):
                found.extend(where.get(place, ()))
        return found

    def __call__(self, obs: np.ndarray, groundings: Sequence[tuple[str, ...]]) -> np.ndarray:
        _, plan, whole, _, _ = self._route_for(groundings)
        points = obs[..., self.position]
        if whole:  # one table answers every grounding, in order
            table, _, index = plan[0]
            return table.contains(points, index)
        out = np.zeros((*points.shape[:-1], len(groundings)), dtype=bool)
        for table, columns, index in plan:
            out[..., columns] = table.contains(points, index)
        return out


class PlanarGeometryHooks:
    """``locate``/``positions`` for the distance potentials: the end effector first, then the
    box (the source paper's priority); both are positions in the table's frame."""

    #: the entities are positions in one frame, so |ee − box| means something
    shared_frame = True

    def __init__(self, places: Sequence[Places], entities: Mapping[str, tuple[str, int, slice]]):
        self.places = places
        #: entity -> (predicate that places it, argument index of the place, obs slice)
        self.entities = dict(entities)
        self._located: dict[AbstractState, dict[str, np.ndarray]] = {}
        self._read = _position_reader([(e, s) for e, (_, _, s) in self.entities.items()])

    def _centre(self, name: str) -> np.ndarray:
        for table in self.places:
            if name in table.centres:
                return table.centre(name)
        raise KeyError(f"place {name!r} has no coordinates")

    def locate(self, subgoal: AbstractState) -> Mapping[str, np.ndarray]:
        if subgoal not in self._located:
            targets = {}
            for entity, (predicate, arg, _) in self.entities.items():
                for atom in subgoal:
                    if atom[0] == predicate:
                        targets[entity] = self._centre(atom[1 + arg])
            self._located[subgoal] = targets
        return self._located[subgoal]

    def positions(self, obs: np.ndarray) -> Mapping[str, list[float]]:
        """Each entity's coordinates in one observation, as plain floats (the distance
        potentials measure them with ``math``, several times faster than on numpy 2-vectors)."""
        return self._read(obs.tolist() if type(obs) is np.ndarray else np.asarray(obs).tolist())

    def positions_of_values(self, values: list[float]) -> Mapping[str, list[float]]:
        """:meth:`positions` from a flat observation's ``tolist()`` (the same floats)."""
        return self._read(values)


def _position_reader(
    slices: Sequence[tuple[str, slice]],
) -> Callable[[list[float]], dict[str, list[float]]]:
    """values -> {entity: its coordinates}, in ``slices``' order. For the planar tasks' one or
    two entities a dict display, half the time of a comprehension (0.10 against 0.21 µs with
    one entity on Python 3.11), which every shaped step of a distance potential pays.

    Example:
        >>> _position_reader([("ee", slice(0, 2)), ("box", slice(2, 4))])([1.0, 2.0, 3.0, 4.0])
        {'ee': [1.0, 2.0], 'box': [3.0, 4.0]}
    """
    if len(slices) == 1:
        ((a, in_a),) = slices
        return lambda values: {a: values[in_a]}
    if len(slices) == 2:
        (a, in_a), (b, in_b) = slices
        return lambda values: {a: values[in_a], b: values[in_b]}
    return lambda values: {entity: values[s] for entity, s in slices}


EE = slice(0, 2)
BOX = slice(2, 4)
EE_ENTITY = {"ee": ("robot_at", 0, EE)}
PUSH_ENTITIES = {"ee": ("robot_at", 0, EE), "box": ("object_at", 1, BOX)}


def _along(a: Point, b: Point, fraction: float) -> Point:
    return (a[0] + fraction * (b[0] - a[0]), a[1] + fraction * (b[1] - a[1]))


def _behind(box: Point, goal: Point, contact: float = CONTACT) -> Point:
    """Where the end effector touches the box from the side opposite to ``goal``."""
    dx, dy = goal[0] - box[0], goal[1] - box[1]
    norm = math.hypot(dx, dy)
    return (box[0] - contact * dx / norm, box[1] - contact * dy / norm)


def push_places(ee_start: Point, box_start: Point, goal: Point, contact: float) -> dict[str, Point]:
    """The places of push's single and multi problems for one start and goal: the end
    effector's start, the box's start, the goal, two waypoints of the box between them, and
    behind each of these, where the end effector touches the box before pushing it on."""
    beyond = (2 * goal[0] - box_start[0], 2 * goal[1] - box_start[1])
    waypoints = {f"w{k}": _along(box_start, goal, k / 3) for k in (1, 2)}
    return {
        "start": ee_start,
        "box_start": box_start,
        "behind_box": _behind(box_start, goal, contact),
        **waypoints,
        **{f"behind_{n}": _behind(w, goal, contact) for n, w in waypoints.items()},
        "goal": goal,
        "behind_goal": _behind(goal, beyond, contact),
    }


G = GEOMETRY
#: coordinates of every named place of the shipped single and multi problems, per task.
PLACES: dict[str, dict[str, Point]] = {
    "reach": {
        "start": G.ee_start,
        "via": _along(G.ee_start, G.reach_goal, 0.5),
        **{f"w{k}": _along(G.ee_start, G.reach_goal, k / 4) for k in (1, 2, 3)},
        "goal": G.reach_goal,
    },
    "maze-reach": {
        "start": G.ee_start,
        "via": (0.30, 0.22),
        "w1": (0.30, -0.30),
        "w2": (0.30, 0.22),
        "w3": (0.50, 0.22),
        "goal": G.maze_goal,
    },
    "push": push_places(G.ee_start, G.box_start, G.box_goal, CONTACT),
}


def waypoint_tables(
    places: Mapping[str, Point], alternatives: Mapping[str, tuple[Point, ...]] | None = None
) -> list[Places]:
    """The place tables of a single or multi model: the waypoints as discs of the success
    radius, and the places behind the box as smaller discs."""
    behind = {n: p for n, p in places.items() if n.startswith("behind")}
    waypoints = {n: p for n, p in places.items() if n not in behind}
    tables = [Places(waypoints, PLACE_RADIUS, alternatives=dict(alternatives or {}))]
    if behind:
        tables.append(Places(behind, BEHIND_RADIUS))
    return tables


def _waypoint_places(task: str) -> list[Places]:
    return waypoint_tables(PLACES[task])


def planar_model(
    domain: str, problem_path, places: list[Places], entities, domain_file: str = "domain.pddl"
) -> AbstractModel:
    """The abstract model of a planar task: ``domain``'s shipped domain file, a problem file,
    one :class:`InPlace` classifier per entity predicate over ``places``, and the geometry
    hooks."""
    classifiers = {
        predicate: Vectorized(
            in_place,
            holding=in_place.holding,
            key=in_place.key,
            key_of_values=in_place.key_of_values,
        )
        for predicate, arg, position in entities.values()
        for in_place in [InPlace(places, position, arg)]
    }
    return AbstractModel(
        domain=pddl_file(domain, domain_file),
        problem=problem_path,
        classifiers=classifiers,
        geometry=PlanarGeometryHooks(places, entities),
    )


def _waypoint_model(task: str, granularity: str) -> AbstractModel:
    entities = PUSH_ENTITIES if task == "push" else EE_ENTITY
    return planar_model(
        task, pddl_file(task, f"{granularity}.pddl"), _waypoint_places(task), entities
    )


def reach_single() -> AbstractModel:
    return _waypoint_model("reach", "single")


def reach_multi() -> AbstractModel:
    return _waypoint_model("reach", "multi")


def maze_reach_single() -> AbstractModel:
    return _waypoint_model("maze-reach", "single")


def maze_reach_multi() -> AbstractModel:
    return _waypoint_model("maze-reach", "multi")


def push_single() -> AbstractModel:
    return _waypoint_model("push", "single")


def push_multi() -> AbstractModel:
    return _waypoint_model("push", "multi")


# ---- grids ------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Grid:
    """Square cells of side ``cell`` whose centres lie in the workspace, aligned so that
    ``anchor`` (the goal) is a cell centre. Row 0 is the top row; columns grow with x."""

    anchor: Point
    cell: float = CELL

    @property
    def shape(self) -> tuple[int, int]:
        (_lx, ly), (hx, _hy) = G.workspace.low, G.workspace.high
        self_cols = math.floor((hx - self.x0) / self.cell + 1e-9) + 1
        self_rows = math.floor((self.y_top - ly) / self.cell + 1e-9) + 1
        return self_rows, self_cols

    @property
    def x0(self) -> float:
        lx = G.workspace.low[0]
        return self.anchor[0] - math.floor((self.anchor[0] - lx) / self.cell + 1e-9) * self.cell

    @property
    def y_top(self) -> float:
        hy = G.workspace.high[1]
        return self.anchor[1] + math.floor((hy - self.anchor[1]) / self.cell + 1e-9) * self.cell

    def centre(self, rc: tuple[int, int]) -> Point:
        # rounded to a nanometre, so that a cell one step from the goal is exactly one cell
        # away and not 0.0499999 m (which the strict success test would count as reached)
        return (
            round(self.x0 + rc[1] * self.cell, 9),
            round(self.y_top - rc[0] * self.cell, 9),
        )

    def cell_of(self, point: Point) -> tuple[int, int]:
        return (
            round((self.y_top - point[1]) / self.cell),
            round((point[0] - self.x0) / self.cell),
        )

    def places(self, names: GridNames) -> Places:
        rows, cols = self.shape
        centres = {
            cell_name((r, c), names): self.centre((r, c)) for r in range(rows) for c in range(cols)
        }
        return Places(centres, self.cell / 2, square=True, grid=True)

    def blocked_edges(
        self, margin: float, walls: Sequence[Rect] = G.maze_walls
    ) -> list[tuple[tuple[int, int], tuple[int, int]]]:
        """Pairs of adjacent cells whose connecting segment touches a wall (maze-reach's by
        default)."""
        rows, cols = self.shape
        blocked = []
        for r in range(rows):
            for c in range(cols):
                for other in ((r + 1, c), (r, c + 1)):
                    if other[0] >= rows or other[1] >= cols:
                        continue
                    a, b = self.centre((r, c)), self.centre(other)
                    points = [_along(a, b, k / 10) for k in range(11)]
                    if any(w.contains(p, margin) for w in walls for p in points):
                        blocked.append(((r, c), other))
        return blocked


def _grid_names(task: str) -> GridNames:
    return GridNames(domain=task, problem=f"{task}-grid", cell_type="place")


def navigation_grid(
    task: str, start: Point, goal: Point, walls: Sequence[Rect], ee_radius: float = G.ee_radius
) -> AbstractModel:
    """The grid model of reach or maze-reach from ``start`` to ``goal``: cells of
    :data:`CELL` aligned on the goal, without the edges whose segment touches a wall."""
    grid, names = Grid(goal), _grid_names(task)
    rows, cols = grid.shape
    pddl = grid_pddl(
        rows,
        cols,
        start=grid.cell_of(start),
        goal=grid.cell_of(goal),
        blocked_edges=grid.blocked_edges(ee_radius, walls) if walls else (),
        names=names,
    )
    problem = generated_file(f"{task}-grid", pddl.problem)
    return planar_model(task, problem, [grid.places(names)], EE_ENTITY)


def reach_grid() -> AbstractModel:
    return navigation_grid("reach", G.ee_start, G.reach_goal, walls=())


def maze_reach_grid() -> AbstractModel:
    return navigation_grid("maze-reach", G.ee_start, G.maze_goal, walls=G.maze_walls)


#: a push along ``d`` may slide the box one cell sideways: the box follows the end effector
#: along the face it pushes, by friction (about 85 % of the end effector's sideways motion)
_SLIDES = {False: (0,), True: (0, -1, 1)}


def push_grid_problem(
    grid: Grid,
    ee_start: Point,
    box_start: Point,
    *,
    diagonal: bool = False,
    goal: Point = G.box_goal,
    round_object: bool = False,
) -> str:
    """The Sokoban-like push problem on ``grid`` (generated, not shipped).

    With ``diagonal``, the end effector also moves between 8-adjacent cells, and a push from
    the cell opposite the box may also slide the box one cell sideways (the end effector
    moves diagonally and the box follows it along the pushed face by friction); the end
    effector ends behind the box's new cell either way. A ``round_object`` (the paper's
    cylinder) is pushed along the line of centres, so it is never slid; it is pushed from its 4
    neighbours only (from a diagonal neighbour, 1.41 cells away, the push would start late and
    leave it 0.4 cells short of the next cell's centre); and since the end effector's diagonal
    move past it would touch it, such a move is a ``(diagonal from to side1 side2)`` fact of
    ``domain-v1.pddl``, free only when the object is in neither side cell.
    """
    names = _grid_names("push")
    rows, cols = grid.shape
    inside = {(r, c) for r in range(rows) for c in range(cols)}
    name = {rc: cell_name(rc, names) for rc in inside}
    facts = [
        f"(robot_at {name[grid.cell_of(ee_start)]})",
        f"(object_at box {name[grid.cell_of(box_start)]})",
    ]
    steps = ((-1, 0), (1, 0), (0, -1), (0, 1))
    moves = steps + (((-1, -1), (-1, 1), (1, -1), (1, 1)) if diagonal else ())
    slides = (0,) if round_object else _SLIDES[diagonal]
    for r, c in sorted(inside):
        for dr, dc in moves:
            ahead = (r + dr, c + dc)
            sides = ((r + dr, c), (r, c + dc))
            if round_object and (dr, dc) not in steps:
                # a diagonal move passes the two cells beside it (domain-v1.pddl)
                if ahead in inside and all(side in inside for side in sides):
                    a, b = (name[side] for side in sides)
                    facts.append(f"(diagonal {name[(r, c)]} {name[ahead]} {a} {b})")
            elif ahead in inside:
                facts.append(f"(neighbors {name[(r, c)]} {name[ahead]})")
            if (dr, dc) not in steps:
                continue  # pushed from a face (or, a cylinder, from a 4-neighbour), not a corner
            for slide in slides:
                # sideways is perpendicular to the push direction (dr, dc)
                sr, sc = slide * dc, slide * dr
                further = (ahead[0] + dr + sr, ahead[1] + dc + sc)
                after = (ahead[0] + sr, ahead[1] + sc)
                if ahead in inside and further in inside and after in inside:
                    # end effector in (r, c) pushes the box from `ahead` to `further`
                    facts.append(
                        f"(push_line {name[(r, c)]} {name[ahead]} {name[further]} {name[after]})"
                    )
    objects = " ".join(name[rc] for rc in sorted(inside))
    init = "\n         ".join(facts)
    return f"""(define (problem push-grid)
  (:domain push)
  (:objects {objects} - place
            box - box)
  (:init {init})
  (:goal (object_at box {name[grid.cell_of(goal)]})))
"""


def push_grid(
    cell: float = CELL,
    *,
    diagonal: bool = False,
    ee_start: Point = G.ee_start,
    box_start: Point = G.box_start,
    goal: Point = G.box_goal,
    round_object: bool = False,
) -> AbstractModel:
    """Push's Sokoban-like grid model on cells of side ``cell`` (the registered v0 model uses
    :data:`CELL`, v1 0.075 m; the invariance checker's toy uses coarser cells); ``diagonal``
    adds 8-adjacent moves and pushes that slide the box sideways, or for a ``round_object``
    diagonal pushes (see :func:`push_grid_problem`)."""
    grid = Grid(goal, cell)
    stem = f"push-grid{'-diagonal' if diagonal else ''}-{cell:g}"
    problem = generated_file(
        stem,
        push_grid_problem(
            grid, ee_start, box_start, diagonal=diagonal, goal=goal, round_object=round_object
        ),
    )
    domain = "domain-v1.pddl" if round_object and diagonal else "domain.pddl"
    places = [grid.places(_grid_names("push"))]
    return planar_model("push", problem, places, PUSH_ENTITIES, domain_file=domain)


def push_grid_diagonal() -> AbstractModel:
    """Push's grid model with diagonal moves and sliding pushes (``model="grid-diagonal"``)."""
    return push_grid(CELL, diagonal=True)
