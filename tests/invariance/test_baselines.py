"""Every reference potential passes on every toy MDP in the settings the theory covers; and
what happens where it does not (time-limit truncation without bootstrapping)."""

from __future__ import annotations

import pytest

from planshape.baselines.paper import PlanBased
from planshape.invariance import check_potential
from planshape.invariance.check import check_shaping
from planshape.invariance.registry import toy_names
from planshape.invariance.settings import DEFAULT_PRESETS
from planshape.invariance.shaped import PotentialBased
from planshape.invariance.toys import make_toy
from planshape.shaping.potentials import ShapingContext, potential_ids
from planshape.testing import assert_policy_invariant


@pytest.mark.parametrize("potential", potential_ids())
def test_reference_potentials_preserve_optimal_actions_everywhere(potential):
    report = assert_policy_invariant(potential)  # what users run in their own suites
    assert report.mdps == toy_names()
    assert {v.setting.kind for v in report.verdicts} == {"discounted", "finite-horizon"}
    assert len(report.verdicts) == len(toy_names()) * len(DEFAULT_PRESETS)
    assert all(v.appendix_gap < 1e-9 for v in report.verdicts)


@pytest.mark.parametrize("scale", [0.1, 25.0])
def test_scale_does_not_matter(scale):
    report = check_potential(
        "distance-varying", mdps=["maze-reach", "push"], potential_kwargs={"scale": scale}
    )
    assert report.preserved


@pytest.mark.parametrize(
    ("potential", "toy"),
    [
        ("plan-based", "maze-reach"),
        ("time-varying", "random-episodic"),
        ("distance-varying", "random-continuing"),
        ("plan-based", "random-episodic"),
    ],
)
def test_finding_truncation_without_bootstrap_is_not_covered(potential, toy):
    """With the episode cut at H by a time limit, the wrapper keeps φ(s_H) (rule 2), right for
    a bootstrapping learner; a learner of the H-step return gains γ^(H-t)·φ(s_H, H) and its
    optimum changes — harmfully, not only by breaking ties."""
    toy_problem = make_toy(toy)
    for preset in ("truncated", "truncated-discounted"):
        verdict = check_shaping(toy_problem, PotentialBased(potential), toy_problem.setting(preset))
        assert not verdict.preserved and verdict.harmful > 0
        example = verdict.counterexample
        assert example.harmful and example.t is not None


class FadingPlanBased(PlanBased):
    """plan-based, fading linearly to 0 at t = H: φ(·, H) is constant (0)."""

    time_dependent = True

    def __init__(self, horizon: int):
        super().__init__()
        self.horizon = horizon

    def potential(self, ctx: ShapingContext) -> float:
        return super().potential(ctx) * max(0, self.horizon - ctx.t) / self.horizon


@pytest.mark.parametrize("toy", ["maze-reach", "random-episodic", "random-continuing"])
def test_a_potential_that_vanishes_at_the_horizon_survives_truncation(toy):
    toy_problem = make_toy(toy)
    shaping = PotentialBased(FadingPlanBased(toy_problem.horizon))
    for preset in ("truncated", "undiscounted", "discounted"):
        assert check_shaping(toy_problem, shaping, toy_problem.setting(preset)).preserved
