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

Example:
    >>> [c.name for c in CONTROLS]
    ['subgoal-bonus', 'no-gamma', 'no-terminal-zero', 'action-potential']
    >>> run_control(CONTROLS[0]).preserved
    False
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from planshape.baselines.paper import PlanBased
from planshape.invariance.augment import AugmentedMDP
from planshape.invariance.check import check_shaping
from planshape.invariance.shaped import PotentialBased, Shaping, Step
from planshape.invariance.toys import make_toy
from planshape.invariance.verdict import MdpVerdict
from planshape.potentials import Potential, ShapingContext, make_potential

__all__ = [
    "CONTROLS",
    "ActionPotential",
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


class ShiftedPlanBased(Potential):
    """``plan-based`` plus a constant: φ = max_idx/n + offset."""

    def __init__(self, offset: float = -3.0, scale: float = 1.0):
        super().__init__(scale)
        self.offset = offset
        self._plan = PlanBased()

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
)


def run_control(control: NegativeControl) -> MdpVerdict:
    """Check ``control`` on its toy in its setting (the verdict must be a violation)."""
    toy = make_toy(control.toy)
    return check_shaping(toy, control.build(), toy.setting(control.preset))
