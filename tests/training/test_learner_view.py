"""The learner's view of the observation (``rescale_observations``): an affine map of the Box
bounds onto [-1, 1], applied outside the shaping, identically in training and evaluation."""

from __future__ import annotations

import gymnasium
import numpy as np
import pytest

import planshape  # noqa: F401  (registers the tasks)
from planshape.errors import BadInputError
from planshape.harness.profiles import PLANAR, RunKey
from planshape.harness.runner import make_evaluation_env, make_learner, rescaled
from planshape.shaping.registration import task_spec
from planshape.training.hyperparams import TABLE, hyperparameters

ACTIONS = [np.array(a, np.float32) for a in ([1.0, 1.0], [-0.5, 1.0], [0.3, -1.0], [1.0, 0.2])]


def affine(raw: np.ndarray, space: gymnasium.spaces.Box) -> np.ndarray:
    return 2.0 * (raw - space.low) / (space.high - space.low) - 1.0


@pytest.mark.parametrize("task", PLANAR)
def test_the_view_is_the_affine_image_and_the_shaping_still_reads_metres(task):
    def rollout(wrap: bool) -> list[tuple[np.ndarray, float, float]]:
        env = gymnasium.make(
            task, reward="shaped", potential="plan-distance", model="grid", gamma=0.99
        )
        raw_space = env.observation_space
        if wrap:
            env = rescaled(env)
        obs, _ = env.reset(seed=3)
        steps = [(obs, 0.0, 0.0)]
        for action in ACTIONS:
            obs, reward, _, _, info = env.step(action)
            steps.append((obs, reward, info["potential"]))
        return steps, raw_space

    raw, space = rollout(wrap=False)
    viewed, _ = rollout(wrap=True)
    for (raw_obs, raw_reward, raw_phi), (obs, reward, phi) in zip(raw, viewed, strict=True):
        np.testing.assert_allclose(obs, affine(raw_obs, space), atol=1e-6)
        assert (reward, phi) == (raw_reward, raw_phi)  # the shaping saw the same metres
        assert np.all(np.abs(obs) <= 1.0 + 1e-6)


def test_training_and_evaluation_see_the_same_view():
    key = RunKey("planshape/MazeReach-v0", "h-star-geodesic/grid", "PPO", 0, 1024)
    settings = hyperparameters(key.task, key.algo)
    assert settings["rescale_observations"] is True
    learner = make_learner(key, settings)
    evaluation = make_evaluation_env(key, settings)
    assert learner.observation_space == evaluation.observation_space
    np.testing.assert_array_equal(learner.observation_space.low, [-1.0, -1.0])
    obs, _ = evaluation.reset(seed=0)
    start = np.array([0.45, -0.32])  # maze-reach's start in metres
    raw_space = gymnasium.make(key.task).observation_space
    np.testing.assert_allclose(obs, affine(start, raw_space), atol=1e-6)
    raw = make_evaluation_env(key, {**settings, "rescale_observations": False})
    np.testing.assert_allclose(raw.reset(seed=0)[0], start, atol=1e-6)


def test_every_table_that_rescales_has_bounded_observations():
    checked = 0
    for (family, _algo), settings in TABLE.items():
        if not settings.rescale_observations:
            continue
        for task in PLANAR:
            if task_spec(task).id.split("/")[1].startswith(family):
                rescaled(gymnasium.make(task))
                checked += 1
    assert checked >= 6  # PPO and SAC on reach, push, maze-reach


def test_an_unbounded_observation_space_is_a_clear_error():
    with pytest.raises(BadInputError, match="CartPole-v1.*finite bounds.*rescale_observations"):
        rescaled(gymnasium.make("CartPole-v1"))
