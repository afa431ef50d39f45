"""Potential.specialize: the per-plan step functions give the potential's own φ, bit for bit.

The shaping wrapper evaluates a reference potential's step function instead of
``potential(ctx)`` on every step, so a step function that differs in the last bit would train
a different φ than the one the invariance checker checks (and change stored numbers). These
tests compare them on every progress value of real plans, along random rollouts.
"""

from __future__ import annotations

import gymnasium
import numpy as np
import pytest

import planshape
from planshape.baselines.heuristic import HeuristicPotential, HStarGeodesic
from planshape.baselines.plan_distance import PlanDistance
from planshape.errors import PotentialValueError
from planshape.shaping.potentials import Potential, ShapingContext, make_potential, potential_ids
from planshape.shaping.registration import task_spec
from planshape.shaping.wrapper import PotentialShaping

#: every registered potential has a step function (a time-dependent one's also takes t)
SPECIALIZED = tuple(potential_ids())
#: the time indices a time-dependent step function is compared at
TIMES = (0, 1, 7, 499)
#: these remember φ per grid cell, so they have a step function on grid models only
PER_CELL = (HeuristicPotential, HStarGeodesic)
#: (task, model, potentials): one plan per case, every potential shaped from it
CASES = [
    (task, model, SPECIALIZED)
    for task in ("planshape/Reach-v1", "planshape/Push-v1", "planshape/MazeReach-v1")
    for model in task_spec(task).models
] + [
    ("planshape/PushRandomized-v1", "grid", ("plan-distance", "plan-path")),
    ("planshape/MetaWorld-reach-v4", "stages", ("distance-varying", "plan-distance")),
]


def shaping_wrapper(env: gymnasium.Env) -> PotentialShaping:
    while not isinstance(env, PotentialShaping):
        env = env.env
    return env


def contexts(
    wrapper: PotentialShaping, obs: np.ndarray, times: tuple[int, ...] = (0,)
) -> list[ShapingContext]:
    """The context of ``obs`` at every progress value of the current plan (and time index)."""
    return [
        ShapingContext(
            obs=obs,
            progress=k,
            t=t,
            subgoals=wrapper.progress.subgoals,
            geometry=wrapper.geometry,
            abstraction=wrapper.progress.abstraction,
        )
        for k in range(len(wrapper.progress.subgoals))
        for t in times
    ]


@pytest.mark.parametrize(("task", "model", "potentials"), CASES)
def test_step_function_equals_the_potential_bit_for_bit(task, model, potentials):
    checked = 0
    for potential in potentials:
        try:
            env = gymnasium.make(
                task, reward="shaped", potential=potential, model=model, gamma=0.99
            )
        except planshape.errors.BadInputError:  # a potential this model cannot carry
            continue
        wrapper = shaping_wrapper(env)
        obs, _ = env.reset(seed=3)
        if wrapper._step_phi is None:
            per_cell = isinstance(wrapper.potential, PER_CELL)
            assert per_cell and not model.startswith("grid"), potential
            continue
        timed = wrapper.potential.time_dependent
        rng = np.random.default_rng(0)
        for step in range(80):
            for ctx in contexts(wrapper, obs, TIMES if timed else (0,)):
                fast = (
                    wrapper._step_phi(obs, ctx.progress, ctx.t)
                    if timed
                    else wrapper._step_phi(obs, ctx.progress)
                )
                slow = wrapper.potential.potential(ctx)
                assert type(fast) is float
                assert repr(fast) == repr(float(slow)), (potential, step, ctx.progress)
                checked += 1
            action = rng.uniform(-1, 1, env.action_space.shape)
            obs, _, terminated, truncated, _ = env.step(action)
            if terminated or truncated:
                obs, _ = env.reset()
    assert checked >= 160


@pytest.mark.parametrize(
    "potential", ["plan-distance", "plan-path", "distance-varying", "time-varying"]
)
def test_shaped_rewards_do_not_depend_on_the_fast_path(monkeypatch, potential):
    """The same rollout with and without step functions gives the same rewards, bit for bit."""

    def rollout() -> list[float]:
        env = gymnasium.make(
            "planshape/Push-v1", reward="shaped", potential=potential, model="grid", gamma=0.99
        )
        env.reset(seed=0)
        rng = np.random.default_rng(1)
        rewards = []
        for _ in range(200):
            _, reward, terminated, truncated, info = env.step(rng.uniform(-1, 1, 2))
            rewards += [reward, info["potential"]]
            if terminated or truncated:
                env.reset()
        return rewards

    fast = rollout()
    monkeypatch.setattr(Potential, "step_function", lambda self, ctx: None)
    assert [repr(r) for r in rollout()] == [repr(r) for r in fast]


def test_a_subclass_that_changes_phi_does_not_inherit_the_step_function():
    class Halved(PlanDistance):
        def potential(self, ctx):
            return super().potential(ctx) / 2

    env = gymnasium.make(
        "planshape/Reach-v1", reward="shaped", potential=Halved, model="grid", gamma=0.99
    )
    wrapper = shaping_wrapper(env)
    obs, info = env.reset(seed=0)
    assert wrapper._step_phi is None
    assert (
        info["potential"]
        == Halved()(contexts(wrapper, obs)[0])
        == PlanDistance()(contexts(wrapper, obs)[0]) / 2
    )


def test_a_time_dependent_potential_has_a_step_function_of_the_time_index_too():
    potential = make_potential("time-varying")
    ctx = ShapingContext(obs=None, progress=1, t=2, subgoals=(frozenset(),) * 3)
    assert potential.step_function(ctx)(None, 1, 2) == potential.potential(ctx) == 0.5 / 3


def test_a_bad_value_from_a_step_function_is_reported_by_the_potential():
    class Broken(Potential):
        def potential(self, ctx):
            return float("nan")

        def specialize(self, ctx):
            return lambda obs, progress: float("nan")

    env = gymnasium.make(
        "planshape/Reach-v1", reward="shaped", potential=Broken, model="grid", gamma=0.99
    )
    with pytest.raises(PotentialValueError, match="finite"):
        env.reset(seed=0)
