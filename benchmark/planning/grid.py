"""Grid navigation PDDL generated from code (mazes, grid models of reaching tasks).

The domain has one type of object, cells named ``cell_<row>_<col>``; the fluent predicate
``(robot_at ?c - cell)``; the static predicate ``(neighbors ?a ?b - cell)``, true for 4-connected
cells in both directions unless a wall blocks the edge or either cell is blocked; and one action::

    (:action move :parameters (?from ?to - cell)
     :precondition (and (robot_at ?from) (neighbors ?from ?to) (not (= ?from ?to)))
     :effect (and (robot_at ?to) (not (robot_at ?from))))

Every name (domain, problem, type, cell prefix, predicates, action) can be changed with
:class:`GridNames`. Blocked cells stay declared as objects (so ``cell_i_j`` exists for every
``i, j``) but have no neighbours. Rows grow downwards, columns to the right.

Example:
    >>> grid = grid_pddl(3, 3, start=(0, 0), goal=(2, 2), blocked_cells={(1, 1)})
    >>> "(neighbors cell_0_1 cell_1_1)" in grid.problem
    False
    >>> "(:goal (robot_at cell_2_2))" in grid.problem
    True
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from planshape.errors import BadInputError

__all__ = ["Cell", "GridNames", "GridPddl", "cell_name", "grid_domain", "grid_edges", "grid_pddl"]

#: (row, column), both from 0.
Cell = tuple[int, int]


@dataclass(frozen=True)
class GridNames:
    """The names the generated PDDL uses; change them to fit a task's vocabulary."""

    domain: str = "grid"
    problem: str = "grid-problem"
    cell_type: str = "cell"
    #: objects are ``f"{cell_prefix}_{row}_{col}"``
    cell_prefix: str = "cell"
    at: str = "robot_at"
    neighbors: str = "neighbors"
    move: str = "move"


@dataclass(frozen=True)
class GridPddl:
    """A generated domain and problem, as text."""

    domain: str
    problem: str

    @property
    def texts(self) -> tuple[str, str]:
        return self.domain, self.problem

    def write(self, directory: str | Path, stem: str = "grid") -> tuple[Path, Path]:
        """Write ``<stem>-domain.pddl`` and ``<stem>-problem.pddl``; return their paths."""
        directory = Path(directory)
        directory.mkdir(parents=True, exist_ok=True)
        domain, problem = directory / f"{stem}-domain.pddl", directory / f"{stem}-problem.pddl"
        domain.write_text(self.domain, encoding="utf-8")
        problem.write_text(self.problem, encoding="utf-8")
        return domain, problem


def cell_name(cell: Cell, names: GridNames = GridNames()) -> str:
    """The object name of a cell.

    Example:
        >>> cell_name((2, 3))
        'cell_2_3'
    """
    return f"{names.cell_prefix}_{cell[0]}_{cell[1]}"


def grid_domain(names: GridNames = GridNames()) -> str:
    """The grid domain's PDDL text (it does not depend on the grid's size)."""
    n = names
    return f"""(define (domain {n.domain})
  (:requirements :strips :typing :negative-preconditions :equality)
  (:types {n.cell_type})
  (:predicates
    ({n.at} ?c - {n.cell_type})
    ({n.neighbors} ?a ?b - {n.cell_type}))
  (:action {n.move}
    :parameters (?from ?to - {n.cell_type})
    :precondition (and ({n.at} ?from) ({n.neighbors} ?from ?to) (not (= ?from ?to)))
    :effect (and ({n.at} ?to) (not ({n.at} ?from)))))
"""


def grid_edges(
    rows: int,
    cols: int,
    *,
    blocked_cells: Iterable[Cell] = (),
    blocked_edges: Iterable[tuple[Cell, Cell]] = (),
) -> list[tuple[Cell, Cell]]:
    """The directed pairs of 4-connected free cells, both directions, in row-major order.

    ``blocked_edges`` are unordered pairs of adjacent cells (a wall between them).

    Example:
        >>> grid_edges(1, 3, blocked_edges=[((0, 2), (0, 1))])
        [((0, 0), (0, 1)), ((0, 1), (0, 0))]
    """
    _check_size(rows, cols)
    blocked = {_checked(c, rows, cols, "blocked cell") for c in blocked_cells}
    walls = set()
    for a, b in blocked_edges:
        a, b = _checked(a, rows, cols, "wall end"), _checked(b, rows, cols, "wall end")
        if abs(a[0] - b[0]) + abs(a[1] - b[1]) != 1:
            raise BadInputError(f"wall {a}-{b}: the cells are not 4-neighbours")
        walls.add(frozenset((a, b)))
    edges = []
    for r in range(rows):
        for c in range(cols):
            for dr, dc in ((-1, 0), (0, -1), (0, 1), (1, 0)):
                other = (r + dr, c + dc)
                if not (0 <= other[0] < rows and 0 <= other[1] < cols):
                    continue
                if (r, c) in blocked or other in blocked or frozenset(((r, c), other)) in walls:
                    continue
                edges.append(((r, c), other))
    return edges


def grid_pddl(
    rows: int,
    cols: int,
    start: Cell,
    goal: Cell,
    *,
    blocked_cells: Iterable[Cell] = (),
    blocked_edges: Iterable[tuple[Cell, Cell]] = (),
    names: GridNames = GridNames(),
) -> GridPddl:
    """A grid domain and a problem from ``start`` to ``goal``.

    Example:
        >>> grid = grid_pddl(2, 2, start=(0, 0), goal=(1, 1), blocked_edges=[((0, 0), (0, 1))])
        >>> print(grid.problem.splitlines()[3])
          (:init (robot_at cell_0_0)
    """
    blocked_cells = set(blocked_cells)
    start, goal = _checked(start, rows, cols, "start"), _checked(goal, rows, cols, "goal")
    for what, cell in (("start", start), ("goal", goal)):
        if cell in blocked_cells:
            raise BadInputError(f"the {what} cell {cell} is blocked")
    edges = grid_edges(rows, cols, blocked_cells=blocked_cells, blocked_edges=blocked_edges)
    cells = " ".join(cell_name((r, c), names) for r in range(rows) for c in range(cols))
    facts = "\n".join(
        f"    ({names.neighbors} {cell_name(a, names)} {cell_name(b, names)})" for a, b in edges
    )
    problem = f"""(define (problem {names.problem})
  (:domain {names.domain})
  (:objects {cells} - {names.cell_type})
  (:init ({names.at} {cell_name(start, names)})
{facts})
  (:goal ({names.at} {cell_name(goal, names)})))
"""
    return GridPddl(grid_domain(names), problem)


def _check_size(rows: int, cols: int) -> None:
    if rows < 1 or cols < 1:
        raise BadInputError(f"a grid needs at least one row and one column, not {rows}x{cols}")


def _checked(cell: Cell, rows: int, cols: int, what: str) -> Cell:
    r, c = (int(x) for x in cell)
    if not (0 <= r < rows and 0 <= c < cols):
        raise BadInputError(f"{what} {tuple(cell)} is outside the {rows}x{cols} grid")
    return r, c
