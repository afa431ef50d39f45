"""The plan-distance potential: plan steps left plus the distance to the next subgoal, in
steps."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from planshape.baselines.plan_distance import PlanDistance, step_targets
from planshape.invariance.toys import PointGeometry
from planshape.shaping.potentials import ShapingContext, make_potential
from tests.baselines.models import bound


def cell_centre(model, atom):
    return model.geometry.locate(frozenset({atom}))["ee"]


def test_hand_values_on_a_point_plan():
    geometry = PointGeometry({"a": (0, 0), "b": (0, 2), "c": (1, 2)})
    subgoals = [frozenset({("robot_at", p)}) for p in "abc"]

    def phi(obs, progress, **kwargs):
        ctx = ShapingContext(
            obs=np.array(obs, float), progress=progress, t=0, subgoals=subgoals, geometry=geometry
        )
        return PlanDistance(**kwargs)(ctx)

    assert phi([0, 0], 0) == -1.0  # 1 step after b, and b is one (2 m) step away
    assert phi([0, 1.5], 0) == pytest.approx(-(1 + 0.25) / 2)
    assert phi([0, 2], 1) == pytest.approx(-0.5)  # c is one (1 m) step away
    assert phi([1, 2], 2) == 0.0
    assert phi([1, 1.5], 2) == pytest.approx(-0.25)  # done, but 0.5 m from the goal
    assert phi([1, 1.5], 2, tolerance=0.6) == 0.0
    assert phi([0, 1.5], 0, normalize=False, scale=3.0) == pytest.approx(-3.75)


def test_monotone_along_the_maze_grid_plan():
    """Walking the plan's cell centres (around the U) with progress tracked as the wrapper
    does, φ never falls, and at the centre of subgoal k it is −(n − k)/n."""
    b = bound("maze_reach_grid")
    phi = make_potential("plan-distance")
    centres = [cell_centre(b.model, next(iter(f))) for f in b.plan.subgoals.fluents]
    n = len(centres) - 1
    assert n == 19
    progress, values = 0, []
    for k, (here, there) in enumerate(itertools.pairwise(centres)):
        for f in np.linspace(0, 1, 10, endpoint=False):
            obs = (here + f * (there - here)).astype(np.float32)
            progress = b.progress.advance(progress, obs) if values else b.progress.initial(obs)
            values.append(phi(b.ctx(obs, progress)))
            if f == 0:
                assert progress == k and values[-1] == pytest.approx(-(n - k) / n, abs=1e-6)
    final = centres[-1].astype(np.float32)
    values.append(phi(b.ctx(final, b.progress.advance(progress, final))))
    assert values[0] == pytest.approx(-1.0, abs=1e-6) and values[-1] == 0.0
    assert all(v2 >= v1 - 1e-6 for v1, v2 in itertools.pairwise(values))
    # the straight line from the start to the goal goes through the wall; φ does not reward it
    from planshape.tasks.planar.geometry import GEOMETRY as G

    under_the_goal = np.array([G.maze_goal[0], -0.25], np.float32)
    assert phi(b.ctx(under_the_goal, 1)) < phi(b.ctx(centres[1].astype(np.float32), 1))


def test_units_are_grid_cells_and_waypoint_segments():
    grid = bound("maze_reach_grid")
    units = [
        u for row in step_targets(grid.model.geometry, grid.plan.subgoals)[1:] for _, _, u in row
    ]
    assert units == pytest.approx([0.05] * len(units))
    multi = bound("maze_reach_multi")
    table = step_targets(multi.model.geometry, multi.plan.subgoals)
    centres = [cell_centre(multi.model, next(iter(f))) for f in multi.plan.subgoals.fluents]
    for j in range(1, len(table)):
        ((_, target, unit),) = table[j]
        assert np.allclose(target, centres[j])
        assert unit == pytest.approx(np.linalg.norm(centres[j] - centres[j - 1]))


def test_push_grid_measures_the_end_effector_then_the_box():
    from planshape.tasks.planar.geometry import GEOMETRY as G

    b = bound("push_grid")
    phi = PlanDistance()
    start = np.array([*G.ee_start, *G.box_start], np.float32)
    assert phi(b.ctx(start, b.progress.initial(start))) == pytest.approx(-1.0, abs=0.05)
    last = b.model.geometry.locate(b.plan.subgoals.fluents[-1])
    done = np.array([*last["ee"], *G.box_goal], np.float32)
    assert phi(b.ctx(done, b.plan.length)) == pytest.approx(0.0, abs=1e-6)
    # the last subgoal places the end effector too (behind the box): away from it, φ < 0
    away = np.array([last["ee"][0] - 0.1, last["ee"][1], *G.box_goal], np.float32)
    assert phi(b.ctx(away, b.plan.length)) == pytest.approx(-2 / b.plan.length, abs=1e-6)


def test_depends_on_observation_and_progress_only():
    b = bound("maze_reach_grid")
    phi = make_potential("plan-distance")
    obs = np.array([0.3, 0.1], np.float32)
    assert {phi(b.ctx(obs, 7, t)) for t in (0, 5, 500)} == {phi(b.ctx(obs, 7))}


def test_sum_adds_every_entity_out_of_place_and_equals_plan_distance_with_one_entity():
    """``plan-distance-sum`` adds the box's distance (in steps) to the end effector's on push's
    grid plan, is ``plan-distance`` on reach's and maze-reach's (one entity), and its fast path
    (``specialize``) computes what ``potential`` does."""
    rng = np.random.default_rng(0)
    first, summed = make_potential("plan-distance"), make_potential("plan-distance-sum")
    for factory in ("reach_grid", "maze_reach_grid"):
        b = bound(factory)
        for obs in rng.uniform(-0.5, 0.5, (20, 2)).astype(np.float32):
            for k in (0, b.plan.length // 2, b.plan.length):
                assert summed(b.ctx(obs, k)) == first(b.ctx(obs, k))
    b = bound("push_grid")
    n = b.plan.length
    fast = summed.step_function(b.ctx(np.zeros(4, np.float32)))
    for obs in rng.uniform(-0.5, 0.5, (20, 4)).astype(np.float32):
        for k in (0, n // 2, n - 1):
            ctx = b.ctx(obs, k)
            table = step_targets(b.model.geometry, b.plan.subgoals)[min(k + 1, n)]
            where = b.model.geometry.positions(obs)
            steps = sum(np.linalg.norm(where[e] - np.asarray(t)) / u for e, t, u in table)
            assert summed(ctx) == pytest.approx(-(n - min(k + 1, n) + steps) / n)
            assert fast(obs, k) == pytest.approx(summed(ctx), abs=1e-12)
            assert summed(ctx) <= first(ctx)


def test_an_unknown_measure_is_refused_with_the_choices():
    from planshape.errors import BadInputError

    with pytest.raises(BadInputError, match="measure='last' is not 'first' or 'sum'"):
        PlanDistance(measure="last")
