"""The augmented MDP and the shaping term reproduce the shaping wrapper exactly."""

from __future__ import annotations

import math

import gymnasium
import numpy as np
import pytest

from planshape.errors import BadInputError, PotentialValueError
from planshape.invariance.shaped import PotentialBased, Step
from planshape.invariance.solve import value_iteration
from planshape.invariance.toys import make_toy
from planshape.shaping.potentials import Potential, ShapingContext, make_potential
from planshape.shaping.wrapper import PotentialShaping
from tests.invariance.tabular import TabularEnv, entry_index


@pytest.mark.parametrize("potential", ["plan-based", "time-varying", "distance-varying"])
@pytest.mark.parametrize("toy_name", ["reach-episodic", "maze-reach", "push", "random-episodic"])
def test_shaping_term_equals_the_wrapper_step_by_step(toy_name, potential):
    """Drive the real PotentialShaping wrapper through random episodes of the toy and compare
    every step's F, progress and φ with the checker's transition-level values."""
    toy = make_toy(toy_name)
    aug, mdp = toy.augmented, toy.mdp
    gamma, horizon = toy.gamma, toy.horizon
    shaping = PotentialBased(potential)
    rng = np.random.default_rng(0)
    steps = 0
    for episode in range(6):
        start = int(rng.choice(np.flatnonzero(~mdp.terminal)))
        env = TabularEnv(mdp, start, seed=episode)
        wrapper = PotentialShaping(
            env, make_potential(potential), toy.progress, gamma=gamma, geometry=toy.geometry
        )
        _, info = wrapper.reset()
        p = int(aug.reset_progress[start])
        assert info["progress"] == p
        x = p * mdp.n_states + start
        dynamic = shaping.time_dependent(aug, horizon)
        assert info["potential"] == pytest.approx(shaping.values(aug, 0, dynamic)[x])
        for t in range(horizon):
            action = int(rng.integers(mdp.n_actions))
            _, reward, terminated, _, info = wrapper.step(action)
            s2 = env.state
            x2 = info["progress"] * mdp.n_states + s2
            k = entry_index(aug.mdp, x * mdp.n_actions + action, x2)  # the transition exists
            bonus = shaping.transition_bonus(aug, Step(t, t + 1, gamma, horizon))
            assert info["shaping"] == pytest.approx(bonus[k], abs=1e-12)
            assert reward == pytest.approx(aug.mdp.rewards[k] + bonus[k], abs=1e-12)
            steps += 1
            if terminated:
                assert info["potential"] == 0.0
                break
            x = x2
    assert steps > 20


def test_augmentation_matches_per_state_progress_tracking():
    toy = make_toy("push")
    aug, progress = toy.augmented, toy.progress
    obs = toy.mdp.observations
    rng = np.random.default_rng(1)
    for k in rng.choice(aug.mdp.transitions.nnz, 200, replace=False):
        x, x2 = int(aug.entry_states[k]), int(aug.entry_next[k])
        s2 = int(aug.state[x2])
        assert aug.plan_progress[x2] == progress.advance(int(aug.plan_progress[x]), obs[s2])
    for s in rng.choice(toy.mdp.n_states, 50, replace=False):
        assert aug.reset_progress[s] == progress.initial(obs[s])


@pytest.mark.parametrize("toy_name", ["reach", "maze-reach", "push", "random-continuing"])
def test_appendix_progress_in_the_state_keeps_the_optimal_values(toy_name):
    """Appendix 8.1: the (s, max_idx) MDP with the original reward has the original Q."""
    toy = make_toy(toy_name)
    aug = toy.augmented
    r = toy.mdp.expected_reward()
    q = value_iteration(toy.mdp.dynamics, r, toy.gamma).q
    q_plus = value_iteration(aug.mdp.dynamics, aug.lift(r), toy.gamma).q
    alive = ~aug.mdp.terminal
    np.testing.assert_allclose(q_plus[alive], aug.lift(q)[alive], atol=1e-9)


def test_reachable_states():
    toy = make_toy("reach-episodic")
    aug = toy.augmented
    n = toy.mdp.n_states
    resets = aug.reset_progress * n + np.arange(n)
    assert aug.reachable[resets].all()
    # full progress only in the goal, which terminates: no other state has it
    final = aug.plan_progress == aug.progress.final
    assert np.array_equal(aug.reachable & final, final & aug.mdp.terminal)
    # progress never below what a reset gives
    assert np.all(aug.plan_progress[aug.reachable] >= aug.reset_progress[aug.state[aug.reachable]])


class Exploding(Potential):
    def potential(self, ctx: ShapingContext) -> float:
        return 1.0 / (ctx.progress - 3)


class NotANumber(Potential):
    def potential(self, ctx: ShapingContext) -> float:
        return math.nan if ctx.progress == 2 else 0.0


@pytest.mark.parametrize(
    ("potential", "message"),
    [
        (Exploding(), "raised ZeroDivisionError at state"),
        (NotANumber(), "returned nan at progress=.*at state"),
    ],
)
def test_a_failing_potential_is_bad_input_naming_the_state(potential, message):
    aug = make_toy("reach").augmented
    with pytest.raises(BadInputError, match=message):
        aug.potential_values(potential, 0)


class SecretClock(Potential):
    """Reads t without declaring time_dependent."""

    def potential(self, ctx: ShapingContext) -> float:
        return ctx.progress + 0.1 * ctx.t


def test_reading_the_time_undeclared_is_refused_naming_the_potential():
    """Checked as if φ(x, 0) held at every t, a potential that reads ctx.t undeclared would
    be checked wrongly: reading it is refused, in the checker and in the wrapper alike."""
    aug = make_toy("random-continuing").augmented
    with pytest.raises(PotentialValueError, match="SecretClock' reads ctx.t without declaring"):
        PotentialBased(SecretClock()).values(aug, 0, time_dependent=False)
    env = gymnasium.make(
        "planshape/Reach-v1", reward="shaped", potential=SecretClock(), model="grid", gamma=0.99
    )
    with pytest.raises(PotentialValueError, match="time_dependent = True"):
        env.reset(seed=0)
    assert not PotentialBased("plan-based").time_dependent(aug, 8)
    assert PotentialBased("time-varying").time_dependent(aug, 8)


@pytest.mark.parametrize("potential", ["plan-based", "time-varying", "distance-varying"])
def test_terminating_step_equals_the_wrapper(potential):
    toy = make_toy("reach-episodic")
    aug, mdp = toy.augmented, toy.mdp
    goal = int(np.flatnonzero(mdp.terminal)[0])
    right = mdp.actions.index("right")
    start = next(
        s for s in range(mdp.n_states) if mdp.transitions.indices[s * mdp.n_actions + right] == goal
    )
    env = TabularEnv(mdp, start)
    wrapper = PotentialShaping(
        env, make_potential(potential), toy.progress, gamma=toy.gamma, geometry=toy.geometry
    )
    wrapper.reset()
    x = int(aug.reset_progress[start]) * mdp.n_states + start
    _, _, terminated, _, info = wrapper.step(right)
    assert terminated and info["potential"] == 0.0
    x2 = info["progress"] * mdp.n_states + goal
    k = entry_index(aug.mdp, x * mdp.n_actions + right, x2)
    bonus = PotentialBased(potential).transition_bonus(aug, Step(0, 1, toy.gamma, toy.horizon))
    assert info["shaping"] == pytest.approx(bonus[k], abs=1e-12)
