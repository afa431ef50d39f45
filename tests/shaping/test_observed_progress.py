"""The learner observes plan progress (``observe_progress``): max_idx / n after the task's
observation, tracked by the same classifiers as the shaping, in training and in evaluation
alike, recorded in a shaped run's settings (so in its id) and nowhere else."""

from __future__ import annotations

import gymnasium
import numpy as np
import pytest

import planshape  # noqa: F401  (registers the tasks)
from planshape.errors import BadInputError
from planshape.harness.profiles import RunKey
from planshape.harness.runner import make_evaluation_env, make_learner
from planshape.shaping.observed_progress import ObservedProgress
from planshape.shaping.registration import instance_plan, observe_progress
from planshape.tasks.planar.oracle import ORACLES
from planshape.training.hyperparams import hyperparameters

GAMMA = 0.99
#: a fixed task and a distribution whose plans differ per instance, with a model of several steps
CASES = [("planshape/Reach-v1", "multi"), ("planshape/MazeReachRandomized-v1", "grid")]


def _shaped(task: str, model: str) -> gymnasium.Env:
    return gymnasium.make(task, reward="shaped", potential="plan-based", model=model, gamma=GAMMA)


@pytest.mark.parametrize(("task", "model"), CASES)
def test_the_appended_number_is_the_shapings_progress_over_n(task, model):
    """Along the task's oracle (:mod:`planshape.tasks.planar.oracle`), on a shaped environment
    the last number is the shaping wrapper's own ``info["progress"]`` divided by the plan's n at
    every step, and the rest is the task's observation unchanged; on the same task without
    shaping (the evaluation environment) the same actions give the same numbers: the wrapper
    tracks progress itself. Seeds 0-2 (a distribution draws another instance, with another
    plan, on each); the oracle walks every plan to its end."""
    for seed in range(3):
        inner = _shaped(task, model)
        shaped = observe_progress(inner, task, model)
        plain = observe_progress(gymnasium.make(task), task, model)
        obs, info = shaped.reset(seed=seed)
        bare, _ = plain.reset(seed=seed)
        base = inner.unwrapped
        oracle = ORACLES[base.task]
        final = inner.get_wrapper_attr("progress").final
        seen = [info["progress"]]
        for _ in range(60):
            assert obs[-1] == pytest.approx(info["progress"] / final)
            np.testing.assert_array_equal(obs, bare)
            action = oracle(obs[:-1], goal=base.goal, geometry=base.geometry)
            obs, _, terminated, truncated, info = shaped.step(action)
            bare, *_ = plain.step(action)
            seen.append(info["progress"])
            if terminated or truncated:
                break
        assert final >= 2 and seen[-1] == final, f"seed {seed}: progress {seen}"
        assert len(set(seen)) >= 3, f"seed {seed}: progress {seen}"
        assert shaped.observation_space.shape[0] == inner.observation_space.shape[0] + 1
        assert (shaped.observation_space.low[-1], shaped.observation_space.high[-1]) == (0, 1)


def test_a_distribution_switches_to_each_episodes_plan_on_reset():
    task = "planshape/MazeReachRandomized-v1"
    env = observe_progress(gymnasium.make(task), task, "grid")
    plans = set()
    for seed in range(4):
        _, info = env.reset(seed=seed)
        plans.add(id(env.progress))
        plan, _geometry = instance_plan(task, "grid", info["instance"])
        assert env.progress is plan
    assert len(plans) > 1


def test_a_non_box_observation_is_a_clear_error():
    with pytest.raises(BadInputError, match="Taxi-v4.*not a flat Box.*observe_progress"):
        ObservedProgress(gymnasium.make("Taxi-v4"), progress=None)  # type: ignore[arg-type]


def test_only_a_shaped_entry_records_the_setting():
    task = "planshape/MetaWorld-button-press-v3"
    shaped = hyperparameters(task, "SBX-SAC", "plan-distance-sum/stages", observe_progress=True)
    assert shaped["observe_progress"] is True
    for entry in ("sparse", "dense"):
        assert hyperparameters(task, "SBX-SAC", entry, observe_progress=True) == hyperparameters(
            task, "SBX-SAC", entry
        )
    assert "observe_progress" not in hyperparameters(task, "SBX-SAC", "plan-distance-sum/stages")


@pytest.mark.parametrize(
    ("task", "algo"),
    [("planshape/MazeReach-v1", "PPO"), ("planshape/MetaWorld-reach-v4", "SBX-SAC")],
)
def test_training_and_evaluation_see_the_progress_alike(task, algo):
    """The learner's observation space is the evaluation environment's, one number longer than
    without the setting; on a planar task the rescaled view maps progress 0 to −1."""
    key = RunKey(task, "plan-based/" + ("grid" if "Maze" in task else "stages"), algo, 0, 64)
    settings = hyperparameters(task, algo, key.entry, observe_progress=True)
    without = hyperparameters(task, algo, key.entry)
    learner = make_learner(key, settings)
    evaluation = make_evaluation_env(key, settings)
    assert learner.observation_space == evaluation.observation_space
    assert evaluation.observation_space.shape[0] == (
        make_evaluation_env(key, without).observation_space.shape[0] + 1
    )
    obs, _ = evaluation.reset(seed=0)
    assert obs[-1] == (-1.0 if settings.get("rescale_observations") else 0.0)
    assert learner.get_env().reset()[0][-1] == obs[-1]


def test_the_probe_refuses_the_option_without_a_plan(capsys):
    from planshape.cli import main

    code = main(
        ["probe", "reach", "dense", "--budget", "64", "--chunks", "1", "--observe-progress"]
    )
    assert code == 2
    assert "--observe-progress shows a plan's progress; entry 'dense' has no plan" in (
        capsys.readouterr().err
    )


def test_the_probe_refuses_the_option_on_a_dict_observation(capsys):
    from planshape.cli import main

    code = main(
        [
            "probe",
            "planshape/FetchReach-v4",
            "plan-distance/stages",
            "--algo",
            "SBX-SAC",
            "--budget",
            "64",
            "--chunks",
            "1",
            "--observe-progress",
        ]
    )
    assert code == 2
    err = capsys.readouterr().err
    assert "planshape/FetchReach-v4 has observation space Dict" in err
    assert "train this task without observe_progress" in err
    assert "Traceback" not in err
