"""The planner-heuristic potentials (h-add, h-ff, h-star, their discount-aware variants and
h-star-geodesic) on the planar grid models."""

from __future__ import annotations

import itertools
import math
import pickle

import gymnasium
import numpy as np
import pytest

import planshape  # noqa: F401  (registers the tasks)
from planshape.baselines.heuristic import HeuristicPotential, HStarGeodesic
from planshape.errors import BadInputError, PotentialError
from planshape.invariance import check_potential
from planshape.planning import GoalDistances, ground_task
from planshape.shaping.potentials import ShapingContext, make_potential, potential_ids
from tests.baselines.models import bound

HEURISTIC_IDS = [
    "h-add",
    "h-ff",
    "h-star",
    "h-add-discounted",
    "h-ff-discounted",
    "h-star-discounted",
    "h-star-geodesic",
]
NEW_IDS = ["plan-distance", "plan-path", "goal-distance", *HEURISTIC_IDS]


def maze():
    return bound("maze_reach_grid")


def centre(rc):
    from planshape.tasks.planar.abstract import Grid
    from planshape.tasks.planar.geometry import GEOMETRY as G

    return np.array(Grid(G.maze_goal).centre(rc))


def test_the_new_potentials_are_registered():
    assert set(NEW_IDS) <= set(potential_ids())
    assert make_potential("h-star-discounted").gamma == "learner"
    assert make_potential("h-ff").gamma is None
    assert isinstance(make_potential("h-star-geodesic"), HStarGeodesic)


@pytest.mark.parametrize("potential", NEW_IDS)
def test_the_new_potentials_keep_the_optimal_policy(potential):
    report = check_potential(potential, mdps=["maze-reach", "push", "random-episodic"])
    assert report.preserved, [v.counterexample for v in report.verdicts if not v.preserved]


def test_linear_values_on_the_maze_grid():
    b = maze()
    start, goal = centre((12, 4)), centre((6, 5))
    for heuristic in ("h-add", "h-ff", "h-star"):
        phi = HeuristicPotential(heuristic)
        assert phi(b.ctx(start)) == -1.0  # normalized by h(ŝ0) = 19, the plan's length
        assert phi(b.ctx(goal)) == 0.0
        assert phi(b.ctx(centre((0, 5)))) == pytest.approx(-6 / 19)
    assert HeuristicPotential("h-star", normalize=False, scale=2.0)(b.ctx(start)) == -38.0


def test_the_discount_aware_variant():
    b = maze()
    gamma = 0.99
    phi = HeuristicPotential("h-star", gamma=gamma)
    assert phi(b.ctx(centre((12, 4)))) == pytest.approx(-1.0)
    assert phi(b.ctx(centre((0, 5)))) == pytest.approx(-(1 - gamma**6) / (1 - gamma**19))
    raw = HeuristicPotential("h-star", gamma=gamma, normalize=False)
    assert raw(b.ctx(centre((0, 5)))) == pytest.approx(-(1 - gamma**6) / (1 - gamma))
    # one step closer pays the same F = γφ' − φ = 1 at any distance from the goal
    for far in ((0, 5), (12, 4)):
        h = GoalDistances(ground_task(b.task)).of_atoms(
            b.abstraction.abstract_state(centre(far).astype(np.float32))
        )
        after = -(1 - gamma ** (h - 1)) / (1 - gamma)
        before = -(1 - gamma**h) / (1 - gamma)
        assert gamma * after - before == pytest.approx(1.0)


def test_dead_ends_get_the_documented_finite_value():
    b = maze()
    wall = centre((10, 5))  # a cell on the U's bottom wall: no move enters or leaves it
    distances = GoalDistances(ground_task(b.task))
    assert (
        distances.max_finite() == 21 and distances.of_atoms({("robot_at", "cell_10_5")}) == math.inf
    )
    assert HeuristicPotential("h-star")(b.ctx(wall)) == pytest.approx(-(1 + 21) / 19)
    assert HeuristicPotential("h-ff", dead_end=50.0)(b.ctx(wall)) == pytest.approx(-50 / 19)
    assert HeuristicPotential("h-star", gamma=0.99)(b.ctx(wall)) == pytest.approx(
        -1 / (1 - 0.99**19)
    )
    assert HStarGeodesic()(b.ctx(wall)) == pytest.approx(-(1 + 21) / 19)


@pytest.mark.parametrize("potential", HEURISTIC_IDS)
def test_the_detour_pays_more_than_the_straight_line_behind_the_wall(potential):
    """(0, 5), above the U, is 0.30 m from the goal and 6 moves away; (11, 5), under the bottom
    wall, is 0.25 m away in a straight line and 19 moves away (around the wall)."""
    from planshape.tasks.planar.geometry import GEOMETRY as G

    b = maze()
    over, under = centre((0, 5)), centre((11, 5))
    assert np.linalg.norm(over - G.maze_goal) > np.linalg.norm(under - G.maze_goal)
    phi = make_potential(potential).for_discount(0.99)
    assert phi(b.ctx(over)) > phi(b.ctx(under))
    # and every free cell: the nearer the goal along the walls, the larger φ
    distances = GoalDistances(ground_task(b.task))
    rows = [
        (
            distances.of_atoms(b.abstraction.abstract_state(centre((r, c)).astype(np.float32))),
            phi(b.ctx(centre((r, c)))),
        )
        for r in range(14)
        for c in range(11)
    ]
    free = sorted((h, v) for h, v in rows if math.isfinite(h))
    for (h1, v1), (h2, v2) in itertools.pairwise(free):
        assert h1 == h2 or v1 > v2


def test_geodesic_rises_within_a_cell_and_equals_h_star_at_cell_centres():
    b = maze()
    geodesic, exact = HStarGeodesic(), HeuristicPotential("h-star")
    for k, fluents in enumerate(b.plan.subgoals.fluents[:-1]):
        (cell,) = fluents
        rc = tuple(int(x) for x in cell[1].split("_")[1:])
        here = centre(rc)
        assert geodesic(b.ctx(here, progress=k)) == pytest.approx(exact(b.ctx(here)))
    # along the plan's first two moves (up, then left: a turn) φ rises at every 5 mm step, by
    # 1/19 per move in all, and the turn adds one upward jump of less than half a move
    path = [centre((12, 4)), centre((11, 4)), centre((11, 3))]
    points = [
        a + f * (c - a)
        for a, c in itertools.pairwise(path)
        for f in np.linspace(0, 1, 10, endpoint=False)
    ] + [path[-1]]
    values = np.array([geodesic(b.ctx(p)) for p in points]) * 19
    rises = np.diff(values)
    assert (rises > 0).all() and values[-1] - values[0] == pytest.approx(2.0)
    assert np.sort(rises)[-2] == pytest.approx(0.1, abs=1e-5) and rises.max() < 0.5


def test_cached_values_equal_values_from_the_full_abstract_state():
    b = bound("push_grid")
    rng = np.random.default_rng(0)
    for heuristic in ("h-ff", "h-add", "h-star"):
        cached, direct = HeuristicPotential(heuristic), HeuristicPotential(heuristic)
        for obs in rng.uniform([0.23, -0.35] * 2, [0.78, 0.30] * 2, (30, 4)).astype(np.float32):
            given = ShapingContext(
                obs=obs,
                progress=0,
                t=0,
                subgoals=b.plan.subgoals,
                geometry=b.model.geometry,
                abstraction=b.abstraction,
                atoms=b.abstraction.abstract_state(obs),
            )
            first = cached(b.ctx(obs))
            assert first == cached(b.ctx(obs)) == direct(given)
            assert math.isfinite(first)


def test_push_grid_values_and_normalization():
    from planshape.tasks.planar.geometry import GEOMETRY as G

    b = bound("push_grid")
    start = np.array([*G.ee_start, *G.box_start], np.float32)
    done = np.array([0.45, 0.10, *G.box_goal], np.float32)
    for potential in HEURISTIC_IDS:
        phi = make_potential(potential).for_discount(0.99)
        # the end effector starts 2 cm off its cell's centre, which only the geodesic sees
        assert phi(b.ctx(start)) == pytest.approx(
            -1.0, abs=0.01 if "geodesic" in potential else 1e-9
        )
        assert phi(b.ctx(done)) == 0.0
    h = HeuristicPotential("h-add", normalize=False)
    assert h(b.ctx(start)) == -66.0  # h_add counts the end effector's and the box's costs


def test_a_potential_pickles_without_its_caches():
    b = maze()
    phi = make_potential("h-ff")
    value = phi(b.ctx(centre((0, 5))))
    clone = pickle.loads(pickle.dumps(phi))
    assert clone.id == "h-ff" and clone(b.ctx(centre((0, 5)))) == value


def test_bad_arguments_and_missing_abstraction():
    with pytest.raises(BadInputError, match="unknown heuristic 'h-foo'"):
        HeuristicPotential("h-foo")
    with pytest.raises(BadInputError, match="a discount in"):
        HeuristicPotential("h-star", gamma=1.0)
    with pytest.raises(PotentialError, match="need the context's abstraction"):
        HeuristicPotential()(ShapingContext(obs=None, progress=0, t=0, subgoals=(frozenset(),)))


@pytest.mark.parametrize("potential", ["h-star-geodesic", "h-ff-discounted", "plan-distance"])
def test_shaped_maze_reach_environment(potential):
    env = gymnasium.make(
        "planshape/MazeReach-v0", reward="shaped", potential=potential, model="grid", gamma=0.99
    )
    _, info = env.reset(seed=0)
    assert info["potential"] == pytest.approx(-1.0, abs=0.05)
    for _ in range(5):  # straight up, against the bottom wall's underside
        *_, info = env.step(np.array([0.0, 1.0], np.float32))
        assert math.isfinite(info["potential"]) and math.isfinite(info["shaping"])
    env.close()


@pytest.mark.parametrize("gamma", [0.9, 0.99])
def test_discounted_potentials_take_the_learners_discount_from_the_wrapper(gamma):
    """h-star-discounted shaped for a learner with γ is −(1 − γ^h)/(1 − γ^h0) with that γ."""
    env = gymnasium.make(
        "planshape/MazeReach-v1",
        reward="shaped",
        potential="h-star-discounted",
        model="grid",
        gamma=gamma,
    )
    obs, info = env.reset(seed=0)
    wrapper = env
    while not hasattr(wrapper, "shaping_gamma"):
        wrapper = wrapper.env
    assert wrapper.potential.gamma == gamma
    fixed = HeuristicPotential("h-star", gamma=gamma).rescaled(wrapper.potential.scale)
    ctx = ShapingContext(
        obs=obs,
        progress=0,
        t=0,
        subgoals=wrapper.progress.subgoals,
        geometry=wrapper.geometry,
        abstraction=wrapper.progress.abstraction,
    )
    assert info["potential"] == fixed(ctx)
    for _ in range(30):
        obs, *_, info = env.step(np.array([1.0, 0.3], np.float32))
    ctx.obs, ctx.progress = obs, info["progress"]
    assert info["potential"] == fixed(ctx)


def test_a_learner_discount_potential_needs_a_discount_below_one():
    with pytest.raises(BadInputError, match="below 1"):
        make_potential("h-star-discounted").for_discount(1.0)
    with pytest.raises(PotentialError, match="for_discount"):
        make_potential("h-star-discounted")(maze().ctx(centre((0, 5))))
    assert make_potential("h-star", gamma=0.5).for_discount(0.9).gamma == 0.5
