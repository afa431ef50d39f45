"""The planar tasks' PDDL models agree with their environments.

For every task and model granularity, a controller that walks the plan's subgoal locations
(asking the task's ``locate`` hook, stepping through the real shaping wrapper) reaches task
success, and plan progress reaches the end of the plan in order.
"""

from __future__ import annotations

import itertools

import gymnasium
import numpy as np
import pytest

import planshape  # noqa: F401  (registers the tasks)
from planshape.shaping.registration import task_spec
from planshape.tasks.planar.oracle import walk_plan

PLANAR = [
    f"planshape/{name}-v{version}" for version in (0, 1) for name in ("Reach", "Push", "MazeReach")
]
CASES = [(task, model) for task in PLANAR for model in task_spec(task).models]


@pytest.mark.parametrize(("task", "model"), CASES, ids=[f"{t}:{m}" for t, m in CASES])
def test_walking_the_plan_reaches_success_with_progress_in_order(task, model):
    env = gymnasium.make(task, reward="shaped", model=model, gamma=0.99, max_episode_steps=300)
    progress, success = walk_plan(env, 300)
    final = env.get_wrapper_attr("progress").final
    assert success, f"{task} {model}: the plan's locations do not lead to success"
    assert progress[-1] == final, f"{task} {model}: progress stopped at {progress[-1]}/{final}"
    assert all(b >= a for a, b in itertools.pairwise(progress))
    # In order: every subgoal index was the furthest reached at some step.
    assert set(range(progress[0], final + 1)) <= set(progress)


@pytest.mark.parametrize("task", PLANAR)
def test_shaped_reward_matches_hand_computation(task):
    """R + γφ(s') − φ(s) with the plan-based φ = max_idx / n, on a real rollout."""
    gamma = 0.9
    env = gymnasium.make(task, reward="shaped", model="multi", gamma=gamma)
    sparse = gymnasium.make(task)
    _, info = env.reset(seed=3)
    sparse.reset(seed=3)
    final = env.get_wrapper_attr("progress").final
    phi_prev = info["progress"] / final
    rng = np.random.default_rng(0)
    for _ in range(15):
        action = rng.uniform(-1, 1, 2).astype(np.float32)
        _, reward, _, _, info = env.step(action)
        _, sparse_reward, _, _, _ = sparse.step(action)
        phi = info["progress"] / final
        assert reward == pytest.approx(sparse_reward + gamma * phi - phi_prev, abs=1e-12)
        phi_prev = phi


def test_maze_grid_plan_goes_around_the_walls():
    env = gymnasium.make("planshape/MazeReach-v0", reward="shaped", model="grid", gamma=0.99)
    env.reset(seed=0)
    geometry = env.get_wrapper_attr("geometry")
    subgoals = env.get_wrapper_attr("progress").subgoals
    ys = [float(geometry.locate(s)["ee"][1]) for s in subgoals]
    # the plan climbs above the walls' tops (y = 0.15) before it comes down to the goal
    assert max(ys) > 0.15 and ys[-1] == pytest.approx(0.0)


def test_push_diagonal_grid_slides_the_box_and_shortens_the_plan():
    """grid-diagonal adds 8-adjacent moves and pushes that slide the box one cell sideways;
    its plan pushes the box 6 times instead of 9 and never walks around it."""
    from planshape.tasks.planar.abstract import Grid, push_grid_problem
    from planshape.tasks.planar.geometry import GEOMETRY as G

    grid = Grid(G.box_goal)
    plain = push_grid_problem(grid, G.ee_start, G.box_start)
    diagonal = push_grid_problem(grid, G.ee_start, G.box_start, diagonal=True)
    # the end effector in cell (9, 2) pushes the box in (8, 2), its start: up, up-left, up-right
    assert "(push_line cell_9_2 cell_8_2 cell_7_2 cell_8_2)" in plain
    assert "cell_9_2 cell_8_2 cell_7_1" not in plain
    for line in ("cell_7_2 cell_8_2", "cell_7_1 cell_8_1", "cell_7_3 cell_8_3"):
        assert f"(push_line cell_9_2 cell_8_2 {line})" in diagonal
    assert "(neighbors cell_10_2 cell_9_3)" in diagonal
    assert "(neighbors cell_10_2 cell_9_3)" not in plain

    lengths, pushes = {}, {}
    for model in ("grid", "grid-diagonal"):
        env = gymnasium.make("planshape/Push-v0", reward="shaped", model=model, gamma=0.99)
        env.reset(seed=0)
        geometry = env.get_wrapper_attr("geometry")
        subgoals = env.get_wrapper_attr("progress").subgoals
        boxes = [tuple(geometry.locate(s)["box"]) for s in subgoals]
        lengths[model] = len(subgoals) - 1
        pushes[model] = sum(a != b for a, b in itertools.pairwise(boxes))
    assert lengths == {"grid": 16, "grid-diagonal": 9}
    assert pushes == {"grid": 9, "grid-diagonal": 6}


@pytest.mark.parametrize("factory", ["reach_grid", "maze_reach_grid", "push_grid"])
def test_grid_cells_tile_the_plane_even_on_their_edges(factory: str) -> None:
    """Every float32 point near a cell edge is in exactly one cell, on the batch path and on
    the one-observation path (two cells at once once made the h* state space explode)."""
    from planshape.tasks.planar import abstract

    model = getattr(abstract, factory)()
    places = model.classifiers["robot_at"].fn.places[0]
    xy = places._xy
    edges_x = (np.unique(xy[:, 0])[:-1] + np.unique(xy[:, 0])[1:]) / 2
    edges_y = (np.unique(xy[:, 1])[:-1] + np.unique(xy[:, 1])[1:]) / 2

    def around(edges: np.ndarray) -> list[np.float32]:
        values = []
        for edge in edges:
            for direction in (-1.0, 1.0):
                step = np.float32(edge)
                for _ in range(3):
                    values.append(step)
                    step = np.nextafter(step, np.float32(direction), dtype=np.float32)
        return values

    inside_x = np.float32(xy[len(xy) // 2, 0])
    inside_y = np.float32(xy[len(xy) // 2, 1])
    points = [(v, inside_y) for v in around(edges_x)] + [(inside_x, v) for v in around(edges_y)]
    every = np.arange(len(xy))
    for x, y in points:
        hits = places.contains(np.array([x, y], np.float32), every)
        assert hits.sum() == 1, (x, y)
        assert places.containing(float(x), float(y)) == np.flatnonzero(hits).tolist()


@pytest.mark.parametrize("task", ["planshape/Push-v1", "planshape/MazeReach-v1"])
def test_remembered_cell_answers_agree_with_the_batch_path(task: str) -> None:
    """Grid classifiers have a key (the entity's cell); the evaluators remember each answer by
    it. On random observations, in and beyond the grid, asked twice, the remembered answers and
    progress equal those of the batch path."""
    env = gymnasium.make(task, reward="shaped", model="grid", gamma=0.99)
    progress = env.get_wrapper_attr("progress")
    evaluator = progress._evaluate
    assert evaluator._keys is not None  # the grid model's classifiers are keyed
    rng = np.random.default_rng(0)
    space = env.observation_space
    observations = rng.uniform(space.low - 0.05, space.high + 0.05, (3000, *space.shape))
    batch = progress.furthest(observations.astype(np.float32))
    for _ in range(2):
        for obs, furthest in zip(observations.astype(np.float32), batch, strict=True):
            assert evaluator.holding(obs) == set(np.flatnonzero(evaluator(obs)).tolist())
            floor = int(rng.integers(0, progress.final + 1))
            assert progress.advance(floor, obs) == max(floor, int(furthest))


GRID_TASKS = [t for t in PLANAR if "grid" in task_spec(t).models]


@pytest.mark.parametrize("task", GRID_TASKS)
def test_keys_from_one_conversion_of_the_observation_are_each_classifiers_key(task: str):
    """The grid classifiers key an observation from one ``tolist()`` for all entities
    (``key_of_values``); that key is each classifier's own ``key(obs)``, for float32 and
    float64 observations, on cell boundaries too (where a wrong coordinate or rounding would
    show), and the evaluators use it."""
    env = gymnasium.make(task, reward="shaped", model="grid", gamma=0.99)
    progress = env.get_wrapper_attr("progress")
    evaluator = progress._evaluate
    assert evaluator._key_of_values is not None
    classifiers = list(progress.abstraction.classifiers.values())
    lattice = classifiers[0].fn.places[0]._finder
    space = env.observation_space
    rng = np.random.default_rng(2)
    observations = rng.uniform(space.low - 0.05, space.high + 0.05, (2000, *space.shape))
    origin = np.resize(lattice.origin, space.shape)  # (x0, y0) under every entity's (x, y)
    cells = np.round((observations - origin) / lattice.pitch)
    on_boundaries = origin + (cells + 0.5) * lattice.pitch  # halfway between two cells' centres
    for obs in [*observations, *on_boundaries]:
        for typed in (obs.astype(np.float32), obs):
            values = typed.tolist()
            for classifier in classifiers:
                assert classifier.key_of_values(values) == classifier.key(typed)
            assert evaluator.key(typed) == evaluator._key_per_classifier(typed)


@pytest.mark.parametrize(
    "task", ["planshape/Reach-v1", "planshape/Push-v1", "planshape/MazeReach-v1"]
)
@pytest.mark.parametrize("model", ["single", "multi"])
def test_hashed_region_answers_agree_with_the_batch_path(task: str, model: str) -> None:
    """The waypoint models' one-observation path hashes every table's discs into one set of
    buckets (InPlace._hashed_for). Around every region's rim (where a bucket or a test could
    be off by one), at its centre and anywhere in the workspace, it answers what the batch
    path answers, for every evaluator of the model (progress and full abstract states)."""
    env = gymnasium.make(task, reward="shaped", model=model, gamma=0.99)
    progress = env.get_wrapper_attr("progress")
    abstraction = progress.abstraction
    evaluators = [progress._evaluate, abstraction.evaluator(list(abstraction.fluent_atoms))]
    space = env.observation_space
    rng = np.random.default_rng(1)
    observations = list(rng.uniform(space.low - 0.05, space.high + 0.05, (500, *space.shape)))
    rim_inside = 0  # observations whose entities are strictly inside a region
    in_place = next(iter(abstraction.classifiers.values())).fn
    tables = in_place.places
    for table in tables:
        regions = [*table.centres.values(), *(p for ps in table.alternatives.values() for p in ps)]
        for cx, cy in regions:
            for angle in rng.uniform(0, 2 * np.pi, 12):
                for radius in (0.0, 0.97 * table.size, table.size, 1.03 * table.size):
                    obs = rng.uniform(space.low, space.high).astype(np.float64)
                    for slot in (slice(0, 2), slice(2, 4))[: len(obs) // 2]:
                        obs[slot] = (cx + radius * np.cos(angle), cy + radius * np.sin(angle))
                    observations.append(obs)
                    rim_inside += radius < 0.99 * table.size
    inside = 0
    for obs in np.asarray(observations, np.float32):
        for evaluator in evaluators:
            held = evaluator.holding(obs)
            assert held == set(np.flatnonzero(evaluator(obs)).tolist()), obs
        inside += bool(held)
    assert inside >= rim_inside  # the regions were entered, not only missed
