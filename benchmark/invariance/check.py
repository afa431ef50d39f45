"""Run a shaping on a toy MDP in a setting, and a potential on every toy: the verdicts.

:func:`check_shaping` solves, exactly,

1. the original MDP (states ``s``), for its optimal Q-values;
2. the augmented MDP ``(s, max_idx)`` with the original reward, to check appendix 8.1 (its
   Q-values equal the original ones lifted; reported as ``appendix_gap``);
3. the augmented MDP with the shaped reward ``R + F`` (layer by layer in time when ``F``
   depends on time),

and compares optimal action sets in every reachable, non-terminal augmented state (and time
layer). :func:`check_potential` does that for one potential on every toy in the settings the
theory covers; it is what the benchmark runs before training a submitted potential.

Example:
    >>> report = check_potential("plan-based", mdps=["random-episodic"])
    >>> report.preserved, len(report.verdicts)
    (True, 3)
"""

from __future__ import annotations

import time
from collections.abc import Iterable, Iterator, Mapping
from typing import Any

import numpy as np

from planshape.errors import CannotVerifyError
from planshape.invariance.registry import default_toys
from planshape.invariance.settings import DEFAULT_PRESETS, Setting
from planshape.invariance.shaped import PotentialBased, Shaping, Step
from planshape.invariance.solve import backward_induction, value_iteration
from planshape.invariance.toys import ToyProblem, make_toy
from planshape.invariance.verdict import (
    MAX_SCALE_RATIO,
    RELATIVE_TOLERANCE,
    Comparison,
    InvarianceReport,
    MdpVerdict,
    tie_tolerance,
)
from planshape.shaping.potentials import Potential, make_potential

__all__ = ["check_potential", "check_shaping"]


#: one compared layer: (t or None, original Q lifted to (s, p), augmented-original Q or None,
#: shaped Q), all of shape (n_x, n_actions)
Layer = tuple[int | None, np.ndarray, np.ndarray | None, np.ndarray]


def check_shaping(
    toy: ToyProblem,
    shaping: Shaping,
    setting: Setting,
    *,
    relative: float = RELATIVE_TOLERANCE,
) -> MdpVerdict:
    """Whether ``shaping`` keeps the optimal actions of ``toy`` in ``setting``."""
    started = time.perf_counter()
    aug = toy.augmented
    active = ~aug.mdp.terminal
    comparison = Comparison(aug, aug.reachable & active, relative)
    dynamic = shaping.time_dependent(aug, setting.horizon)
    solve = _discounted_layers if setting.kind == "discounted" else _finite_layers
    appendix_gap, appendix_holds = 0.0, True
    # what the Q-tables cannot show comes first: a φ that is not a potential is not solved
    not_a_potential = shaping.probe(aug, setting)
    layers = () if not_a_potential else solve(toy, shaping, setting, dynamic)
    for t, q_lifted, q_plus, q_shaped in layers:
        if q_plus is not None:  # appendix 8.1: progress in the state changes no Q-value
            gap = float(np.abs(q_plus - q_lifted)[active].max(initial=0.0))
            appendix_gap = max(appendix_gap, gap)
            appendix_holds &= gap <= tie_tolerance(q_lifted[active], relative=relative)
        _check_scale(q_lifted[active], q_shaped[active], shaping, toy, setting)
        comparison.add(q_lifted, q_shaped, t)
    return MdpVerdict(
        mdp=toy.name,
        shaping=shaping.name,
        setting=setting,
        preserved=comparison.mismatches == 0 and appendix_holds and not not_a_potential,
        time_dependent=dynamic,
        checked=comparison.checked,
        mismatches=comparison.mismatches,
        harmful=comparison.harmful,
        tolerance=relative,
        appendix_gap=appendix_gap,
        augmented_states=aug.n_states,
        state_action_pairs=aug.mdp.n_pairs,
        seconds=time.perf_counter() - started,
        counterexample=comparison.counterexample(),
        not_a_potential=not_a_potential,
    )


def _check_scale(
    q_original: np.ndarray,
    q_shaped: np.ndarray,
    shaping: Shaping,
    toy: ToyProblem,
    setting: Setting,
) -> None:
    """Refuse a check whose shaped Q-values are too large to resolve the tie tolerance."""
    original = max(1.0, float(np.abs(q_original).max(initial=0.0)))
    shaped = float(np.abs(q_shaped).max(initial=0.0))
    if shaped > MAX_SCALE_RATIO * original:
        raise CannotVerifyError(
            f"cannot verify {shaping.name!r} on {toy.name} ({setting.label}): its shaped "
            f"Q-values reach {shaped:.3g}, {shaped / original:.3g} times the task's "
            f"({original:.3g}), beyond the {MAX_SCALE_RATIO:g} at which ties of the task's "
            "scale can be told apart; check the potential at unit scale (scale=1: shaping is "
            "scale-equivariant, so the verdict is the same at any scale)"
        )


def _discounted_layers(
    toy: ToyProblem, shaping: Shaping, setting: Setting, dynamic: bool
) -> Iterator[Layer]:
    """γ < 1, infinite horizon: one stationary layer, or for a time-dependent shaping with
    time capped at H, the stationary layer t ≥ H and then t = H−1 … 0."""
    aug, gamma, horizon = toy.augmented, setting.gamma, setting.horizon
    r_aug = aug.lift(toy.mdp.expected_reward())
    q_lifted = aug.lift(value_iteration(toy.mdp.dynamics, toy.mdp.expected_reward(), gamma).q)
    q_plus = value_iteration(aug.mdp.dynamics, r_aug, gamma).q
    if not dynamic:
        bonus = shaping.expected(aug, Step(0, 0, gamma, horizon))
        yield None, q_lifted, q_plus, value_iteration(aug.mdp.dynamics, r_aug + bonus, gamma).q
        return
    bonus = shaping.expected(aug, Step(horizon, horizon, gamma, horizon))
    q_stationary = value_iteration(aug.mdp.dynamics, r_aug + bonus, gamma).q
    yield horizon, q_lifted, q_plus, q_stationary
    layers = backward_induction(
        aug.mdp.dynamics,
        lambda t: r_aug + shaping.expected(aug, Step(t, t + 1, gamma, horizon)),
        gamma,
        horizon,
        final_values=q_stationary.max(axis=1),
    )
    for t, q_shaped in layers:
        yield t, q_lifted, None, q_shaped


def _finite_layers(
    toy: ToyProblem, shaping: Shaping, setting: Setting, dynamic: bool
) -> Iterator[Layer]:
    """Finite horizon H: layers t = H−1 … 0; the last step ends the episode by termination
    (``finite-horizon``) or truncation (``finite-horizon-truncated``)."""
    aug, gamma, horizon = toy.augmented, setting.gamma, setting.horizon
    end = "terminated" if setting.kind == "finite-horizon" else "truncated"
    r_base = toy.mdp.expected_reward()
    r_aug = aug.lift(r_base)
    cache: dict[int, np.ndarray] = {}

    def shaped_reward(t: int) -> np.ndarray:
        key = t if dynamic or t == horizon - 1 else -1  # time-free F: one table mid-episode
        if key not in cache:
            step = Step(t, t + 1, gamma, horizon, end if t + 1 == horizon else None)
            cache[key] = r_aug + shaping.expected(aug, step)
        return cache[key]

    original = backward_induction(toy.mdp.dynamics, lambda t: r_base, gamma, horizon)
    plus = backward_induction(aug.mdp.dynamics, lambda t: r_aug, gamma, horizon)
    shaped = backward_induction(aug.mdp.dynamics, shaped_reward, gamma, horizon)
    for (t, q), (_, q_plus), (_, q_shaped) in zip(original, plus, shaped, strict=True):
        yield t, aug.lift(q), q_plus, q_shaped


def check_potential(
    reference: str | Potential | type[Potential],
    *,
    mdps: Iterable[str] | None = None,
    settings: Iterable[str] | None = None,
    potential_kwargs: Mapping[str, Any] | None = None,
    relative: float = RELATIVE_TOLERANCE,
) -> InvarianceReport:
    """Check a potential on every toy MDP (or ``mdps``) in every setting the theory covers (or
    the named ``settings``, see :data:`planshape.invariance.settings.PRESETS`).

    Args:
        reference: a registered id, ``"module:attr"``, a :class:`Potential` subclass or instance.
        mdps: toy names (:func:`planshape.invariance.toys.toy_names`); all of them by default.
        settings: setting presets; ``("discounted", "finite-horizon", "undiscounted")`` by default.
        potential_kwargs: keyword arguments for the potential's constructor.
        relative: the tie tolerance relative to the Q scale.

    Raises :class:`planshape.errors.BadInputError` for an unknown potential, toy or setting, or
    a potential that fails on a toy.
    """
    potential = make_potential(reference, **dict(potential_kwargs or {}))
    names = list(mdps) if mdps is not None else default_toys()
    presets = list(settings) if settings is not None else list(DEFAULT_PRESETS)
    toys = [make_toy(name) for name in names]  # unknown names fail before any solving
    setting_of = {(t.name, p): t.setting(p) for t in toys for p in presets}
    # the learner of a toy discounts with the toy's γ: a potential defined through the
    # learner's discount is that toy's one in every setting (a fixed φ, also where γ = 1)
    shaping_of = {t.name: PotentialBased(potential.for_discount(t.gamma)) for t in toys}
    verdicts = [
        check_shaping(toy, shaping_of[toy.name], setting_of[toy.name, preset], relative=relative)
        for toy in toys
        for preset in presets
    ]
    return InvarianceReport(potential.name, tuple(verdicts), relative)
