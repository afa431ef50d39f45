"""Property tests: random MDPs with random valid potentials are always preserved; random
non-potential bonuses are flagged exactly when brute-force enumeration of deterministic policies
says the optimum changed."""

from __future__ import annotations

import numpy as np
from hypothesis import HealthCheck, assume, event, given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from planshape.invariance.check import check_shaping
from planshape.invariance.settings import Setting
from planshape.invariance.shaped import PotentialBased, Step
from planshape.invariance.solve import value_iteration
from tests.invariance.tabular import (
    TableBonus,
    TablePotential,
    brute_force_finite_sets,
    brute_force_optimal_sets,
    chain_toy,
)

REWARDS = st.sampled_from([-1.0, -0.5, 0.0, 0.0, 0.5, 1.0])
PROPERTY = settings(
    max_examples=100,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)


@st.composite
def chain_toys(draw, max_states=5, max_actions=3, max_regions=3, deterministic=False):
    n = draw(st.integers(2, max_states))
    n_a = draw(st.integers(2, max_actions))
    regions = draw(st.integers(2, max_regions))
    labels = draw(st.lists(st.integers(-1, regions - 1), min_size=n, max_size=n))
    successors, weights, rewards = [], [], []
    for _ in range(n):
        row_s, row_w, row_r = [], [], []
        for _ in range(n_a):
            k = 1 if deterministic else draw(st.integers(1, min(3, n)))
            nxt = draw(st.lists(st.integers(0, n - 1), min_size=k, max_size=k, unique=True))
            row_s.append(nxt)
            row_w.append(draw(st.lists(st.integers(1, 3), min_size=k, max_size=k)))
            row_r.append(draw(st.lists(REWARDS, min_size=k, max_size=k)))
        successors.append(row_s)
        weights.append(row_w)
        rewards.append(row_r)
    rest = draw(st.lists(st.sampled_from([False, False, True]), min_size=n - 1, max_size=n - 1))
    terminal = [False, *rest]
    return chain_toy(
        labels=labels,
        successors=successors,
        weights=weights,
        rewards=rewards,
        terminal=terminal,
        regions=regions,
        gamma=draw(st.sampled_from([0.5, 0.8, 0.9])),
        horizon=draw(st.integers(1, 4)),
    )


@PROPERTY
@given(toy=chain_toys(), kind=st.sampled_from(["state", "progress", "time"]), data=st.data())
def test_random_valid_potentials_are_always_preserved(toy, kind, data):
    n, regions = toy.mdp.n_states, toy.progress.final + 1
    shape = {"state": (n,), "progress": (n, regions), "time": (n, regions, toy.horizon + 1)}
    table = data.draw(arrays(float, shape[kind], elements=st.floats(-5, 5, width=32)))
    shaping = PotentialBased(TablePotential(table, kind))
    for preset in ("discounted", "finite-horizon", "undiscounted"):
        verdict = check_shaping(toy, shaping, toy.setting(preset))
        assert verdict.preserved, (preset, verdict.counterexample)
        assert verdict.time_dependent == (kind == "time")


def _no_near_ties(aug, per_entry_list, gamma):
    """Skip MDPs whose optimal Q-values have gaps near the tie tolerance (either verdict could
    then be right): every gap is 0 (to 1e-11) or above 1e-6. (The solver only filters.)"""
    for per_entry in per_entry_list:
        r = aug.mdp.expected(per_entry)
        q = value_iteration(aug.mdp.dynamics, r, gamma).q[~aug.mdp.terminal]
        gaps = np.abs(q[:, :, None] - q[:, None, :])
        assume(not np.any((gaps > 1e-11) & (gaps < 1e-6)))


@PROPERTY
@given(toy=chain_toys(max_states=3, max_actions=2, max_regions=2), data=st.data())
def test_random_bonuses_discounted_verdict_equals_brute_force(toy, data):
    aug = toy.augmented
    assume((~aug.mdp.terminal).sum() <= 6)
    nnz = aug.mdp.transitions.nnz
    bonus = np.array(data.draw(st.lists(REWARDS, min_size=nnz, max_size=nnz)))
    original, shaped = aug.mdp.rewards, aug.mdp.rewards + bonus
    _no_near_ties(aug, [original, shaped], toy.gamma)
    tol = 1e-7  # no gap lies between 1e-11 and 1e-6 (see _no_near_ties)
    truth_original = brute_force_optimal_sets(aug, original, toy.gamma, tol)
    truth_shaped = brute_force_optimal_sets(aug, shaped, toy.gamma, tol)
    compared = aug.reachable & ~aug.mdp.terminal
    preserved = np.array_equal(truth_original[compared], truth_shaped[compared])
    event(f"bonus {'keeps' if preserved else 'changes'} the optimum")
    verdict = check_shaping(toy, TableBonus(bonus), toy.setting("discounted"))
    assert verdict.preserved == preserved, verdict.counterexample


@PROPERTY
@given(
    toy=chain_toys(max_states=4, max_actions=2, max_regions=2, deterministic=True),
    gamma=st.sampled_from([0.8, 1.0]),
    data=st.data(),
)
def test_random_bonuses_finite_horizon_verdict_equals_brute_force(toy, gamma, data):
    aug = toy.augmented
    nnz = aug.mdp.transitions.nnz
    bonus = np.array(data.draw(st.lists(REWARDS, min_size=nnz, max_size=nnz)))
    horizon = toy.horizon
    tol = 1e-6
    original = brute_force_finite_sets(aug, lambda t: aug.mdp.rewards, gamma, horizon, tol)
    shaped = brute_force_finite_sets(aug, lambda t: aug.mdp.rewards + bonus, gamma, horizon, tol)
    compared = aug.reachable & ~aug.mdp.terminal
    preserved = all(np.array_equal(original[t][compared], shaped[t][compared]) for t in original)
    event(f"bonus {'keeps' if preserved else 'changes'} the optimum")
    verdict = check_shaping(toy, TableBonus(bonus), Setting("finite-horizon", gamma, horizon))
    assert verdict.preserved == preserved, verdict.counterexample


@PROPERTY
@given(
    toy=chain_toys(max_states=4, max_actions=2, max_regions=3, deterministic=True), data=st.data()
)
def test_truncated_verdict_equals_brute_force(toy, data):
    """Time-limit truncation without bootstrapping (not covered by the theory): whatever the
    checker says about a time-indexed potential agrees with enumeration."""
    aug = toy.augmented
    n, regions, horizon = toy.mdp.n_states, toy.progress.final + 1, toy.horizon
    table = data.draw(
        arrays(float, (n, regions, horizon + 1), elements=st.sampled_from([-1.0, 0.0, 0.5, 2.0]))
    )
    shaping = PotentialBased(TablePotential(table, "time"))
    setting = Setting("finite-horizon-truncated", 1.0, horizon)

    def shaped_at(t):
        end = "truncated" if t + 1 == horizon else None
        return aug.mdp.rewards + shaping.transition_bonus(aug, Step(t, t + 1, 1.0, horizon, end))

    original = brute_force_finite_sets(aug, lambda t: aug.mdp.rewards, 1.0, horizon, 1e-6)
    shaped = brute_force_finite_sets(aug, shaped_at, 1.0, horizon, 1e-6)
    compared = aug.reachable & ~aug.mdp.terminal
    preserved = all(np.array_equal(original[t][compared], shaped[t][compared]) for t in original)
    event(f"truncation {'keeps' if preserved else 'changes'} the optimum")
    assert check_shaping(toy, shaping, setting).preserved == preserved
