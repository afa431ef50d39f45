"""``planshape.testing.assert_policy_invariant``: the assertion users put in their own suites
returns the report for a valid potential and raises AssertionError with the counterexample
(state, optimal actions with and without shaping, regret) for an invalid one."""

from __future__ import annotations

import pytest

from planshape.errors import BadInputError
from planshape.invariance.controls import GrowingPlanBased, HiddenStateBonus, ReadsTimeUndeclared
from planshape.testing import assert_policy_invariant


def test_a_valid_potential_returns_its_report():
    report = assert_policy_invariant("plan-distance", mdps=["reach", "push"])
    assert report.preserved and report.mdps == ["reach", "push"]


def test_an_invalid_shaping_raises_with_the_counterexample():
    with pytest.raises(AssertionError) as caught:
        assert_policy_invariant(GrowingPlanBased(1.2), mdps=["reach"], settings=["discounted"])
    assert "grows faster than 1/γ" in str(caught.value)
    with pytest.raises(AssertionError, match="not a function of the augmented state"):
        assert_policy_invariant(HiddenStateBonus(), mdps=["reach"])


def test_a_q_value_counterexample_names_state_actions_and_regret():
    with pytest.raises(AssertionError) as caught:
        assert_policy_invariant(
            "plan-based", mdps=["reach-episodic"], settings=["truncated"]
        )  # truncation without bootstrapping: not covered by the theory
    message = str(caught.value)
    for part in ("state ", "optimal original {", "vs shaped {", "regret "):
        assert part in message, message


def test_refused_potentials_are_bad_input_not_assertions():
    with pytest.raises(BadInputError, match="reads ctx.t without declaring"):
        assert_policy_invariant(ReadsTimeUndeclared(), mdps=["reach"])
