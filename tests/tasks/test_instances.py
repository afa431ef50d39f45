"""Task-instance distributions of the planar tasks: the instance sets, the environments that
draw from them, the per-instance plans the shaping wrapper switches between, and the scripted
experts on the held-out instances."""

from __future__ import annotations

import itertools
import json
import math
import warnings

import gymnasium
import numpy as np
import pytest

import planshape  # noqa: F401  (registers the tasks)
from planshape.cli import main
from planshape.errors import BadInputError
from planshape.shaping.registration import task_spec
from planshape.tasks.planar import PushEnv, ReachEnv, run_oracle
from planshape.tasks.planar.geometry import PAPER_GEOMETRY as G
from planshape.tasks.planar.instances import EVAL_SIZE, TRAIN_SIZE, Instance, instance_set
from planshape.tasks.planar.oracle import segment_clear, walk_plan
from planshape.tasks.planar.paper_models import PUSH_CELL

RANDOMIZED = {
    "reach": "planshape/ReachRandomized-v1",
    "push": "planshape/PushRandomized-v1",
    "maze-reach": "planshape/MazeReachRandomized-v1",
}
GAMMA = 0.99


# ---- the instance sets -------------------------------------------------------------------------


@pytest.mark.parametrize("task", RANDOMIZED)
def test_sets_are_fixed_disjoint_and_of_their_sizes(task: str) -> None:
    sets = instance_set(task)
    assert (len(sets.train), len(sets.eval)) == (TRAIN_SIZE, EVAL_SIZE) and EVAL_SIZE >= 32
    assert not set(sets.train) & set(sets.eval)
    assert len(set(sets.train)) == TRAIN_SIZE and len(set(sets.eval)) == EVAL_SIZE
    instance_set.cache_clear()  # drawn again from the seeds: the same instances
    assert instance_set(task) == sets


def test_the_sets_are_pinned() -> None:
    """The first instances of each set, as drawn on the machine that wrote this test: a change
    of the generator (or of numpy's) changes every stored run of the distributions."""
    assert instance_set("reach").eval[0] == Instance((0.511, 0.0407), (0.3861, 0.2754))
    assert instance_set("push").eval[0] == Instance(
        (0.6721, -0.0804), (0.632, 0.078), (0.407, 0.153)
    )
    assert instance_set("maze-reach").eval[0].goal == (0.5304, -0.0155)


@pytest.mark.parametrize("task", RANDOMIZED)
def test_every_instance_needs_what_the_fixed_task_needs(task: str) -> None:
    sets = instance_set(task)
    for instance in sets.train + sets.eval:
        if task == "push":
            travel = np.subtract(instance.goal, instance.box_start) / PUSH_CELL
            assert np.allclose(travel, np.round(travel), atol=1e-3)  # whole cells
            assert math.hypot(*np.round(travel)) >= 2  # the object must travel
            assert math.dist(instance.ee_start, instance.box_start) > G.contact_distance
        else:
            walls = G.reach_walls if task == "reach" else G.maze_walls
            # the straight way is blocked: the detour is needed
            assert not segment_clear(instance.ee_start, instance.goal, walls, G.ee_radius)
            assert all(w.distance(instance.ee_start) > G.ee_radius for w in walls)


# ---- the environments --------------------------------------------------------------------------


@pytest.mark.parametrize("task", RANDOMIZED)
def test_the_goal_is_observed_and_the_episode_is_an_instance(task: str) -> None:
    env = gymnasium.make(RANDOMIZED[task])
    obs, info = env.reset(seed=3)
    instance = info["instance"]
    assert instance in instance_set(task).train  # trains on the training set by default
    assert isinstance(env.observation_space, gymnasium.spaces.Box)
    assert env.observation_space.shape == (6,) if task == "push" else (4,)
    np.testing.assert_allclose(obs[-2:], instance.goal, atol=1e-6)
    np.testing.assert_allclose(obs[:2], instance.ee_start, atol=1e-6)
    seen = {env.reset(seed=s)[1]["instance"] for s in range(30)}
    assert len(seen) > 10  # every reset draws one


def test_reset_options_choose_a_held_out_instance() -> None:
    env = gymnasium.make(RANDOMIZED["push"], instances="eval")
    obs, info = env.reset(options={"instance": 7})
    assert info["instance"] == instance_set("push").eval[7]
    np.testing.assert_allclose(obs[2:4], info["instance"].box_start, atol=1e-6)
    with pytest.raises(BadInputError, match=r"index in \[0, 50\)"):
        env.reset(options={"instance": 50})
    with pytest.raises(BadInputError, match="needs instances="):
        ReachEnv(version="v1").reset(options={"instance": 0})


def test_planshape_tasks_reports_the_instances(capsys) -> None:
    assert main(["tasks", "--json", RANDOMIZED["reach"], "planshape/Reach-v1"]) == 0
    rows = {row["id"]: row for row in json.loads(capsys.readouterr().out)}
    assert rows[RANDOMIZED["reach"]]["instances"] == {"train": TRAIN_SIZE, "eval": EVAL_SIZE}
    assert rows["planshape/Reach-v1"]["instances"] is None


# ---- the scripted experts on the held-out instances --------------------------------------------


@pytest.mark.parametrize("task", RANDOMIZED)
def test_the_oracle_solves_the_held_out_instances_within_the_horizon(task: str) -> None:
    env = gymnasium.make(RANDOMIZED[task], instances="eval")
    solved = [
        run_oracle(env, 10_000, options={"instance": k}).final_success for k in range(EVAL_SIZE)
    ]
    assert sum(solved) >= 0.95 * EVAL_SIZE


CASES = [(t, m) for t in RANDOMIZED.values() for m in task_spec(t).models]


@pytest.mark.parametrize(("task", "model"), CASES, ids=[f"{t}:{m}" for t, m in CASES])
def test_walking_each_instances_plan_reaches_success_in_order(task: str, model: str) -> None:
    """On a sample of held-out instances, the scripted controller walks each instance's own plan
    through the classifiers to the task's success, with progress reaching the plan's end in
    order (all 50 instances of every model pass: see the closing note of the change)."""
    env = gymnasium.make(
        task, reward="shaped", model=model, gamma=GAMMA, instances="eval", max_episode_steps=400
    )
    for k in (0, 17, 33):
        progress, success = walk_plan(env, 400, options={"instance": k})
        final = env.get_wrapper_attr("progress").final
        assert success and progress[-1] == final, f"instance {k}: {progress[-1]}/{final}"
        assert all(b >= a for a, b in itertools.pairwise(progress))
        assert set(range(progress[0], final + 1)) <= set(progress)


# ---- shaping per instance ----------------------------------------------------------------------


@pytest.mark.parametrize("potential", ["plan-based", "plan-distance", "distance-varying"])
def test_each_episode_is_shaped_with_its_instances_plan_and_telescopes(potential: str) -> None:
    """The plan switches only on reset (to that instance's), and over every episode
    Σ γ^t F_t = γ^T φ_T − φ_0 exactly (correctness rule 3)."""
    env = gymnasium.make(
        RANDOMIZED["push"], reward="shaped", potential=potential, model="grid", gamma=GAMMA
    )
    rng = np.random.default_rng(0)
    plans = []
    for episode in range(3):
        _, info = env.reset(seed=episode)
        progress = env.get_wrapper_attr("progress")
        plans.append(progress)
        phi0, total, discount = info["potential"], 0.0, 1.0
        for _ in range(30):
            _, _, terminated, truncated, step = env.step(rng.uniform(-1, 1, 2).astype(np.float32))
            assert env.get_wrapper_attr("progress") is progress  # never switched mid-episode
            total += discount * step["shaping"]
            discount *= GAMMA
            if terminated or truncated:
                break
        assert total == pytest.approx(discount * step["potential"] - phi0, abs=1e-12)
    assert len({id(p) for p in plans}) == 3  # three instances, three plans
    goals = [p.subgoals[-1] for p in plans]
    assert len(set(goals)) == 3  # each plan ends at its own instance's goal


def test_a_distribution_without_an_instance_in_info_is_refused() -> None:
    from planshape.shaping.registration import shape_instances

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        env = shape_instances(
            PushEnv(version="v1"), RANDOMIZED["push"], "grid", "plan-based", gamma=GAMMA
        )
    with pytest.raises(BadInputError, match="info\\['instance'\\]"):
        env.reset(seed=0)
