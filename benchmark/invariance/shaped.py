"""Shaping terms on the augmented MDP, transition by transition, as the wrapper computes them.

A :class:`Shaping` gives the bonus ``F`` of every stored transition ``(x, a, x')`` of an
:class:`AugmentedMDP` for a step taken at time ``t``; the checker adds its expectation to the
original reward. :class:`PotentialBased` reproduces
:class:`planshape.shaping.wrapper.PotentialShaping`
exactly:

* ``F = γ·φ(x', t+1) − φ(x, t)`` with γ the setting's discount (rule 1);
* ``φ(x', ·) = 0`` when the step terminates — entering a terminal state, or reaching the end of
  a finite horizon that ends by termination — and kept on truncation (rule 2);
* ``φ(x, t)`` is the value the previous step stored: the wrapper stores φ of the state it just
  entered, with the progress and time of that state, so it is a function of ``(x, t)`` (rule 3);
* at a reset, progress is ``max(0, furthest subgoal reached in s0)`` and ``t = 0`` (rule 4; see
  :attr:`AugmentedMDP.reachable`).

Its two switches, ``discount`` and ``zero_at_termination``, turn it into the mistakes that two
negative controls make (:mod:`planshape.invariance.controls`).

Example:
    >>> from planshape.baselines.paper import PlanBased
    >>> from planshape.invariance.toys import make_toy
    >>> aug = make_toy("random-episodic").augmented
    >>> shaping = PotentialBased(PlanBased())
    >>> F = shaping.transition_bonus(aug, Step(t=0, t_next=1, gamma=0.9, horizon=10))
    >>> F.shape == aug.mdp.transitions.data.shape
    True
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Literal
from weakref import WeakKeyDictionary

import numpy as np

from planshape.invariance.augment import AugmentedMDP
from planshape.invariance.probes import growth, hidden_state, step_function_mismatch
from planshape.invariance.settings import Setting
from planshape.shaping.potentials import Potential, make_potential

__all__ = ["PotentialBased", "Shaping", "Step"]


@dataclass(frozen=True)
class Step:
    """A step from time ``t`` to time ``t_next`` under discount ``gamma``, in a check whose
    horizon (or time cap) is ``horizon``.

    ``t_next`` equals ``t`` in the stationary part of a time-capped check. ``horizon_end`` says
    whether the episode ends at ``t_next`` because of the horizon: not at all (``None``), by
    termination (the wrapper's φ' is 0) or by truncation (φ' is kept).
    """

    t: int
    t_next: int
    gamma: float
    horizon: int
    horizon_end: Literal["terminated", "truncated"] | None = None


class Shaping(ABC):
    """A bonus added to every transition of an augmented MDP. Subclasses implement
    :meth:`transition_bonus`; ``name`` labels results."""

    name: str = "shaping"

    def time_dependent(self, aug: AugmentedMDP, horizon: int) -> bool:
        """Whether the bonus depends on ``t`` (then every time layer is solved separately)."""
        return False

    def probe(self, aug: AugmentedMDP, setting: Setting) -> str:
        """A counterexample the Q-tables cannot show, or ``""`` (see :class:`PotentialBased`)."""
        return ""

    @abstractmethod
    def transition_bonus(self, aug: AugmentedMDP, step: Step) -> np.ndarray:
        """``F`` of every stored transition of ``aug.mdp`` (aligned with its ``data``)."""

    def expected(self, aug: AugmentedMDP, step: Step) -> np.ndarray:
        """``E[F | x, a]``, shape ``(n_x, n_actions)``."""
        return aug.mdp.expected(self.transition_bonus(aug, step))


class PotentialBased(Shaping):
    """The shaping wrapper's ``F = γ·φ(x', t') − φ(x, t)`` for a :class:`Potential`.

    Args:
        potential: φ: a registered id, ``"module:attr"``, a class or an instance.
        discount: multiply φ(x') by γ (the wrapper does; ``False`` is the source paper's
            released code, negative control (b)).
        zero_at_termination: φ(x') = 0 when the step terminates (the wrapper does; ``False``
            is negative control (c)).
    """

    def __init__(
        self,
        potential: Potential | str | type[Potential],
        *,
        discount: bool = True,
        zero_at_termination: bool = True,
    ):
        self.potential = make_potential(potential)
        self.discount = discount
        self.zero_at_termination = zero_at_termination
        self.name = self.potential.name
        # per augmented MDP (weakly: a toy built for one check must not pin memory, nor let a
        # later MDP at the same address see its tables): t -> φ table
        self._tables: WeakKeyDictionary[AugmentedMDP, dict[int, np.ndarray]] = WeakKeyDictionary()
        self._probed: WeakKeyDictionary[AugmentedMDP, dict[int, str]] = WeakKeyDictionary()

    def time_dependent(self, aug: AugmentedMDP, horizon: int) -> bool:
        """As declared by ``Potential.time_dependent``: an undeclared potential cannot read
        the time (:meth:`planshape.shaping.potentials.Potential.__call__`)."""
        return self.potential.time_dependent

    def probe(self, aug: AugmentedMDP, setting: Setting) -> str:
        """What the table cannot show (:mod:`planshape.invariance.probes`): φ keeping state
        across calls, and, discounted, γ^t·φ that does not vanish; ``""`` if neither."""
        probed = self._probed.setdefault(aug, {})
        if setting.horizon not in probed:  # the same for every setting of that horizon
            probed[setting.horizon] = hidden_state(
                self.potential, aug, setting.horizon, self._table(aug, 0)
            ) or self._step_function_mismatch(aug, setting.horizon)
        found = probed[setting.horizon]
        if not found and setting.kind == "discounted":
            found = growth(self.potential, aug, setting.gamma, setting.horizon)
        return found

    def _step_function_mismatch(self, aug: AugmentedMDP, horizon: int) -> str:
        """:func:`step_function_mismatch` at t = 0, and for a time-dependent potential also at
        the second and the last step of the horizon."""
        last = horizon - 1
        times = sorted({0, min(1, last), last}) if self.potential.time_dependent else [0]
        for t in times:
            found = step_function_mismatch(self.potential, aug, self._table(aug, t), t)
            if found:
                return found
        return ""

    def values(self, aug: AugmentedMDP, t: int, time_dependent: bool) -> np.ndarray:
        """φ(x, t) of every augmented state (φ(x, 0) when φ does not depend on time)."""
        return self._table(aug, t if time_dependent else 0)

    def _table(self, aug: AugmentedMDP, t: int) -> np.ndarray:
        tables = self._tables.setdefault(aug, {})
        if t not in tables:
            tables[t] = aug.potential_values(self.potential, t)
        return tables[t]

    def transition_bonus(self, aug: AugmentedMDP, step: Step) -> np.ndarray:
        dynamic = self.time_dependent(aug, step.horizon)
        now = self.values(aug, step.t, dynamic)[aug.entry_states]
        after = self.values(aug, step.t_next, dynamic)[aug.entry_next]
        if self.zero_at_termination:
            if step.horizon_end == "terminated":
                after = np.zeros_like(after)
            else:
                after = np.where(aug.entry_terminates, 0.0, after)
        factor = step.gamma if self.discount else 1.0
        return factor * after - now
