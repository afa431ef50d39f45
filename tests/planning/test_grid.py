"""Generated grid PDDL: the neighbour relation, walls, names, and shortest plans."""

from __future__ import annotations

from collections import deque

import pytest

from planshape.errors import BadInputError
from planshape.planning import GridNames, cell_name, grid_pddl, parse_task, solve_text
from planshape.planning.grid import grid_edges


def test_four_connected_in_both_directions():
    edges = grid_edges(3, 4)
    assert len(edges) == 2 * (3 * 3 + 2 * 4)  # horizontal and vertical pairs, both ways
    assert ((1, 1), (1, 2)) in edges and ((1, 2), (1, 1)) in edges
    assert ((0, 0), (1, 1)) not in edges


def test_blocked_cells_and_walls_remove_neighbour_facts():
    edges = grid_edges(3, 3, blocked_cells=[(1, 1)], blocked_edges=[((0, 0), (0, 1))])
    assert not [e for e in edges if (1, 1) in e]
    assert ((0, 0), (0, 1)) not in edges and ((0, 1), (0, 0)) not in edges
    assert ((0, 0), (1, 0)) in edges


def test_task_from_generated_text():
    grid = grid_pddl(2, 3, start=(0, 0), goal=(1, 2))
    task = parse_task(grid.domain, grid.problem)
    assert task.static_predicates == {"neighbors"}
    assert task.init - task.static_atoms() == {("robot_at", "cell_0_0")}
    assert task.goal == {("robot_at", "cell_1_2")}
    assert len(task.objects_of_type("cell")) == 6


def test_names_are_configurable(tmp_path):
    names = GridNames(domain="maze", problem="maze-1", cell_type="tile", cell_prefix="t",
                      at="agent_in", neighbors="adjacent", move="step")  # fmt: skip
    grid = grid_pddl(2, 2, start=(0, 0), goal=(1, 1), names=names)
    domain, problem = grid.write(tmp_path)
    task = parse_task(domain.read_text(), problem.read_text())
    assert task.domain_name == "maze" and set(task.actions) == {"step"}
    assert task.goal == {("agent_in", cell_name((1, 1), names))} == {("agent_in", "t_1_1")}
    assert task.objects["t_0_1"] == "tile"


def shortest_path_length(rows, cols, start, goal, **walls) -> int:
    edges = grid_edges(rows, cols, **walls)
    distance, queue = {start: 0}, deque([start])
    while queue:
        cell = queue.popleft()
        for a, b in edges:
            if a == cell and b not in distance:
                distance[b] = distance[cell] + 1
                queue.append(b)
    return distance[goal]


def test_planned_maze_is_a_shortest_path_around_the_walls():
    walls = {"blocked_cells": [(1, 0), (1, 1), (1, 2), (3, 1), (3, 2), (3, 3)]}
    grid = grid_pddl(5, 4, start=(0, 0), goal=(4, 0), **walls)
    plan = solve_text(grid.domain, grid.problem, cache_dir=False)
    assert plan.length == shortest_path_length(5, 4, (0, 0), (4, 0), **walls) == 10
    assert plan.subgoals.fluents[-1] == {("robot_at", "cell_4_0")}
    visited = [next(iter(f))[1] for f in plan.subgoals.fluents]
    assert not {"cell_1_0", "cell_1_1", "cell_1_2", "cell_3_1"} & set(visited)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"start": (0, 5)}, r"start \(0, 5\) is outside the 3x3 grid"),
        ({"blocked_cells": [(2, 2)]}, r"the goal cell \(2, 2\) is blocked"),
        ({"blocked_edges": [((0, 0), (1, 1))]}, r"not 4-neighbours"),
    ],
)
def test_bad_grids(kwargs, message):
    arguments = {"start": (0, 0), "goal": (2, 2), **kwargs}
    with pytest.raises(BadInputError, match=message):
        grid_pddl(3, 3, **arguments)
