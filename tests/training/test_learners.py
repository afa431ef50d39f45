"""Learner backends: stable-baselines3 (PyTorch) and SBX (JAX) under one set of algorithm ids,
sharing the hyperparameter tables, reproducible, and never mixed in a leaderboard cell."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

import planshape  # noqa: F401  (registers the tasks)
from planshape.errors import UnknownIdError
from planshape.harness.machine import cpu_description
from planshape.harness.profiles import RunKey
from planshape.harness.runner import RunSpec, execute, make_learner
from planshape.training.hyperparams import hyperparameters
from planshape.training.learners import LEARNERS, learner

TASK = "planshape/Reach-v1"


@pytest.mark.parametrize("algo", sorted(LEARNERS))
def test_every_learner_builds_on_a_shaped_task_with_the_shared_table(algo: str) -> None:
    settings = hyperparameters(TASK, algo)
    assert settings == hyperparameters(TASK, learner(algo).table)
    model = make_learner(RunKey(TASK, "plan-based/grid", algo, 0, 64), settings)
    assert type(model).__module__.split(".")[0] == learner(algo).module
    assert model.gamma == settings["gamma"]


def test_an_unknown_algorithm_lists_the_known_ones() -> None:
    with pytest.raises(UnknownIdError, match="SBX-SAC"):
        hyperparameters(TASK, "SBX-SACC")


@pytest.mark.parametrize("algo", ["SBX-SAC", "SBX-PPO"])
def test_an_sbx_run_is_reproducible_and_records_its_backend(algo: str) -> None:
    budget = 1024 if algo == "SBX-PPO" else 256
    spec = RunSpec.create(RunKey(TASK, "plan-distance/grid", algo, 1, budget), "t", budget // 2, 1)
    first, second = execute(spec), execute(spec)
    keep = ("step", "success_rate", "final_distance", "sparse_return")
    assert [{k: r[k] for k in keep} for r in first] == [{k: r[k] for k in keep} for r in second]
    assert first[0]["packages"]["sbx-rl"] != "missing"
    assert first[0]["packages"]["jax"] != "missing"
    assert first[0]["algo"] == algo
    assert first[0]["cpu"] == cpu_description() != "unknown"  # its numbers depend on the CPU


def _memory_mappings() -> int:
    with open("/proc/self/maps") as maps:
        return sum(1 for _ in maps)


@pytest.mark.skipif(not Path("/proc/self/maps").exists(), reason="counts Linux memory mappings")
def test_runs_one_after_another_do_not_pile_up_compiled_code() -> None:
    """Every SBX run compiles its own functions (about 480 memory mappings for SBX-SAC, which
    the next run does not reuse); execute frees them after the run, so a benchmark worker's
    mappings stay flat instead of reaching vm.max_map_count (65,530) after some 130 runs.
    A run trained after the release has the numbers of the first."""
    spec = RunSpec.create(RunKey(TASK, "plan-distance/grid", "SBX-SAC", 1, 256), "t", 128, 1)
    spec = dataclasses.replace(
        spec, hyperparameters={**spec.hyperparameters, "learning_starts": 64}
    )
    first = execute(spec)  # with gradient steps: the update is compiled too
    before = _memory_mappings()
    again = [execute(spec) for _ in range(2)]
    assert _memory_mappings() - before < 300  # 2 × ~480 without the release
    keep = ("step", "success_rate", "final_distance", "sparse_return")
    assert all(
        [{k: r[k] for k in keep} for r in rows] == [{k: r[k] for k in keep} for r in first]
        for rows in again
    )


def test_backends_are_different_cells() -> None:
    from planshape.results.cells import summarize
    from tests.results.synthetic import make_run

    rows = make_run(algo="SAC", seed=0) + make_run(algo="SBX-SAC", seed=0)
    cells = {(r["task"], r["algo"], r["entry"]) for r in summarize(rows)}
    assert {algo for _, algo, _ in cells} == {"SAC", "SBX-SAC"}


def test_the_training_vecenv_skips_the_info_copy_without_changing_a_number(monkeypatch) -> None:
    """FreshInfoVecEnv drops DummyVecEnv's deep copy of the infos; a run trains to the very
    same numbers with either."""
    from stable_baselines3.common.vec_env import DummyVecEnv

    from planshape.training import algorithm

    spec = RunSpec.create(RunKey(TASK, "plan-distance/grid", "PPO", 2, 2048), "t", 1024, 1)
    fresh = execute(spec)
    monkeypatch.setattr(algorithm, "FreshInfoVecEnv", DummyVecEnv)
    copied = execute(spec)
    keep = ("step", "success_rate", "final_distance", "sparse_return")
    assert [{k: r[k] for k in keep} for r in fresh] == [{k: r[k] for k in keep} for r in copied]


def test_fresh_info_vecenv_reports_episode_ends_like_dummy_vecenv() -> None:
    from stable_baselines3.common.env_util import make_vec_env

    from planshape.training.algorithm import FreshInfoVecEnv

    venv = make_vec_env(TASK, n_envs=2, seed=0, vec_env_cls=FreshInfoVecEnv)
    venv.reset()
    for _ in range(50):  # Reach-v1 truncates at 50 steps
        _, _, dones, infos = venv.step(venv.action_space.sample()[None].repeat(2, 0))
    assert dones.all() and infos[0] is not infos[1]
    assert all(i["TimeLimit.truncated"] and "terminal_observation" in i for i in infos)
