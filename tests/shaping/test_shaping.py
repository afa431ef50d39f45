"""Correctness rules 1–4 of potential-based shaping, checked on arbitrary trajectories."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planshape.baselines.paper import PlanBased, TimeVarying
from planshape.errors import BadInputError, PotentialError
from planshape.shaping.potentials import Potential, ShapingContext
from planshape.shaping.wrapper import PotentialShaping
from tests.toys import LineEnv, ScriptedEnv, line_progress


class StateAndProgress(Potential):
    """An arbitrary potential over (obs, progress): exercises rule 3 with state dependence."""

    def potential(self, ctx: ShapingContext) -> float:
        return 3.0 * ctx.progress + math.sin(7.0 * float(ctx.obs[0]))


class TimeIndexed(Potential):
    time_dependent = True

    def potential(self, ctx: ShapingContext) -> float:
        return (ctx.progress + 1.0) / (ctx.t + 2.0) - 0.1 * ctx.t


POTENTIALS = [PlanBased(), TimeVarying(scale=5.0), StateAndProgress(), TimeIndexed()]


@st.composite
def trajectories(draw):
    """A random trajectory: positions on the line, rewards and an ending (none, terminated,
    truncated, or both)."""
    length = draw(st.integers(1, 30))
    positions = draw(st.lists(st.floats(0.0, 1.0), min_size=length + 1, max_size=length + 1))
    rewards = draw(st.lists(st.floats(-1.0, 1.0), min_size=length, max_size=length))
    ending = draw(st.sampled_from(["none", "terminated", "truncated", "both"]))
    terminated = [False] * length
    truncated = [False] * length
    terminated[-1] = ending in ("terminated", "both")
    truncated[-1] = ending in ("truncated", "both")
    return positions, rewards, terminated, truncated


def run_episode(env: PotentialShaping, steps: int):
    _, info = env.reset(seed=0)
    phis, progresses, records = [info["potential"]], [info["progress"]], []
    for _ in range(steps):
        _, reward, terminated, truncated, info = env.step(0)
        records.append((reward, info, terminated, truncated))
        phis.append(info["potential"])
        progresses.append(info["progress"])
    return phis, progresses, records


@settings(max_examples=150, deadline=None)
@given(trajectory=trajectories(), potential=st.sampled_from(POTENTIALS), gamma=st.floats(0.5, 1.0))
def test_shaping_telescopes_and_zeroes_at_termination(trajectory, potential, gamma):
    positions, rewards, terminated, truncated = trajectory
    env = PotentialShaping(
        ScriptedEnv(positions, rewards, terminated, truncated),
        potential,
        line_progress(),
        gamma=gamma,
    )
    phis, progresses, records = run_episode(env, len(rewards))

    # Rule 3: Σ γ^t F_t = γ^T φ_T − φ_0 over the episode.
    discounted = sum(gamma**t * info["shaping"] for t, (_, info, _, _) in enumerate(records))
    steps = len(records)
    assert discounted == pytest.approx(gamma**steps * phis[-1] - phis[0], rel=1e-9, abs=1e-9)
    for t, (reward, info, _, _) in enumerate(records):
        # Each F uses the φ stored at the previous step, and the shaped reward is R + F.
        assert info["shaping"] == pytest.approx(gamma * phis[t + 1] - phis[t], abs=1e-12)
        assert reward == pytest.approx(info["reward_original"] + info["shaping"], abs=1e-12)
    # Rule 2: φ' = 0 after a termination; a truncation alone keeps φ'.
    if terminated[-1]:
        assert phis[-1] == 0.0
    elif truncated[-1]:
        ctx = ShapingContext(
            obs=np.array([positions[-1]]),
            progress=progresses[-1],
            t=steps,
            subgoals=env.progress.subgoals,
        )
        assert phis[-1] == pytest.approx(potential(ctx))
    # Progress never decreases.
    assert all(b >= a for a, b in itertools.pairwise(progresses))


@settings(max_examples=60, deadline=None)
@given(trajectory=trajectories())
def test_progress_and_time_reset_on_reset(trajectory):
    positions, rewards, terminated, truncated = trajectory
    env = PotentialShaping(
        ScriptedEnv(positions, rewards, terminated, truncated),
        TimeIndexed(),
        line_progress(),
        gamma=0.9,
    )
    first = run_episode(env, len(rewards))
    second = run_episode(env, len(rewards))
    # Rule 4: a second episode of the same script is an exact replay.
    assert first[0] == second[0] and first[1] == second[1]
    assert second[1][0] == env.progress.initial(np.array([positions[0]]))


def test_progress_reaches_goal_in_order_on_line_env():
    env = PotentialShaping(LineEnv(), PlanBased(), line_progress(), gamma=0.99)
    env.reset(seed=1)
    seen = []
    for _ in range(12):
        _, _, _, _, info = env.step(np.array([1.0]))
        seen.append(info["progress"])
    assert seen[-1] == 2 and seen == sorted(seen) and 1 in seen


def test_gamma_is_required_and_checked():
    with pytest.raises(TypeError, match="gamma"):
        PotentialShaping(LineEnv(), PlanBased(), line_progress())  # type: ignore[call-arg]
    for bad in (0.0, 1.5, float("nan"), "0.99", True):
        with pytest.raises(BadInputError, match="gamma"):
            PotentialShaping(LineEnv(), PlanBased(), line_progress(), gamma=bad)


class ReturnsNaN(Potential):
    def potential(self, ctx: ShapingContext) -> float:
        return float("nan")


def test_non_finite_potential_raises_naming_the_potential():
    env = PotentialShaping(LineEnv(), ReturnsNaN(), line_progress(), gamma=0.99)
    with pytest.raises(PotentialError, match="ReturnsNaN.*finite"):
        env.reset(seed=0)

    class Infinite(Potential):
        time_dependent = True

        def potential(self, ctx: ShapingContext) -> float:
            return float("inf") if ctx.t else 0.0

    env = PotentialShaping(LineEnv(), Infinite(), line_progress(), gamma=0.99)
    env.reset(seed=0)
    with pytest.raises(PotentialError, match="Infinite.*t=1"):
        env.step(np.array([1.0]))


def test_info_keys_on_every_step():
    env = PotentialShaping(LineEnv(), PlanBased(), line_progress(), gamma=0.99)
    _, info = env.reset(seed=0)
    assert {"potential", "progress"} <= set(info)
    _, _, _, _, info = env.step(np.array([1.0]))
    assert {"reward_original", "shaping", "potential", "progress", "success"} <= set(info)
