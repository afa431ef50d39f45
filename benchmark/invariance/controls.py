"""Negative controls: shapings that provably change the optimal policy, which the checker must
flag. Each control is a mistake, a toy MDP and a setting, with the argument why it fails there.

(a) ``subgoal-bonus`` — a bonus that is not potential-based: +2 on every step that ends in an
    intermediate subgoal of the plan. On ``reach`` (continuing, γ = 0.95) the plan's cells are
    its subgoals; parked on the last one, next to the goal, the agent earns 2 per step by
    staying, against 1 per step in the goal (the final subgoal earns no bonus): the shaped
    optimum stays next to the goal, the original enters it.
(b) ``no-gamma`` — ``F = φ(s') − φ(s)`` without γ, under γ = 0.95, the shaping of the source
    paper's released code, with ``plan-based`` at scale 2 on ``reach-episodic``. Next to the
    goal (progress n−1, φ = 2(n−1)/n ≈ 1.85), entering the goal earns 1 + 0 − φ < 0 while
    staying earns φ − φ = 0 on every step: the agent never enters the goal. With γ, staying
    earns −(1−γ)φ per step, −φ in all, and entering (1 − φ) is better.
(c) ``no-terminal-zero`` — φ(s') kept when the step terminates, with ``plan-based`` shifted by
    −3 (φ = max_idx/n − 3 ≤ −2: a constant shift, which a continuing task cannot tell apart)
    on ``push`` (episodic, γ = 0.9). Pushing the box into the goal at step T adds
    γ^T·φ_T ≤ −2γ^T to a reward γ^(T−1): a net γ^(T−1)(1 − 2γ) < 0, while never terminating
    costs nothing beyond −φ0: the agent never completes the push. Zeroing φ at termination (the
    wrapper) makes the shift cancel exactly.
(d) ``action-potential`` — a "potential" that reads the action being taken,
    φ(s, a) = plan-based(s) − 2·[a = stay], in ``F = γ·φ(s', a) − φ(s, a)``: every ``stay``
    earns 2(1 − γ) more, 2 in all over an endless stay, more than the goal's reward of 1 on
    ``reach-episodic``: the agent stays where it is. (Reading the *previous* action would be
    harmless: that is a potential over (s, a_prev), a valid augmented state.)

(e) ``hidden-state`` — a ``Potential`` that remembers its last output ψ and returns
    φ(s') = (ψ + 2·[s' on an intermediate subgoal]) / γ. Each φ the wrapper computes along an
    episode then gives F = γ·φ(s') − φ(s) = 2·[s' on an intermediate subgoal]: exactly (a)'s
    bonus, disguised as a potential, and the optimum parks next to the goal on ``reach``. A
    table filled once per state is a valid potential whatever it holds, so only calling φ along
    episodes, in different orders, shows it (:func:`planshape.invariance.probes.hidden_state`).
(f) ``growth`` — a declared time-dependent φ(s, t) = 1.2^t · max_idx/n under γ = 0.95 on
    ``reach``: staying on an intermediate subgoal earns F_t = (1.2γ − 1)·φ_t > 0, growing
    without bound, so never entering the goal pays more than entering it. Capping t at the
    horizon makes it look bounded; γ^t·φ is probed up to 32 horizons
    (:func:`planshape.invariance.probes.growth`).

What the API makes impossible is refused instead (exit 2, :data:`REFUSED`): a potential that
reads ``ctx.t`` without declaring ``time_dependent``, one that writes into ``ctx.obs`` (the
learner's observation), and one so large that ties drown in the solvers' precision.

Example:
    >>> [c.name for c in CONTROLS]
    ['subgoal-bonus', 'no-gamma', 'no-terminal-zero', 'action-potential', 'hidden-state', 'growth']
    >>> run_control(CONTROLS[0]).preserved
    False
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from planshape.invariance.augment import AugmentedMDP
from planshape.invariance.check import check_shaping
from planshape.invariance.shaped import PotentialBased, Shaping, Step
from planshape.invariance.toys import make_toy
from planshape.invariance.verdict import MdpVerdict
from planshape.shaping.potentials import Potential, ShapingContext, make_potential

__all__ = [
    "CONTROLS",
    "REFUSED",
    "ActionPotential",
    "GrowingPlanBased",
    "HiddenStateBonus",
    "NegativeControl",
    "ShiftedPlanBased",
    "SubgoalBonus",
    "run_control",
]


class SubgoalBonus(Shaping):
    """``F = bonus`` on every step that ends where an intermediate plan subgoal (``0 < i < n``)
    is reached: a subgoal reward, not potential-based."""

    def __init__(self, bonus: float = 2.0):
        self.bonus = bonus
        self.name = f"subgoal-bonus({bonus:g})"

    def transition_bonus(self, aug: AugmentedMDP, step: Step) -> np.ndarray:
        reached = np.asarray(aug.progress.reached(aug.base.observations))
        in_subgoal = reached[:, 1:-1].any(axis=1)  # an empty slice (n ≤ 1) is never reached
        return self.bonus * in_subgoal[aug.state[aug.entry_next]].astype(float)


#: the registered potential the shifted and growing controls are built on (the paper's
#: plan-based potential, found through the registry: the engine imports no baseline)
REFERENCE = "plan-based"


class ShiftedPlanBased(Potential):
    """``plan-based`` plus a constant: φ = max_idx/n + offset."""

    def __init__(self, offset: float = -3.0, scale: float = 1.0):
        super().__init__(scale)
        self.offset = offset
        self._plan = make_potential(REFERENCE)

    def potential(self, ctx: ShapingContext) -> float:
        return self._plan.potential(ctx) + self.offset


class ActionPotential(Shaping):
    """``F = γ·φ(s', a) − φ(s, a)`` with ``φ(s, a) = ψ(s) + offsets[a]``: a potential that
    looks at the action being taken (φ(s', ·) = 0 on termination, as in the wrapper)."""

    def __init__(self, potential: Potential | str, offsets: Mapping[str, float]):
        self.state_part = PotentialBased(potential)
        self.offsets = dict(offsets)
        self.name = f"action-potential({self.state_part.name}, {self.offsets})"

    def transition_bonus(self, aug: AugmentedMDP, step: Step) -> np.ndarray:
        table = np.array([self.offsets.get(a, 0.0) for a in aug.mdp.actions])[aug.entry_actions]
        psi = self.state_part.values(aug, 0, time_dependent=False)
        after = np.where(aug.entry_terminates, 0.0, psi[aug.entry_next] + table)
        if step.horizon_end == "terminated":
            after = np.zeros_like(after)
        return step.gamma * after - (psi[aug.entry_states] + table)


class HiddenStateBonus(Potential):
    """φ(s') = (last output + bonus·[s' on an intermediate subgoal]) / γ: control (a)'s bonus,
    carried in state across calls (control (e))."""

    def __init__(self, bonus: float = 2.0, gamma: float = 0.95, scale: float = 1.0):
        super().__init__(scale)
        self.bonus, self.gamma, self._last = bonus, gamma, 0.0

    def potential(self, ctx: ShapingContext) -> float:
        held = ctx.abstract_state
        on_subgoal = any(sub <= held for sub in ctx.subgoals[1:-1])
        self._last = (self._last + self.bonus * on_subgoal) / self.gamma
        if abs(self._last) > 1e6:  # stay finite over long probes; the shaping is unchanged
            self._last = 0.0
        return self._last


class GrowingPlanBased(Potential):
    """φ(s, t) = base^t · max_idx / n: declared time-dependent, growing faster than 1/γ when
    base·γ > 1 (control (f))."""

    time_dependent = True

    def __init__(self, base: float = 1.2, scale: float = 1.0):
        super().__init__(scale)
        self.base = base
        self._plan = make_potential(REFERENCE)

    def potential(self, ctx: ShapingContext) -> float:
        return self.base**ctx.t * self._plan.potential(ctx)


class ReadsTimeUndeclared(Potential):
    """Reads ``ctx.t`` without declaring ``time_dependent`` (refused)."""

    def potential(self, ctx: ShapingContext) -> float:
        return ctx.progress / max(ctx.final, 1) + (0.5 if ctx.t == 7 else 0.0)


class WritesObservation(Potential):
    """Writes into ``ctx.obs``, the learner's observation (refused)."""

    def potential(self, ctx: ShapingContext) -> float:
        ctx.obs[0] = 0.0
        return 0.0


@dataclass(frozen=True)
class NegativeControl:
    """A shaping that must be flagged, where, and why.

    Attributes:
        name: the control's id; ``mistake``: what is wrong with it.
        toy, preset: the toy MDP and setting on which it provably changes the optimum.
        build: makes the :class:`Shaping`.
        argument: why the optimal policy changes there (see the module docstring).
    """

    name: str
    mistake: str
    toy: str
    preset: str
    build: Callable[[], Shaping]
    argument: str


CONTROLS: tuple[NegativeControl, ...] = (
    NegativeControl(
        "subgoal-bonus",
        "(a) a subgoal bonus that is not potential-based",
        "reach",
        "discounted",
        lambda: SubgoalBonus(2.0),
        "staying on the last intermediate subgoal earns 2 per step, the goal only 1",
    ),
    NegativeControl(
        "no-gamma",
        "(b) F = φ(s') − φ(s) without γ, under γ < 1",
        "reach-episodic",
        "discounted",
        lambda: PotentialBased(make_potential("plan-based", scale=2.0), discount=False),
        "next to the goal, entering earns 1 − φ < 0 and staying earns 0 forever",
    ),
    NegativeControl(
        "no-terminal-zero",
        "(c) a nonzero potential after termination in an episodic task",
        "push",
        "discounted",
        lambda: PotentialBased(ShiftedPlanBased(-3.0), zero_at_termination=False),
        "completing at step T nets γ^(T−1)(1 + γ·φ_T) < 0 with φ ≤ −2; never completing nets 0",
    ),
    NegativeControl(
        "action-potential",
        "(d) a 'potential' that looks at the action",
        "reach-episodic",
        "discounted",
        lambda: ActionPotential(make_potential("plan-based"), {"stay": -2.0}),
        "an endless stay earns 2 of shaping, the goal only 1",
    ),
    NegativeControl(
        "hidden-state",
        "(e) a potential that keeps state across calls: a disguised subgoal bonus",
        "reach",
        "discounted",
        lambda: PotentialBased(HiddenStateBonus(2.0, gamma=0.95)),
        "along an episode F = 2·[on an intermediate subgoal]: (a)'s bonus",
    ),
    NegativeControl(
        "growth",
        "(f) a time-dependent potential growing faster than 1/γ",
        "reach",
        "discounted",
        lambda: PotentialBased(GrowingPlanBased(1.2)),
        "staying on a subgoal earns (1.2γ − 1)·φ_t per step, without bound",
    ),
)

#: potentials the API refuses (exit 2) rather than checks: (name, potential, message part)
REFUSED: tuple[tuple[str, Callable[[], Potential], str], ...] = (
    ("undeclared-time", ReadsTimeUndeclared, "reads ctx.t without declaring time_dependent"),
    ("writes-observation", WritesObservation, "writes into ctx.obs"),
    ("magnitude", lambda: make_potential("plan-based", scale=1e9), "cannot verify"),
)


def run_control(control: NegativeControl) -> MdpVerdict:
    """Check ``control`` on its toy in its setting (the verdict must be a violation)."""
    toy = make_toy(control.toy)
    return check_shaping(toy, control.build(), toy.setting(control.preset))
