"""Grounding, the delete-relaxation heuristics and exact goal distances, against hand values,
Fast Downward (its translator's grounding and its optimal plans) and pyperplan."""

from __future__ import annotations

import math
import random
import re
from pathlib import Path

import pytest

from planshape.errors import BadInputError, UnsolvableError
from planshape.planning import (
    GoalDistances,
    grid_pddl,
    ground_task,
    h_add,
    h_ff,
    h_max,
    load_task,
    parse_task,
    plan_text,
)
from planshape.planning.model import PddlTask
from planshape.planning.relaxed import relaxed_costs, relaxed_plan
from tests.toys import LINE_DOMAIN, LINE_PROBLEM, line_task

# A key at ``x`` opens two doors: h_max, h_add, h_FF and h* all differ.
KEYS_DOMAIN = """\
(define (domain keys)
  (:requirements :strips :typing :negative-preconditions)
  (:types place door)
  (:constants x - place)
  (:predicates (at ?p - place) (road ?a ?b - place) (key) (open ?d - door) (locked ?d - door))
  (:action go :parameters (?a ?b - place)
    :precondition (and (at ?a) (road ?a ?b)) :effect (and (at ?b) (not (at ?a))))
  (:action take :parameters () :precondition (and (at x) (not (key))) :effect (key))
  (:action unlock :parameters (?d - door)
    :precondition (and (key) (locked ?d)) :effect (and (open ?d) (not (locked ?d)))))
"""
KEYS_PROBLEM = """\
(define (problem keys-1) (:domain keys)
  (:objects s - place d1 d2 - door)
  (:init (at s) (road s x) (road x s) (locked d1) (locked d2))
  (:goal (and (open d1) (open d2))))
"""


def keys():
    return ground_task(parse_task(KEYS_DOMAIN, KEYS_PROBLEM))


def maze_task() -> PddlTask:
    from planshape.tasks.planar.abstract import maze_reach_grid

    model = maze_reach_grid()
    return load_task(model.domain, model.problem)


def push_task() -> PddlTask:
    from planshape.tasks.planar.abstract import push_grid

    model = push_grid()
    return load_task(model.domain, model.problem)


# ---- grounding --------------------------------------------------------------------------------


def test_grounding_joins_static_preconditions():
    ground = ground_task(parse_task(LINE_DOMAIN, LINE_PROBLEM))
    assert sorted(str(op.action) for op in ground.operators) == [
        "(move left middle)",
        "(move middle left)",
        "(move middle right)",
        "(move right middle)",
    ]
    assert ground_task(ground.task) is ground  # once per task
    push = ground_task(push_task())
    assert len(push.operators) == 1082  # 4·|cells| moves less the borders, plus the pushes
    assert all(op.neg for op in push.operators)  # (not (object_at ?b ?to)) is kept


def test_a_task_without_schemas_cannot_be_grounded():
    with pytest.raises(BadInputError, match="parse it from PDDL"):
        ground_task(line_task())


@pytest.mark.parametrize("which", ["maze", "push"])
def test_grounding_matches_fast_downwards_relaxed_exploration(which):
    # Fast Downward's translator ships with up-fast-downward, a dependency
    from fast_downward.translate import instantiate, normalize, options, pddl_parser

    task = maze_task() if which == "maze" else push_task()
    options.set_options([task.domain_file, task.problem_file])  # its normalize reads options
    fd_task = pddl_parser.open(task.domain_file, task.problem_file)
    normalize.normalize(fd_task)
    _, _, actions, _, _, _ = instantiate.explore(fd_task)
    ground = ground_task(task)
    costs = relaxed_costs(ground, ground.ids(task.init), "max", complete=True)
    reachable = {
        str(op.action) for k, op in enumerate(ground.operators) if not math.isinf(costs.op_cost[k])
    }
    assert reachable == {a.name for a in actions}


# ---- relaxed heuristics -----------------------------------------------------------------------


def test_hand_values_on_the_keys_domain():
    ground = keys()
    start = ground.ids({("at", "s"), ("locked", "d1"), ("locked", "d2")})
    # at x: 1, key: 2, open di: 3 each
    assert h_max(ground, start) == 3
    assert h_add(ground, start) == 6
    assert h_ff(ground, start) == h_ff(ground, start, "add") == 4  # go, take, unlock ×2
    assert (
        GoalDistances(ground)(ground.mask({("at", "s"), ("locked", "d1"), ("locked", "d2")})) == 4
    )
    holding = ground.ids({("at", "s"), ("key",), ("locked", "d1"), ("locked", "d2")})
    assert (h_max(ground, holding), h_add(ground, holding), h_ff(ground, holding)) == (1, 2, 2)
    done = ground.ids({("at", "s"), ("open", "d1"), ("open", "d2")})
    assert (h_max(ground, done), h_add(ground, done), h_ff(ground, done)) == (0, 0, 0)


def test_hand_values_on_the_line_domain():
    ground = ground_task(parse_task(LINE_DOMAIN, LINE_PROBLEM))
    for place, expected in (("left", 2), ("middle", 1), ("right", 0)):
        ids = ground.ids({("at", place)})
        assert h_max(ground, ids) == h_add(ground, ids) == h_ff(ground, ids) == expected
    assert h_add(ground, []) == h_ff(ground, []) == math.inf  # nowhere: a dead end


def test_heuristics_are_nonnegative_finite_and_zero_exactly_at_goal_states():
    ground = ground_task(maze_task())
    distances = GoalDistances(ground)
    for atom in ground.atoms:
        ids, mask = ground.ids({atom}), ground.mask({atom})
        exact = distances(mask)
        values = (h_max(ground, ids), h_add(ground, ids), h_ff(ground, ids))
        assert all(v >= 0 for v in values)
        assert all((v == 0) == ground.is_goal(mask) for v in (*values, exact))
        # on a grid every relaxed plan is a shortest path: all of them are h*
        assert values == (exact, exact, exact) and math.isfinite(exact)
    push = ground_task(push_task())
    robots = [a for a in push.atoms if a[0] == "robot_at"]
    boxes = [a for a in push.atoms if a[0] == "object_at"]
    rng = random.Random(0)
    for _ in range(40):
        state = {rng.choice(robots), rng.choice(boxes)}
        ids = push.ids(state)
        goal = push.is_goal(push.mask(state))
        for value in (h_max(push, ids), h_add(push, ids), h_ff(push, ids)):
            assert value >= 0 and (value == 0) == goal


def _stripped(domain: str) -> str:
    """The domain pyperplan can read: no (in)equalities, no negative preconditions (the delete
    relaxation drops them anyway)."""
    domain = re.sub(r"\(not \(= \?[\w-]+ \?[\w-]+\)\)", "", domain)
    domain = re.sub(r"\(not \(object_at \?b \?to\)\)", "", domain)
    return domain.replace(":negative-preconditions", "").replace(":equality", "")


@pytest.mark.parametrize("which", ["maze", "push"])
def test_relaxed_heuristics_agree_with_pyperplan(which, tmp_path: Path):
    from pyperplan.grounding import ground as pyperplan_ground
    from pyperplan.heuristics.relaxation import hAddHeuristic, hMaxHeuristic
    from pyperplan.pddl.parser import Parser
    from pyperplan.search.searchspace import make_root_node

    from planshape.tasks.common import pddl_file
    from planshape.tasks.planar.abstract import Grid, maze_reach_grid, push_grid_problem
    from planshape.tasks.planar.geometry import GEOMETRY as G

    if which == "maze":
        model = maze_reach_grid()
        domain, problem = model.domain.read_text(), model.problem.read_text()
    else:  # a coarser push grid: pyperplan grounds push's five parameters by enumeration
        domain = pddl_file("push", "domain.pddl").read_text()
        problem = push_grid_problem(Grid(G.box_goal, 0.12), G.ee_start, G.box_start)
    (tmp_path / "d.pddl").write_text(_stripped(domain))
    (tmp_path / "p.pddl").write_text(problem)
    parser = Parser(str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl"))
    theirs = pyperplan_ground(parser.parse_problem(parser.parse_domain()))
    reference = hAddHeuristic(theirs), hMaxHeuristic(theirs)
    ground = ground_task(parse_task(domain, problem))
    robots = [a for a in ground.atoms if a[0] == "robot_at"]
    boxes = [a for a in ground.atoms if a[0] == "object_at"]
    rng = random.Random(1)
    for _ in range(30):
        state = {rng.choice(robots)} | ({rng.choice(boxes)} if boxes else set())
        ids = ground.ids(state)
        node = make_root_node(frozenset("(" + " ".join(a) + ")" for a in state))
        assert (h_add(ground, ids), h_max(ground, ids)) == tuple(h(node) for h in reference)
        # h_FF depends on how ties between achievers are broken (pyperplan's differ), so it is
        # checked against its definition instead: a relaxed plan, no shorter than h_max
        for supporters in ("max", "add"):
            plan = relaxed_plan(ground, ids, supporters)
            if math.isinf(h_add(ground, ids)):  # a box on the border: a dead end
                assert plan is None and h_ff(ground, ids, supporters) == math.inf
                continue
            assert plan is not None and _relaxed_plan_reaches_goal(ground, ids, plan)
            assert h_max(ground, ids) <= len(plan) == h_ff(ground, ids, supporters)
            assert supporters == "max" or len(plan) <= h_add(ground, ids)


def _relaxed_plan_reaches_goal(ground, state, plan) -> bool:
    """Whether the operators of ``plan``, applied without deletes in some order, reach the
    goal from ``state``."""
    reached, pending, changed = set(state), set(plan), True
    while changed:
        changed = False
        for k in list(pending):
            if set(ground.operators[k].pre) <= reached:
                reached |= set(ground.operators[k].add)
                pending.discard(k)
                changed = True
    return set(ground.goal) <= reached


# ---- exact distances ---------------------------------------------------------------------------


def _problem_from(task: PddlTask, state: set) -> str:
    objects = "\n    ".join(f"{o} - {t}" for o, t in sorted(task.objects.items()))
    init = "\n    ".join("(" + " ".join(a) + ")" for a in sorted(task.static_atoms() | state))
    goal = " ".join("(" + " ".join(a) + ")" for a in sorted(task.goal))
    return f"""(define (problem from-state) (:domain {task.domain_name})
  (:objects {objects})
  (:init {init})
  (:goal (and {goal})))
"""


def _optimal_cost(task: PddlTask, state: set) -> float:
    domain = Path(task.domain_file).read_text()
    try:
        return plan_text(domain, _problem_from(task, state), search="astar-blind").cost
    except UnsolvableError:
        return math.inf


def test_exact_distances_equal_fast_downwards_optimal_plan_costs_on_the_maze_grid():
    task = maze_task()
    ground = ground_task(task)
    distances = GoalDistances(ground)
    robots = sorted(a for a in ground.atoms if a[0] == "robot_at")
    for atom in random.Random(2).sample(robots, 5):
        assert distances.of_atoms({atom}) == _optimal_cost(task, {atom}), atom
    start = {a for a in task.init if a[0] == "robot_at"}
    assert distances.of_atoms(start) == 19  # the plan around the U


def test_exact_distances_on_the_push_grid_follow_the_real_semantics():
    task = push_task()
    ground = ground_task(task)
    distances = GoalDistances(ground)
    assert 20_000 < distances.n_states < 25_000
    start = {a for a in task.init if a[0] in ("robot_at", "object_at")}
    assert distances.of_atoms(start) == _optimal_cost(task, start) == 16
    # a box in a corner can never leave it: a dead end, and Fast Downward agrees
    corner = {("robot_at", "cell_1_1"), ("object_at", "box", "cell_0_0")}
    assert distances.of_atoms(corner) == _optimal_cost(task, corner) == math.inf
    # a state outside the space reachable from :init (the end effector on the box: no action
    # leads there) is explored on demand
    off = {("robot_at", "cell_5_5"), ("object_at", "box", "cell_5_5")}
    before = distances.n_states
    assert distances.of_atoms(off) == _forward_bfs(ground, ground.mask(off)) < math.inf
    assert distances.n_states > before
    assert distances.of_atoms(start) == 16  # and the states labelled before keep their values


def _forward_bfs(ground, start: int) -> float:
    """h* by the textbook forward breadth-first search (independent of GoalDistances)."""
    frontier, seen, depth = [start], {start}, 0
    while frontier:
        if any(ground.is_goal(s) for s in frontier):
            return depth
        following = []
        for state in frontier:
            for _, after in ground.successors(state):
                if after not in seen:
                    seen.add(after)
                    following.append(after)
        frontier, depth = following, depth + 1
    return math.inf


def test_state_spaces_beyond_the_limit_are_refused():
    ground = ground_task(parse_task(*grid_pddl(4, 4, start=(0, 0), goal=(3, 3)).texts))
    with pytest.raises(BadInputError, match="more than 5 states"):
        GoalDistances(ground, max_states=5)
    distances = GoalDistances(ground, max_states=17)
    two = ground.mask({("robot_at", "cell_0_0"), ("robot_at", "cell_2_2")})
    with pytest.raises(BadInputError, match="more than 17 states"):
        distances(two)  # two robots: pairs of cells, more than the limit
    assert distances.n_states == 16 and distances.of_atoms({("robot_at", "cell_1_1")}) == 4
