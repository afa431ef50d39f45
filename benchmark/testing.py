"""Assertions for users' own test suites: regression-test the invariance argument.

:func:`assert_policy_invariant` runs the invariance checker (:mod:`planshape.invariance`) on a
potential and raises :class:`AssertionError` with the counterexample when the shaping changes
the optimal policy on some toy MDP: the state, the optimal actions with and without shaping,
and the regret. It needs no test framework (seals style); with pytest::

    from planshape.testing import assert_policy_invariant

    def test_my_potential_keeps_the_optimal_policy():
        assert_policy_invariant("my_package.potentials:MyPotential")

Example:
    >>> report = assert_policy_invariant("plan-based", mdps=["random-episodic"])
    >>> report.preserved
    True
    >>> from planshape.invariance.controls import GrowingPlanBased
    >>> assert_policy_invariant(GrowingPlanBased(1.2), mdps=["reach"])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    AssertionError: ...GrowingPlanBased does not keep the optimal policy: ...grows faster...
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from planshape.invariance.check import check_potential
from planshape.invariance.verdict import RELATIVE_TOLERANCE, InvarianceReport
from planshape.shaping.potentials import Potential

__all__ = ["assert_policy_invariant"]


def assert_policy_invariant(
    potential: str | Potential | type[Potential],
    *,
    mdps: Iterable[str] | None = None,
    settings: Iterable[str] | None = None,
    potential_kwargs: Mapping[str, Any] | None = None,
    relative: float = RELATIVE_TOLERANCE,
) -> InvarianceReport:
    """Check ``potential`` on the toy MDPs; return the report, or raise ``AssertionError``.

    Args:
        potential: a registered id, ``"module:attr"``, a :class:`Potential` subclass or
            instance.
        mdps: toy names (``planshape check-invariance --list``); all of them by default.
        settings: setting presets (``discounted``, ``finite-horizon``, ``undiscounted``, …);
            those the theory covers by default.
        potential_kwargs: keyword arguments for the potential's constructor.
        relative: the tie tolerance relative to the task's Q scale.

    Raises:
        AssertionError: on the first violated check, with its counterexample.
        planshape.errors.BadInputError: a potential the checker refuses (unknown, failing,
            reading ``ctx.t`` undeclared, writing ``ctx.obs``, too large to verify).
    """
    report = check_potential(
        potential,
        mdps=mdps,
        settings=settings,
        potential_kwargs=potential_kwargs,
        relative=relative,
    )
    if report.preserved:
        return report
    failed = next(v for v in report.verdicts if not v.preserved)
    if failed.not_a_potential:
        detail = failed.not_a_potential
    elif failed.counterexample is not None:
        detail = failed.counterexample.describe()
    else:
        detail = f"appendix 8.1 gap {failed.appendix_gap:.3g}"
    counted = (
        ""
        if failed.not_a_potential
        else f", {failed.mismatches} of {failed.checked} compared states differ"
    )
    raise AssertionError(
        f"{report.potential} does not keep the optimal policy: {failed.status} on {failed.mdp} "
        f"({failed.setting.label}){counted}; {detail}. {report.summary()}"
    )
