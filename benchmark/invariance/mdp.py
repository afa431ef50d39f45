"""The tabular MDP type: finite states and actions, sparse transitions, termination.

States and actions are integers. Transitions are one sparse matrix ``P`` of shape
``(n_states * n_actions, n_states)`` whose row ``s * n_actions + a`` is the distribution of the
next state after action ``a`` in state ``s``; rewards ``R(s, a, s')`` are stored per transition,
aligned with ``P.data``, so that a shaping term can be added transition by transition, exactly as
the shaping wrapper adds it step by step.

*Termination* is a property of the state entered: a step into a ``terminal`` state ends the
episode (the wrapper sees ``terminated=True``), collects that step's reward and nothing after.
The agent never acts in a terminal state, so those states are never compared.

Example:
    >>> mdp = TabularMDP.from_transitions(
    ...     n_states=2, actions=("stay", "go"),
    ...     state=[0, 0, 1, 1], action=[0, 1, 0, 1], next_state=[0, 1, 1, 1],
    ...     probability=[1.0, 1.0, 1.0, 1.0], reward=[0.0, 1.0, 0.0, 0.0],
    ...     terminal=[False, True])
    >>> mdp.expected_reward().tolist()
    [[0.0, 1.0], [0.0, 0.0]]
    >>> mdp.continuation.toarray().tolist()  # no value flows out of terminal states
    [[1.0, 0.0], [0.0, 0.0], [0.0, 0.0], [0.0, 0.0]]
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from planshape.errors import BadInputError
from planshape.invariance.solve import Dynamics

__all__ = ["TabularMDP"]

#: how far a row of probabilities may sum from 1
PROBABILITY_TOLERANCE = 1e-9


@dataclass(frozen=True, eq=False)
class TabularMDP:
    """A finite MDP with sparse transitions (build one with :meth:`from_transitions`).

    Attributes:
        transitions: ``P``, CSR of shape ``(n_states * n_actions, n_states)``, rows sum to 1.
        rewards: ``R(s, a, s')`` of every stored entry of ``transitions`` (aligned with its
            ``data``).
        terminal: ``(n_states,)`` bool: entering such a state ends the episode.
        actions: the actions' names (their count is ``n_actions``).
        observations: ``(n_states, obs_dim)`` what classifiers and potentials see in each state,
            or ``None`` (an augmented MDP keeps its observations in its base MDP).
    """

    transitions: sp.csr_array
    rewards: np.ndarray
    terminal: np.ndarray
    actions: tuple[str, ...]
    observations: np.ndarray | None = None

    @property
    def n_states(self) -> int:
        return self.transitions.shape[1]

    @property
    def n_actions(self) -> int:
        return len(self.actions)

    @property
    def n_pairs(self) -> int:
        """Number of state-action pairs (rows of ``transitions``)."""
        return self.transitions.shape[0]

    @functools.cached_property
    def entry_rows(self) -> np.ndarray:
        """The row (``s * n_actions + a``) of every stored transition."""
        counts = np.diff(self.transitions.indptr)
        return np.repeat(np.arange(self.n_pairs, dtype=np.int64), counts)

    def expected(self, per_entry: np.ndarray) -> np.ndarray:
        """``Σ_s' P(s'|s, a) · per_entry`` for every pair: shape ``(n_states, n_actions)``."""
        totals = np.bincount(
            self.entry_rows, weights=self.transitions.data * per_entry, minlength=self.n_pairs
        )
        return totals.reshape(self.n_states, self.n_actions)

    def expected_reward(self) -> np.ndarray:
        """``r(s, a) = E[R(s, a, s')]``, shape ``(n_states, n_actions)``."""
        return self.expected(self.rewards)

    @functools.cached_property
    def continuation(self) -> sp.csr_array:
        """``P`` with every terminal state's column and rows zeroed: ``Q = r + γ·C·V`` then
        never carries value out of, or into, a terminal state."""
        keep = (~self.terminal).astype(float)
        rows = np.repeat(keep, self.n_actions)
        data = self.transitions.data * keep[self.transitions.indices] * rows[self.entry_rows]
        matrix = sp.csr_array(
            (data, self.transitions.indices.copy(), self.transitions.indptr.copy()),
            shape=self.transitions.shape,
        )
        matrix.eliminate_zeros()  # in place: hence the copies above
        return matrix

    @functools.cached_property
    def dynamics(self) -> Dynamics:
        """:attr:`continuation` prepared for the solvers (action-major, with self-loops)."""
        return Dynamics.from_continuation(self.continuation, self.n_actions)

    @classmethod
    def from_transitions(
        cls,
        *,
        n_states: int,
        actions: Sequence[str],
        state: Sequence[int] | np.ndarray,
        action: Sequence[int] | np.ndarray,
        next_state: Sequence[int] | np.ndarray,
        probability: Sequence[float] | np.ndarray,
        reward: Sequence[float] | np.ndarray,
        terminal: Sequence[bool] | np.ndarray | None = None,
        observations: np.ndarray | None = None,
    ) -> TabularMDP:
        """An MDP from one row per transition ``(s, a, s', P(s'|s, a), R(s, a, s'))``.

        Repeated ``(s, a, s')`` rows are merged (probabilities add up, rewards are averaged by
        probability); zero-probability rows are dropped. Every ``(s, a)`` must have a
        distribution summing to 1.
        """
        n_actions = len(actions)
        arrays = [np.asarray(v).ravel() for v in (state, action, next_state, probability, reward)]
        s, a, s2 = (np.asarray(v, dtype=np.int64) for v in arrays[:3])
        p, r = (np.asarray(v, dtype=float) for v in arrays[3:])
        if not len(s) == len(a) == len(s2) == len(p) == len(r):
            raise BadInputError("state, action, next_state, probability, reward differ in length")
        for name, values, bound in (
            ("state", s, n_states),
            ("action", a, n_actions),
            ("next_state", s2, n_states),
        ):
            if len(values) and (values.min() < 0 or values.max() >= bound):
                raise BadInputError(f"{name} out of range [0, {bound})")
        if np.any(p < 0) or not np.all(np.isfinite(p)) or not np.all(np.isfinite(r)):
            raise BadInputError("probabilities must be finite and >= 0, rewards finite")
        keep = p > 0
        s, a, s2, p, r = s[keep], a[keep], s2[keep], p[keep], r[keep]
        rows = s * n_actions + a
        key = rows * n_states + s2
        unique, inverse = np.unique(key, return_inverse=True)
        prob = np.bincount(inverse, weights=p)
        rewards = np.bincount(inverse, weights=p * r) / prob
        u_rows, u_cols = unique // n_states, unique % n_states
        n_rows = n_states * n_actions
        sums = np.bincount(u_rows, weights=prob, minlength=n_rows)
        bad = np.flatnonzero(np.abs(sums - 1.0) > PROBABILITY_TOLERANCE)
        if len(bad):
            s_bad, a_bad = divmod(int(bad[0]), n_actions)
            raise BadInputError(
                f"the next-state distribution of state {s_bad}, action {actions[a_bad]!r} sums "
                f"to {sums[bad[0]]:g}, not 1 ({len(bad)} such pairs)"
            )
        indptr = np.concatenate([[0], np.cumsum(np.bincount(u_rows, minlength=n_rows))])
        transitions = sp.csr_array((prob, u_cols, indptr), shape=(n_rows, n_states))
        term = np.zeros(n_states, bool) if terminal is None else np.asarray(terminal, bool)
        if term.shape != (n_states,):
            raise BadInputError(f"terminal must have shape ({n_states},), not {term.shape}")
        if observations is not None:
            observations = np.asarray(observations, dtype=float)
            if observations.ndim != 2 or len(observations) != n_states:
                raise BadInputError(
                    f"observations must have shape ({n_states}, obs_dim), not {observations.shape}"
                )
        return cls(transitions, rewards, term, tuple(actions), observations)
