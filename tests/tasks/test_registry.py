"""Checks that every registered task passes, parametrized over the registry (``ids=`` the task
id): a new task is tested without writing a test.

* Gymnasium's and stable-baselines3's environment checkers, for every reward variant (shaped:
  every PDDL model, with the plan-based potential);
* the same seed gives the same trajectory;
* a model missing a classifier fails at binding, naming the predicate;
* unknown task ids, models and reward variants are refused with the valid ones listed.
"""

from __future__ import annotations

import dataclasses
import warnings

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env as gymnasium_check_env
from stable_baselines3.common.env_checker import check_env as sb3_check_env

import planshape  # noqa: F401  (registers the tasks)
from planshape.errors import BadInputError, RegistrationError, UnknownIdError
from planshape.shaping.registration import abstract_model, shape, task_ids, task_spec

GAMMA = 0.99
VARIANTS = [
    (task, variant)
    for task in task_ids()
    for variant in ["sparse", "dense", *(f"shaped:{m}" for m in task_spec(task).models)]
]


def make(task: str, variant: str) -> gymnasium.Env:
    if variant.startswith("shaped:"):
        model = variant.split(":", 1)[1]
        return gymnasium.make(task, reward="shaped", model=model, gamma=GAMMA)
    return gymnasium.make(task, reward=variant)


@pytest.mark.parametrize(("task", "variant"), VARIANTS, ids=[f"{t}-{v}" for t, v in VARIANTS])
def test_environment_checkers(task: str, variant: str) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # e.g. MetaWorld's unbounded object coordinates
        gymnasium_check_env(make(task, variant).unwrapped, skip_render_check=True)
        sb3_check_env(make(task, variant))


def rollout(env: gymnasium.Env, seed: int, steps: int = 30) -> tuple[list, list]:
    obs, _ = env.reset(seed=seed)
    env.action_space.seed(seed)
    observations, rewards = [obs], []
    for _ in range(steps):
        obs, reward, terminated, truncated, _ = env.step(env.action_space.sample())
        observations.append(obs)
        rewards.append(float(reward))
        if terminated or truncated:
            break
    return observations, rewards


def _same(a, b) -> bool:
    if isinstance(a, dict):
        return all(np.array_equal(a[k], b[k]) for k in a)
    return np.array_equal(a, b)


@pytest.mark.parametrize("task", task_ids(), ids=str)
def test_same_seed_same_trajectory(task: str) -> None:
    variant = f"shaped:{task_spec(task).default_model}"
    first, second = rollout(make(task, variant), 7), rollout(make(task, variant), 7)
    assert all(_same(a, b) for a, b in zip(first[0], second[0], strict=True))
    assert first[1] == second[1]


@pytest.mark.parametrize("task", task_ids(), ids=str)
def test_a_model_missing_a_classifier_names_the_predicate(task: str) -> None:
    model = abstract_model(task_spec(task))
    dropped = sorted(model.classifiers)[0]
    broken = dataclasses.replace(
        model, classifiers={k: v for k, v in model.classifiers.items() if k != dropped}
    )
    with pytest.raises(RegistrationError, match=rf"\['{dropped}'\].*no classifier"):
        shape(gymnasium.make(task), broken, "plan-based", gamma=GAMMA)


def test_unknown_ids_list_the_valid_ones() -> None:
    with pytest.raises(gymnasium.error.Error):
        gymnasium.make("planshape/Reech-v0")
    with pytest.raises(UnknownIdError, match="unknown task 'planshape/Reech-v0'.*Reach-v0"):
        task_spec("planshape/Reech-v0")
    with pytest.raises(UnknownIdError, match="unknown model 'gird'.*did you mean 'grid'"):
        gymnasium.make("planshape/Reach-v0", reward="shaped", model="gird", gamma=GAMMA)
    with pytest.raises(UnknownIdError, match="unknown reward variant 'dens'.*dense, shaped"):
        gymnasium.make("planshape/Reach-v0", reward="dens")
    with pytest.raises(UnknownIdError, match="unknown potential"):
        gymnasium.make("planshape/Reach-v0", reward="shaped", potential="nope", gamma=GAMMA)


def test_shaping_options_need_the_shaped_reward_and_a_gamma() -> None:
    with pytest.raises(BadInputError, match="needs gamma="):
        gymnasium.make("planshape/Reach-v0", reward="shaped")
    with pytest.raises(BadInputError, match="apply only with reward='shaped'"):
        gymnasium.make("planshape/Reach-v0", model="grid")


def test_planshape_tasks_lists_ids_models_predicates_and_rewards(capsys) -> None:
    import json

    from planshape.cli import main

    assert main(["tasks", "--json", "planshape/Push-v0"]) == 0
    (row,) = json.loads(capsys.readouterr().out)
    assert row["models"]["grid"]["predicates"] == ["object_at", "robot_at"]
    assert row["rewards"] == ["sparse", "dense", "shaped"]
    assert main(["tasks", "planshape/Nope-v0"]) == 2


MODELS = [(task, model) for task in task_ids() for model in task_spec(task).models]


@pytest.mark.parametrize(("task", "model"), MODELS, ids=[f"{t}-{m}" for t, m in MODELS])
def test_one_observation_classification_agrees_with_the_batch_path(task: str, model: str) -> None:
    """The shaping wrapper classifies one observation per step through ``holding`` (sparse,
    Python) and batches through arrays; both must give the same atoms on visited states."""
    env = make(task, f"shaped:{model}")
    observations, _ = rollout(env, seed=0, steps=60)
    # after the reset: a task-instance distribution binds the episode's instance's plan
    abstraction = env.get_wrapper_attr("progress").abstraction
    evaluator = abstraction.evaluator(abstraction.fluent_atoms)
    env.observation_space.seed(0)
    observations += [env.observation_space.sample() for _ in range(60)]
    for obs in observations:
        assert evaluator.holding(obs) == set(np.flatnonzero(evaluator(obs)).tolist())


def test_a_task_family_is_a_field_of_its_registration():
    """The family keys the hyperparameter tables; it is registered, not parsed from the id. For
    every task it is what the id's name gave before, so no run id changes."""
    from planshape.errors import RegistrationError
    from planshape.shaping.registration import TaskSpec, task_ids
    from planshape.training.hyperparams import family

    for task in task_ids():
        name = task.split("/", 1)[-1]
        assert family(task) == name.replace("_", "-").split("-", 1)[0], task
    with pytest.raises(RegistrationError, match="name its family"):
        TaskSpec(
            id="planshape/X-v0", env_entry_point="m:E", models={"a": "m:a"}, max_episode_steps=5
        )
