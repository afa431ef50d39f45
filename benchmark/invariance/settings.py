"""The settings the invariance checker solves in, and what the theory says about each.

Let the shaped reward be the wrapper's ``F = γ·φ(x', t') − φ(x, t)`` over the augmented state
``x = (s, max_idx)`` (and time ``t``), with ``φ(x', t') = 0`` when the step *terminates*. Over
any trajectory that stops after ``T`` steps the shaping telescopes:

    Σ_{k<T} γ^k F_k = γ^T φ_T − φ(x_0, 0),      φ_T = 0 if the trajectory terminated.

The original reward never depends on progress, so the augmented MDP with the original reward
has the same optimal Q-values as the original MDP (the source paper's appendix 8.1, checked on
every toy as ``appendix_gap``). Whether the shaped MDP keeps the optimal actions depends on
what happens to ``γ^T φ_T``:

``discounted`` — γ < 1, infinite horizon; time limits are *truncations* that the learner
    bootstraps through (stable-baselines3 does), so the objective is the infinite-horizon one.
    ``γ^T φ_T → 0`` for bounded φ: preserved for every φ(s, max_idx) (Ng, Harada & Russell 1999
    on the augmented MDP) and every φ(s, max_idx, t) (Devlin & Kudenko 2012: the time-augmented
    MDP). A time-dependent φ is checked with its time index capped at ``horizon`` —
    φ(x, min(t, H)) — which is itself a valid dynamic potential, and which keeps the
    time-augmented MDP finite: the stationary part (t ≥ H) is solved by value iteration and the
    layers t < H by backward induction from it. Checked layers: t = 0 … H.
``finite-horizon`` — the episode *ends* at step ``H`` (the environment reports termination, so
    the wrapper's φ at ``H`` is 0); any γ ≤ 1, γ = 1 included ("undiscounted"). The shaping
    sums to ``−φ(x_t, t)`` from every time ``t``: preserved for every φ(s, max_idx, t).
    Checked layers: t = 0 … H−1.
``finite-horizon-truncated`` — the episode is *cut* at ``H`` by a time limit (truncation: the
    wrapper keeps φ(x_H, H), correctness rule 2) and the learner does **not** bootstrap, i.e.
    it maximizes the return of the first ``H`` steps. The shaping then sums to
    ``γ^{H−t} φ(x_H, H) − φ(x_t, t)``: a terminal bonus on the state reached at ``H``. Not
    covered by the theory; preserved only when φ(·, H) is constant on what can be reached at
    ``H``. Rule 2 is right for bootstrapping learners (``discounted``); this setting shows what
    it costs a learner that does not bootstrap.

Example:
    >>> Setting("finite-horizon", gamma=1.0, horizon=20).label
    'finite-horizon γ=1 H=20'
    >>> Setting.preset("truncated", gamma=0.9, horizon=20).covered_by_theory
    False
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from planshape.errors import BadInputError, UnknownIdError

__all__ = ["DEFAULT_PRESETS", "PRESETS", "THEORY", "Setting", "SettingKind"]

SettingKind = Literal["discounted", "finite-horizon", "finite-horizon-truncated"]

#: one line per kind: what is guaranteed, and by whom
THEORY: dict[str, str] = {
    "discounted": (
        "γ<1, infinite horizon (time limits bootstrapped): preserved for every φ(s, max_idx) "
        "[Ng et al. 1999 + appendix 8.1] and φ(s, max_idx, t) [Devlin & Kudenko 2012]; "
        "time-dependent φ checked with t capped at H"
    ),
    "finite-horizon": (
        "episode ends (terminates) at H, γ≤1: preserved for every φ(s, max_idx, t), since "
        "φ=0 at the end [Devlin & Kudenko 2012; Grześ 2017]"
    ),
    "finite-horizon-truncated": (
        "episode cut at H by a time limit (φ(s_H) kept), no bootstrapping: NOT covered; the "
        "shaped return gains γ^(H−t)·φ(s_H, H), preserved only if φ(·, H) is constant"
    ),
}

#: named settings for the command line: kind, and whether γ is the toy's or 1
PRESETS: dict[str, tuple[SettingKind, bool]] = {
    "discounted": ("discounted", False),
    "finite-horizon": ("finite-horizon", False),
    "undiscounted": ("finite-horizon", True),
    "truncated": ("finite-horizon-truncated", True),
    "truncated-discounted": ("finite-horizon-truncated", False),
}

#: the settings the theory covers: what ``check_potential`` runs unless told otherwise
DEFAULT_PRESETS: tuple[str, ...] = ("discounted", "finite-horizon", "undiscounted")


@dataclass(frozen=True)
class Setting:
    """One way of solving a toy MDP.

    Attributes:
        kind: ``"discounted"``, ``"finite-horizon"`` or ``"finite-horizon-truncated"`` (see the
            module docstring).
        gamma: the discount, which is also the shaping's γ.
        horizon: the episode length ``H`` of the finite-horizon kinds; for ``"discounted"``, the
            cap on a time-dependent potential's time index.
    """

    kind: SettingKind
    gamma: float
    horizon: int

    def __post_init__(self) -> None:
        if self.kind not in THEORY:
            raise UnknownIdError("setting kind", self.kind, THEORY)
        if not 0 < self.gamma <= 1:
            raise BadInputError(f"gamma must be in (0, 1], not {self.gamma}")
        if self.kind == "discounted" and self.gamma >= 1:
            raise BadInputError("the discounted setting needs gamma < 1")
        if self.horizon < 1:
            raise BadInputError(f"the horizon must be at least 1, not {self.horizon}")

    @classmethod
    def preset(cls, name: str, *, gamma: float, horizon: int) -> Setting:
        """The named setting for a toy whose own discount is ``gamma``."""
        if name not in PRESETS:
            raise UnknownIdError("setting", name, PRESETS)
        kind, undiscounted = PRESETS[name]
        return cls(kind, 1.0 if undiscounted else gamma, horizon)

    @property
    def finite(self) -> bool:
        return self.kind != "discounted"

    @property
    def covered_by_theory(self) -> bool:
        """Whether potential-based shaping is guaranteed to preserve optimal actions here."""
        return self.kind != "finite-horizon-truncated"

    @property
    def theory(self) -> str:
        return THEORY[self.kind]

    @property
    def label(self) -> str:
        return f"{self.kind} γ={self.gamma:g} H={self.horizon}"

    def to_dict(self) -> dict[str, object]:
        return {
            "kind": self.kind,
            "gamma": self.gamma,
            "horizon": self.horizon,
            "covered_by_theory": self.covered_by_theory,
        }
