"""Tie tolerance, comparison, counterexamples and the JSON report."""

from __future__ import annotations

import json

import numpy as np
import pytest

from planshape.invariance import check_potential
from planshape.invariance.check import check_shaping
from planshape.invariance.toys import make_toy
from planshape.invariance.verdict import (
    RELATIVE_TOLERANCE,
    Comparison,
    optimal_actions,
    tie_tolerance,
)
from tests.invariance.tabular import TableBonus


@pytest.mark.parametrize("scale", [1.0, 1e3, 1e-3])
def test_ties_within_the_stated_tolerance(scale):
    """Actions within 1e-8 · max(1, max|Q|) of the best are tied; 1e-6 apart are not."""
    base = 0.7 * scale
    q = np.array([[base, base - 1e-10 * max(1, base), base - 1e-6 * max(1, base)]])
    tol = tie_tolerance(q)
    assert tol == pytest.approx(RELATIVE_TOLERANCE * max(1.0, base))
    assert optimal_actions(q, tol).tolist() == [[True, True, False]]


def _comparison(toy_name: str):
    aug = make_toy(toy_name).augmented
    compared = aug.reachable & ~aug.mdp.terminal
    return aug, compared, Comparison(aug, compared, RELATIVE_TOLERANCE)


def test_comparison_reports_the_worst_mismatch_as_counterexample():
    aug, compared, comparison = _comparison("reach")
    rng = np.random.default_rng(0)
    q = rng.normal(size=(aug.n_states, aug.mdp.n_actions))
    shaped = q - 5.0  # a state-wise shift changes no optimal action
    x = int(np.flatnonzero(compared)[7])
    worst = int(q[x].argmin())
    shaped[x, worst] = shaped[x].max() + 1.0  # the shaped optimum is the original worst
    comparison.add(q, shaped, t=3)
    assert (comparison.checked, comparison.mismatches, comparison.harmful) == (
        int(compared.sum()),
        1,
        1,
    )
    example = comparison.counterexample()
    assert example.augmented_state == x and example.t == 3
    assert example.state == aug.state[x] and example.progress == aug.plan_progress[x]
    assert example.shaped_optimal == [aug.mdp.actions[worst]]
    assert example.regret == pytest.approx(q[x].max() - q[x].min())
    assert example.harmful and example.q_original == pytest.approx(q[x].tolist())
    assert example.observation == pytest.approx(aug.observation(x).tolist())


def test_a_broken_tie_is_a_mismatch_but_not_harmful():
    aug, compared, comparison = _comparison("reach")
    q = np.zeros((aug.n_states, aug.mdp.n_actions))
    shaped = q.copy()
    x = int(np.flatnonzero(compared)[0])
    shaped[x, 1] = 1e-3
    comparison.add(q, shaped, None)
    assert (comparison.mismatches, comparison.harmful) == (1, 0)
    assert not comparison.counterexample().harmful


def test_differences_below_tolerance_are_no_mismatch():
    aug, _, comparison = _comparison("reach")
    q = np.random.default_rng(2).normal(size=(aug.n_states, aug.mdp.n_actions))
    comparison.add(q, q + 1e-11 * np.random.default_rng(3).normal(size=q.shape), 0)
    assert comparison.mismatches == 0 and comparison.counterexample() is None


def test_a_zero_bonus_is_preserved_and_the_appendix_holds():
    toy = make_toy("random-continuing")
    bonus = np.zeros(toy.augmented.mdp.transitions.nnz)
    verdict = check_shaping(toy, TableBonus(bonus), toy.setting("discounted"))
    assert verdict.preserved and verdict.status == "preserved"
    assert verdict.appendix_gap < 1e-9


def test_report_is_json_with_a_verdict_per_mdp():
    report = check_potential(
        "plan-based", mdps=["random-episodic", "reach"], settings=["discounted", "truncated"]
    )
    data = json.loads(report.to_json())
    assert [m["mdp"] for m in data["mdps"]] == ["random-episodic", "reach"]
    assert data["preserved"] is False  # the truncated setting is not covered
    for entry in data["mdps"]:
        kinds = [c["setting"]["kind"] for c in entry["checks"]]
        assert kinds == ["discounted", "finite-horizon-truncated"]
        assert entry["preserved"] == all(c["preserved"] for c in entry["checks"])
        discounted, truncated = entry["checks"]
        assert discounted["preserved"] and discounted["counterexample"] is None
        assert discounted["setting"]["covered_by_theory"] is True
        assert not truncated["setting"]["covered_by_theory"]
    assert data["tolerance"]["relative"] == RELATIVE_TOLERANCE
