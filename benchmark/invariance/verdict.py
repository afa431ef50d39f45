"""Comparing optimal action sets, and the JSON-ready results of a check.

**Tolerance for ties.** In a table of Q-values (one time layer of one MDP), action ``a`` is
optimal in state ``x`` when

    Q(x, a) ≥ max_b Q(x, b) − τ,     τ = 1e-8 · max(1, max |Q| of the original layer).

τ does not grow with the shaping: a potential of size 10^9 would otherwise make every action
tie and the check vacuous (and hide an invalid shaping added to it). A shaped Q-table more than
:data:`MAX_SCALE_RATIO` times the original's cannot resolve τ (the solvers' error grows with
the scale), so that check is refused as unverifiable (:class:`CannotVerifyError`) rather than
passed.

The solvers are accurate to about 1e-12 of the same scale, four orders of magnitude below τ, so
exact ties (two paths of the same length) stay ties after shaping, and real differences larger
than τ are never mistaken for ties. Optimal *sets* are compared state by state: the verdict is
*preserved* when they are equal in every compared state. A difference is *harmful* when some
shaped-optimal action is worse than τ in the original MDP (a learner of the shaped reward can
end up with a policy that is not optimal); otherwise the shaping only broke ties.

Example:
    >>> import numpy as np
    >>> optimal_actions(np.array([[1.0, 1.0 - 1e-12, 0.0]]), tie_tolerance(np.ones(1))).tolist()
    [[True, True, False]]
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from planshape.invariance.augment import AugmentedMDP
from planshape.invariance.settings import Setting

__all__ = [
    "RELATIVE_TOLERANCE",
    "Comparison",
    "Counterexample",
    "InvarianceReport",
    "MdpVerdict",
    "optimal_actions",
    "tie_tolerance",
]

#: τ relative to the Q-value scale (see the module docstring)
RELATIVE_TOLERANCE = 1e-8
#: the largest shaped/original Q scale at which τ is still resolved: the solvers are accurate
#: to about 1e-12 of their scale, so at 10^3 times the original's their error is 1e-9 of it,
#: ten times below τ
MAX_SCALE_RATIO = 1e3


def tie_tolerance(*tables: np.ndarray, relative: float = RELATIVE_TOLERANCE) -> float:
    """τ = relative · max(1, max |Q| over ``tables``)."""
    scale = max([1.0] + [float(np.abs(q).max(initial=0.0)) for q in tables])
    return relative * scale


def optimal_actions(q: np.ndarray, tolerance: float) -> np.ndarray:
    """Boolean ``(n, n_actions)``: which actions are within ``tolerance`` of the best."""
    return q >= q.max(axis=1, keepdims=True) - tolerance


@dataclass(frozen=True)
class Counterexample:
    """One augmented state where the optimal actions differ.

    Attributes:
        state: the base MDP's state index; ``observation`` is what the classifiers saw there.
        progress: ``max_idx``; ``t``: the time index (``None`` in a stationary check).
        reset_state: whether a reset in ``state`` lands exactly here (progress as reset gives
            it, ``t = 0``).
        original_optimal, shaped_optimal: the optimal action sets.
        q_original, q_shaped: the Q-values of every action (in ``actions`` order).
        regret: how much original return the worst shaped-optimal action loses (≥ 0).
        harmful: ``regret`` exceeds the tolerance.
    """

    state: int
    augmented_state: int
    observation: list[float]
    progress: int
    t: int | None
    reset_state: bool
    actions: list[str]
    original_optimal: list[str]
    shaped_optimal: list[str]
    q_original: list[float]
    q_shaped: list[float]
    regret: float
    harmful: bool

    def describe(self) -> str:
        when = "" if self.t is None else f", t={self.t}"
        where = " (a reset state)" if self.reset_state else ""
        q_o = ", ".join(f"{a}={q:.6g}" for a, q in zip(self.actions, self.q_original, strict=True))
        q_s = ", ".join(f"{a}={q:.6g}" for a, q in zip(self.actions, self.q_shaped, strict=True))
        return (
            f"state {self.state} obs={self.observation} progress={self.progress}{when}{where}: "
            f"optimal original {{{', '.join(self.original_optimal)}}} vs shaped "
            f"{{{', '.join(self.shaped_optimal)}}}; regret {self.regret:.6g}"
            f"{'' if self.harmful else ' (ties only)'}; Q original [{q_o}]; Q shaped [{q_s}]"
        )


@dataclass(frozen=True)
class MdpVerdict:
    """The result of checking one shaping on one toy MDP in one setting.

    Attributes:
        mdp: the toy's name; ``shaping``: the potential's (or control's) name.
        setting: how it was solved (see :mod:`planshape.invariance.settings`).
        preserved: optimal action sets equal in every compared state (and appendix 8.1 held).
        time_dependent: whether the shaping was checked layer by layer in time.
        checked: compared (augmented state, time) pairs; ``mismatches`` differ, ``harmful``
            of them with a shaped-optimal action that is suboptimal originally.
        tolerance: τ relative to the Q scale.
        appendix_gap: max |Q⁺ − Q| between the augmented MDP with the original reward and the
            original MDP (appendix 8.1 says 0; anything above τ fails the verdict).
        augmented_states, state_action_pairs: size of the augmented MDP (per time layer).
        seconds: wall time of the check.
        counterexample: the mismatch with the largest regret, if any.
        not_a_potential: what the Q-tables cannot show, with its counterexample
            (:mod:`planshape.invariance.probes`): φ keeps state across calls, or γ^t·φ grows;
            a non-empty value fails the verdict.
    """

    mdp: str
    shaping: str
    setting: Setting
    preserved: bool
    time_dependent: bool
    checked: int
    mismatches: int
    harmful: int
    tolerance: float
    appendix_gap: float
    augmented_states: int
    state_action_pairs: int
    seconds: float
    counterexample: Counterexample | None = None
    not_a_potential: str = ""

    @property
    def status(self) -> str:
        if self.preserved:
            return "preserved"
        if self.not_a_potential:
            return "violated (not a potential)"
        if self.mismatches and not self.harmful:
            return "violated (ties)"
        return "violated"

    def to_dict(self) -> dict[str, Any]:
        data = asdict(self)
        data["setting"] = self.setting.to_dict()
        data["setting"]["label"] = self.setting.label
        data["setting"]["theory"] = self.setting.theory
        data["status"] = self.status
        return data


@dataclass(frozen=True)
class InvarianceReport:
    """Every verdict of one potential (or shaping) over the toy MDPs; JSON-serializable.

    ``preserved`` is true when every verdict is.
    """

    potential: str
    verdicts: tuple[MdpVerdict, ...]
    tolerance: float = RELATIVE_TOLERANCE
    notes: tuple[str, ...] = field(default=())

    @property
    def preserved(self) -> bool:
        return all(v.preserved for v in self.verdicts)

    @property
    def mdps(self) -> list[str]:
        return list(dict.fromkeys(v.mdp for v in self.verdicts))

    def preserved_on(self, mdp: str) -> bool:
        return all(v.preserved for v in self.verdicts if v.mdp == mdp)

    def summary(self) -> str:
        """One line for a leaderboard: the verdict and where it fails.

        Example: ``"preserved on 18 of 18 checks"`` or
        ``"violated on maze-reach (finite-horizon-truncated γ=1 H=28); 17 of 18 preserved"``.
        """
        kept = sum(v.preserved for v in self.verdicts)
        if self.preserved:
            return f"preserved on {kept} of {len(self.verdicts)} checks"
        failed = "; ".join(f"{v.mdp} ({v.setting.label})" for v in self.verdicts if not v.preserved)
        return f"violated on {failed}; {kept} of {len(self.verdicts)} preserved"

    def to_dict(self) -> dict[str, Any]:
        return {
            "potential": self.potential,
            "preserved": self.preserved,
            "summary": self.summary(),
            "tolerance": {"relative": self.tolerance, "rule": "Q >= max Q - tol*max(1, max|Q|)"},
            "notes": list(self.notes),
            "mdps": [
                {
                    "mdp": mdp,
                    "preserved": self.preserved_on(mdp),
                    "checks": [v.to_dict() for v in self.verdicts if v.mdp == mdp],
                }
                for mdp in self.mdps
            ],
        }

    def to_json(self, **kwargs: Any) -> str:
        return json.dumps(self.to_dict(), **kwargs)


class Comparison:
    """Accumulates the comparison of original and shaped Q-tables, layer by layer.

    Args:
        aug: the augmented MDP (for observations and progress in counterexamples).
        compared: ``(n_x,)`` which augmented states are compared (reachable, non-terminal).
        relative: τ relative to the Q scale.
    """

    def __init__(self, aug: AugmentedMDP, compared: np.ndarray, relative: float):
        self.aug = aug
        self.compared = compared
        self.relative = relative
        self.checked = 0
        self.mismatches = 0
        self.harmful = 0
        self._best: tuple[float, int, int | None, np.ndarray, np.ndarray, float] | None = None

    def add(self, q_original: np.ndarray, q_shaped: np.ndarray, t: int | None) -> None:
        """Compare one layer: ``q_original`` is already lifted to the augmented states."""
        mask = self.compared
        if not mask.any():
            return
        tol = tie_tolerance(q_original[mask], relative=self.relative)
        best_o, best_s = optimal_actions(q_original, tol), optimal_actions(q_shaped, tol)
        differ = mask & np.any(best_o != best_s, axis=1)
        regret = q_original.max(axis=1) - np.where(best_s, q_original, np.inf).min(axis=1)
        self.checked += int(mask.sum())
        self.mismatches += int(differ.sum())
        self.harmful += int(np.sum(differ & (regret > tol)))
        if differ.any():
            candidates = np.flatnonzero(differ)
            x = int(candidates[np.argmax(regret[candidates])])
            if self._best is None or regret[x] > self._best[0]:
                self._best = (float(regret[x]), x, t, q_original[x].copy(), q_shaped[x].copy(), tol)

    def counterexample(self) -> Counterexample | None:
        if self._best is None:
            return None
        regret, x, t, q_o, q_s, tol = self._best
        aug, actions = self.aug, list(self.aug.mdp.actions)
        s, p = int(aug.state[x]), int(aug.plan_progress[x])
        pick = lambda q: [  # noqa: E731
            a for a, ok in zip(actions, optimal_actions(q[None], tol)[0], strict=True) if ok
        ]
        return Counterexample(
            state=s,
            augmented_state=x,
            observation=[round(float(v), 6) for v in aug.observation(x)],
            progress=p,
            t=t,
            reset_state=p == int(aug.reset_progress[s]) and t in (0, None),
            actions=actions,
            original_optimal=pick(q_o),
            shaped_optimal=pick(q_s),
            q_original=[float(v) for v in q_o],
            q_shaped=[float(v) for v in q_s],
            regret=regret,
            harmful=regret > tol,
        )
