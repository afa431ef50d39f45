"""The plan-path potential: the chain to the last entity plus its way along the plan's path."""

from __future__ import annotations

import math

import gymnasium
import numpy as np
import pytest

import planshape  # noqa: F401  (registers the tasks)
from planshape.baselines import plan_path
from planshape.baselines.plan_path import PlanPath, Polyline
from planshape.errors import PotentialError
from planshape.invariance.toys import PointGeometry
from planshape.shaping.potentials import ShapingContext, make_potential


def test_registered():
    assert isinstance(make_potential("plan-path"), PlanPath)


def test_polyline_rest_by_hand():
    path = Polyline([(0, 0), (0, 2), (1, 2)])
    assert path.rest((0, 1)) == pytest.approx(2.0)  # on the path: 1 m up, 1 m right
    assert path.rest((0, -1)) == pytest.approx(4.0)  # 1 m onto the start, then all 3 m
    assert path.rest((-1, 0)) == pytest.approx(5**0.5 + 1)  # the corner is nearer than the start
    assert path.rest((2, 2)) == pytest.approx(1.0)  # past the end: straight back to it
    assert Polyline([(1, 1)]).rest((1, 2)) == 1.0
    assert Polyline([(0, 0), (0, 0), (0, 1)]).rest((0, 0)) == pytest.approx(1.0)


def test_the_plane_fast_path_agrees_with_numpy_in_any_dimension():
    rng = np.random.default_rng(1)
    for _ in range(50):
        points = rng.uniform(-1, 1, (int(rng.integers(2, 8)), 2))
        points[1] = points[0]  # a zero-length segment too
        path = Polyline(points)
        x = rng.uniform(-1.5, 1.5, 2)
        assert path.rest(x) == pytest.approx(path._rest_any(x), abs=1e-12)
        lifted = Polyline(np.c_[points, np.zeros(len(points))])  # the same path in 3-D
        assert lifted.rest([*x, 0.0]) == pytest.approx(path.rest(x), abs=1e-12)


def shaped(task, model):
    env = gymnasium.make(task, reward="shaped", potential="plan-path", model=model, gamma=1.0)
    env.reset(seed=0)
    return env


def context(env, obs, progress=0, t=0):
    return ShapingContext(
        obs=np.asarray(obs, np.float32),
        progress=progress,
        t=t,
        subgoals=env.get_wrapper_attr("progress").subgoals,
        geometry=env.get_wrapper_attr("geometry"),
    )


@pytest.mark.parametrize("model", ["grid", "grid-diagonal", "multi"])
def test_push_minus_one_at_the_plan_start_and_zero_at_the_goal(model):
    env = shaped("planshape/Push-v0", model)
    geometry = env.get_wrapper_attr("geometry")
    subgoals = env.get_wrapper_attr("progress").subgoals
    start = geometry.locate(subgoals[0])
    goal = geometry.locate(subgoals[-1])["box"]
    phi = make_potential("plan-path")
    assert phi(context(env, [*start["ee"], *start["box"]])) == pytest.approx(-1.0)
    assert phi(context(env, [*goal, *goal])) == pytest.approx(0.0, abs=1e-6)


def test_a_function_of_the_observation_alone_and_lipschitz():
    """No jump when a subgoal is reached or skipped: |Δφ| ≤ 2 Σ|Δp| / d0 on every step."""
    env = shaped("planshape/Push-v0", "grid")
    phi = make_potential("plan-path")
    rng = np.random.default_rng(0)
    obs = np.array([0.45, -0.3, 0.35, -0.1])  # Ŝ[0]'s places: φ = −1 there
    assert phi(context(env, obs)) == pytest.approx(-1.0)
    box_path = plan_path.entity_path(
        env.get_wrapper_attr("geometry"), env.get_wrapper_attr("progress").subgoals, "box"
    )
    d0 = np.linalg.norm(obs[:2] - obs[2:]) + box_path.rest(obs[2:])
    previous = -1.0
    for _ in range(300):
        step = rng.normal(0, 0.01, 4)
        obs = obs + step
        value = phi(context(env, obs, progress=int(rng.integers(0, 17)), t=int(rng.integers(99))))
        assert value == phi(context(env, obs))
        moved = np.linalg.norm(step[:2]) + np.linalg.norm(step[2:])
        assert abs(value - previous) <= 2 * moved / d0 + 1e-6
        previous = value


@pytest.mark.parametrize(
    ("task", "model", "entity"),
    [
        ("planshape/Reach-v1", "grid", "ee"),
        ("planshape/MazeReach-v1", "grid", "ee"),
        ("planshape/MazeReach-v1", "multi", "ee"),
        ("planshape/Push-v1", "grid", "box"),
        ("planshape/Push-v1", "grid-diagonal", "box"),
    ],
)
def test_rest_is_the_way_onto_the_last_segment(task, model, entity):
    """The least segment value is always the last segment's (the module docstring's triangle
    inequality): the path before it does not enter φ. Equal up to rounding (an earlier
    segment that ties may round one bit lower) at random points around the plan, the wall's
    far side included."""
    env = shaped(task, model)
    path = plan_path.entity_path(
        env.get_wrapper_attr("geometry"), env.get_wrapper_attr("progress").subgoals, entity
    )
    assert len(path._segments) > 1
    last = [path._backwards[0]]
    rng = np.random.default_rng(2)
    low, high = path.points.min(axis=0) - 0.2, path.points.max(axis=0) + 0.2
    for x in rng.uniform(low, high, (5000, 2)).tolist():
        assert path.rest(x) == pytest.approx(plan_path._least(last, *x), rel=0, abs=1e-12)


def test_maze_reach_path_goes_around_the_wall():
    env = shaped("planshape/MazeReach-v0", "grid")
    path = plan_path.entity_path(
        env.get_wrapper_attr("geometry"), env.get_wrapper_attr("progress").subgoals, "ee"
    )
    assert path.points[:, 1].max() > 0.15  # over the walls' tops
    phi = make_potential("plan-path")
    start = path.points[0]
    # further along the path is better, though straight-line closer to the goal is not
    assert phi(context(env, path.points[len(path.points) // 2])) > phi(context(env, start))


def test_no_place_for_the_last_entity_is_a_clear_error():
    geometry = PointGeometry({"a": (0, 0)})
    ctx = ShapingContext(np.zeros(2), 0, 0, [frozenset(), frozenset()], geometry)
    with pytest.raises(PotentialError, match="plan-path.*places 'ee'"):
        make_potential("plan-path")(ctx)


def least_over_every_segment(path: Polyline, x: list[float]) -> float:
    """The exact minimum of every segment's value, in rest's arithmetic, with no shortcut."""
    return min(
        math.hypot(
            x[0] - ax - t * dx,
            x[1] - ay - t * dy,
        )
        + (1.0 - t) * length
        + after
        for (ax, ay), (dx, dy), squared, length, after in path._segments
        for t in [
            min(
                max(((x[0] - ax) * dx + (x[1] - ay) * dy) / squared if squared else 0.0, 0.0),
                1.0,
            )
        ]
    )


def test_rest_stops_early_but_equals_the_minimum_over_every_segment():
    """The search stops once the length after a segment reaches the best value found; the
    result must be the exact minimum over all segments (stored runs depend on its bits)."""
    rng = np.random.default_rng(0)
    points = np.cumsum(rng.uniform(-0.05, 0.05, (30, 2)), axis=0)
    path = Polyline(points)
    for x in rng.uniform(-0.3, 0.3, (500, 2)).tolist():
        assert path.rest(x) == least_over_every_segment(path, x)


@pytest.mark.parametrize("task", ["planshape/Reach-v1", "planshape/MazeReach-v1"])
def test_cell_candidates_give_the_minimum_over_every_segment_bit_for_bit(task):
    """rest searches only the segments that can be least in x's cell: on the grid models'
    paths (straight runs of cells, whose segments tie exactly where x is behind them) its
    result is the exact minimum over every segment, at many points of each cell, on the
    cells' edges and corners, and off the path."""
    env = gymnasium.make(task, reward="shaped", potential="plan-path", model="grid", gamma=0.99)
    env.reset(seed=0)
    wrapper = env
    while not hasattr(wrapper, "potential"):
        wrapper = wrapper.env
    path = plan_path.entity_path(wrapper.geometry, wrapper.progress.subgoals, "ee")
    assert len(path._segments) > 10  # around the wall (reach) or the U (maze-reach)
    cell = path._cell
    rng = np.random.default_rng(1)
    low, high = path.points.min(axis=0) - 0.1, path.points.max(axis=0) + 0.1
    samples = rng.uniform(low, high, (3000, 2)).tolist()
    # many points inside a few cells, and the cells' own edges and corners
    corners = np.floor(rng.uniform(low, high, (50, 2)) / cell) * cell
    samples += (corners[:, None, :] + rng.uniform(0, cell, (50, 20, 2))).reshape(-1, 2).tolist()
    samples += corners.tolist() + (corners + np.array([cell, 0.0])).tolist()
    samples += path.points.tolist()
    for x in samples:
        assert path.rest(x) == least_over_every_segment(path, x), x
    assert path._near and max(map(len, path._near.values())) < len(path._segments)


def test_cell_candidates_on_segments_whose_least_changes_within_a_cell():
    """The same on segments whose values cross everywhere (arbitrary segments with ascending
    lengths after them, as rest's search order needs): here the least segment changes inside
    cells, so a candidate set without the Lipschitz margin misses it (with no margin 264 of
    these 60,000 points differ, with a margin of one cell 4)."""
    for seed in range(3):
        rng = np.random.default_rng(seed)
        path = Polyline(np.cumsum(rng.uniform(-0.05, 0.05, (12, 2)), axis=0))
        segments, after = [], 0.0
        for _ in range(12):
            start, step = rng.uniform(-0.2, 0.2, 2), rng.uniform(-0.1, 0.1, 2)
            length = float(np.hypot(*step))
            segments.append((start.tolist(), step.tolist(), length * length, length, after))
            after += float(rng.uniform(0, 0.03))
        path._backwards, path._segments = segments, segments[::-1]
        for x in rng.uniform(-0.3, 0.3, (20000, 2)).tolist():
            assert path.rest(x) == least_over_every_segment(path, x), x


def test_rest_of_a_point_with_no_cell():
    """NaN and infinite coordinates fall back to the search over every segment."""
    path = Polyline([(0, 0), (0, 1), (1, 1)])
    assert path.rest([math.inf, 0.0]) == math.inf
    assert path.rest([math.nan, 0.0]) == math.inf  # no segment's value compares below inf
