"""End to end on the line toy task: real Fast Downward plan, real classifiers, shaped reward
equal to a hand computation."""

from __future__ import annotations

import numpy as np
import pytest

from planshape.baselines.paper import PlanBased, TimeVarying
from planshape.shaping.registration import AbstractModel, shape
from tests.toys import LineEnv, at, write_line_model


@pytest.fixture
def line_model(tmp_path) -> AbstractModel:
    domain, problem = write_line_model(tmp_path)
    return AbstractModel(domain=domain, problem=problem, classifiers={"at": at})


def test_real_plan_gives_the_expected_subgoals(line_model):
    env = shape(LineEnv(), line_model, "plan-based", gamma=0.9)
    subgoals = env.get_wrapper_attr("progress").subgoals
    fluents = [sorted(a for a in s if a[0] == "at") for s in subgoals]
    assert fluents == [[("at", "left")], [("at", "middle")], [("at", "right")]]


@pytest.mark.parametrize("terminate", [False, True])
def test_shaped_reward_equals_hand_computation(line_model, terminate):
    gamma = 0.9
    env = shape(LineEnv(terminate_on_success=terminate), line_model, PlanBased(), gamma=gamma)
    env.reset(seed=0)
    # x goes 0.1, 0.2, ... with action +1. at(middle) holds from x = 0.35 (|x-0.5| <= 0.15),
    # at(right) from x = 0.85. φ = progress / 2.
    expected_progress = [0, 0, 0, 1, 1, 1, 1, 1, 2]
    phi_prev = 0.0
    for k, progress in enumerate(expected_progress, start=1):
        _, reward, terminated, _, info = env.step(np.array([1.0]))
        x = 0.1 * k
        success = abs(x - 1.0) <= 0.15
        phi = 0.0 if (terminate and success) else progress / 2
        assert info["progress"] == progress
        assert terminated == (terminate and success)
        assert reward == pytest.approx(float(success) + gamma * phi - phi_prev, abs=1e-12)
        phi_prev = phi


def test_time_varying_by_hand(line_model):
    gamma = 0.95
    env = shape(LineEnv(), line_model, TimeVarying(), gamma=gamma)
    env.reset(seed=0)
    rewards = [env.step(np.array([1.0]))[1] for _ in range(4)]
    # progress reaches 1 at step 4 (x = 0.4): φ_4 = (1/2) / (4 + 1); φ_0..φ_3 = 0
    assert rewards[:3] == [0.0, 0.0, 0.0]
    assert rewards[3] == pytest.approx(gamma * 0.5 / 5)
