"""The shaping wrapper inside stable-baselines3 VecEnvs, and the γ pairing check (rule 1)."""

from __future__ import annotations

import numpy as np
import pytest
from stable_baselines3 import PPO
from stable_baselines3.common.vec_env import DummyVecEnv

from planshape.baselines.paper import PlanBased
from planshape.errors import GammaMismatchError
from planshape.shaping.wrapper import PotentialShaping
from planshape.training.algorithm import check_gamma, make_algorithm, shaping_gammas
from tests.toys import LineEnv, line_progress


def shaped_line(gamma: float = 0.95):
    return PotentialShaping(LineEnv(), PlanBased(), line_progress(), gamma=gamma)


def test_learner_with_a_different_gamma_is_refused():
    venv = DummyVecEnv([shaped_line, shaped_line])
    with pytest.raises(GammaMismatchError, match=r"gamma=0\.95.*gamma=0\.99"):
        make_algorithm(PPO, venv, gamma=0.99, n_steps=16, batch_size=16)
    with pytest.raises(GammaMismatchError):
        check_gamma(0.9, shaped_line())


def test_learner_takes_the_shaping_gamma_and_trains_inside_a_vecenv():
    venv = DummyVecEnv([shaped_line, shaped_line])
    assert shaping_gammas(venv) == [0.95, 0.95]
    model = make_algorithm(PPO, venv, n_steps=16, batch_size=16, n_epochs=1, seed=0)
    assert model.gamma == 0.95
    model.learn(64)
    # the wrapper sits inside the VecEnv, so info carries the shaping terms per environment
    venv.reset()
    _, _, _, infos = venv.step(np.ones((2, 1), dtype=np.float32))
    assert all({"shaping", "progress", "reward_original"} <= set(i) for i in infos)


def test_unshaped_env_has_no_shaping_gamma():
    assert shaping_gammas(LineEnv()) == []
    check_gamma(0.5, LineEnv())  # nothing to check against
