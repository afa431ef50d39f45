"""Exact optimal Q-values of tabular MDPs: value iteration and backward induction, vectorized.

Both solvers work on the *continuation* matrix ``C`` (the transition matrix with terminal
states' columns and rows zeroed, :attr:`TabularMDP.continuation`) and expected rewards
``r(s, a)``, and return ``Q(s, a) = r(s, a) + γ Σ_s' C(s'|s, a) V(s')``. They first put ``C``
in action-major row order (:class:`Dynamics`, row ``a · n_states + s``) so that the maximum over
actions is a reduction over contiguous rows; one backup is one sparse matrix-vector product and
a few vector operations.

* :func:`value_iteration` (γ < 1, infinite horizon) iterates the *Jacobi* backup (Puterman
  1994, §6.3.3), which treats each action's self-loop exactly,

      V(s) ← max_a [r(s, a) + γ Σ_{s'≠s} C(s'|s, a) V(s')] / (1 − γ C(s|s, a)),

  a γ-contraction with the same fixed point as the ordinary backup ``T``, much faster where
  "stay" actions loop. Every iteration also applies ``T`` to the same ``V`` (the same product)
  and stops on McQueen's bounds for it: with ``δ = TV − V``,

      TV + γ/(1−γ)·min δ  ≤  V*  ≤  TV + γ/(1−γ)·max δ

  (0 joins ``δ``'s range when probability leaks out through termination). It returns the
  bracket's midpoint once the bracket is narrower than ``1e-10 · max(1, max|V|)``, a hundred
  times below the verdicts' tie tolerance. The bounds hold whatever ``V`` is, so an ``initial``
  guess only changes the speed, never the result.
* :func:`backward_induction` (finite horizon ``H``, any γ ≤ 1) yields ``Q_t`` for
  ``t = H−1, …, 0`` from ``V_H`` (0 by default) with a reward that may depend on ``t``.

Example:
    >>> import numpy as np, scipy.sparse as sp
    >>> C = sp.csr_array(np.array([[1.0, 0.0], [0.0, 1.0], [0.0, 1.0], [0.0, 1.0]]))
    >>> r = np.array([[0.0, 0.0], [1.0, 1.0]])   # state 1 pays 1 per step
    >>> solution = value_iteration(C, r, gamma=0.5)
    >>> np.round(solution.q, 9).tolist()   # in state 0, waiting is worth 0.5·V(0) = 0.5
    [[0.5, 1.0], [2.0, 2.0]]
    >>> [(t, q.tolist()) for t, q in backward_induction(C, lambda t: r, gamma=1.0, horizon=2)]
    [(1, [[0.0, 0.0], [1.0, 1.0]]), (0, [[0.0, 1.0], [2.0, 2.0]])]
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from planshape.errors import BadInputError, PlanshapeError

__all__ = [
    "RELATIVE_ACCURACY",
    "Dynamics",
    "NotConvergedError",
    "ValueIterationResult",
    "backward_induction",
    "value_iteration",
]

#: value iteration stops when V* is bracketed to this, relative to max(1, max|V|)
RELATIVE_ACCURACY = 1e-10


class NotConvergedError(PlanshapeError):
    """Value iteration hit its iteration limit before its error bound met the tolerance."""


@dataclass(frozen=True, eq=False)
class Dynamics:
    """``C`` in action-major row order, prepared once per MDP (see the module docstring).

    Attributes:
        matrix: ``C`` with row ``a · n_states + s`` = row ``s · n_actions + a`` of ``C``.
        self_loops: ``(n_actions, n_states)``: ``C(s|s, a)``.
        leaks: whether some row sums to less than 1 (termination, or a terminal state's row).
    """

    matrix: sp.csr_array
    self_loops: np.ndarray
    leaks: bool

    @property
    def n_actions(self) -> int:
        return self.self_loops.shape[0]

    @property
    def n_states(self) -> int:
        return self.self_loops.shape[1]

    @classmethod
    def from_continuation(cls, continuation: sp.csr_array, n_actions: int) -> Dynamics:
        n_rows, n_states = continuation.shape
        if n_rows != n_states * n_actions:
            raise BadInputError(
                f"continuation has shape {continuation.shape}, expected "
                f"({n_states * n_actions}, {n_states}) for {n_actions} actions"
            )
        order = (np.arange(n_states)[None, :] * n_actions + np.arange(n_actions)[:, None]).ravel()
        matrix = sp.csr_array(continuation)[order]
        rows = np.repeat(np.arange(matrix.shape[0]), np.diff(matrix.indptr))
        on_diagonal = matrix.indices == rows % n_states
        self_loops = np.bincount(
            rows[on_diagonal], weights=matrix.data[on_diagonal], minlength=matrix.shape[0]
        ).reshape(n_actions, n_states)
        leaks = bool(np.any(np.asarray(matrix.sum(axis=1)) < 1 - 1e-12))
        return cls(matrix, self_loops, leaks)


@dataclass(frozen=True)
class ValueIterationResult:
    """Optimal Q-values and how they were obtained.

    Attributes:
        q: ``(n_states, n_actions)`` optimal Q-values.
        iterations: backups performed.
        error_bound: a bound on ``max |V − V*|`` of the values ``q`` was computed from.
    """

    q: np.ndarray
    iterations: int
    error_bound: float


def _dynamics(continuation: Dynamics | sp.sparray | sp.spmatrix, n_actions: int) -> Dynamics:
    if isinstance(continuation, Dynamics):
        if continuation.n_actions != n_actions:
            raise BadInputError(
                f"dynamics have {continuation.n_actions} actions, rewards {n_actions}"
            )
        return continuation
    return Dynamics.from_continuation(continuation, n_actions)


def _check_gamma(gamma: float, upper: float) -> None:
    if not 0 <= gamma <= upper:
        raise BadInputError(f"gamma must be in [0, {upper:g}], not {gamma}")


def value_iteration(
    continuation: Dynamics | sp.sparray | sp.spmatrix,
    rewards: np.ndarray,
    gamma: float,
    *,
    initial: np.ndarray | None = None,
    relative_accuracy: float = RELATIVE_ACCURACY,
    max_iterations: int = 1_000_000,
    jacobi: bool = True,
) -> ValueIterationResult:
    """Optimal discounted Q-values of an infinite-horizon MDP (γ < 1), see the module docstring.

    Args:
        continuation: ``C`` (shape ``(n_states * n_actions, n_states)``, rows sum to ≤ 1), or
            its :class:`Dynamics`.
        rewards: ``r``, shape ``(n_states, n_actions)``.
        gamma: the discount, 0 ≤ γ < 1.
        initial: a first guess of ``V*`` (zeros by default); it changes the speed only.
        relative_accuracy: the bracket on ``V*`` must be narrower than this times
            ``max(1, max|V|)``.
        max_iterations: give up (:class:`NotConvergedError`) after this many backups.
        jacobi: iterate the Jacobi backup (default) or the ordinary one; both stop on the
            ordinary backup's bounds, so they agree to the accuracy asked for.
    """
    if gamma >= 1:
        raise BadInputError("value iteration needs gamma < 1; use a finite horizon for gamma = 1")
    _check_gamma(gamma, 1.0)
    n_states, n_actions = rewards.shape
    dyn = _dynamics(continuation, n_actions)
    if dyn.n_states != n_states:
        raise BadInputError(f"dynamics have {dyn.n_states} states, rewards {n_states}")
    r = np.ascontiguousarray(rewards.T)
    loops = dyn.self_loops
    denominator = 1.0 - gamma * loops
    factor = gamma / (1 - gamma)
    values = np.zeros(n_states) if initial is None else np.array(initial, dtype=float)
    for iteration in range(1, max_iterations + 1):
        q = r + gamma * (dyn.matrix @ values).reshape(n_actions, n_states)
        backed_up = q.max(axis=0)
        delta = backed_up - values
        low, high = float(delta.min()), float(delta.max())
        if dyn.leaks:
            low, high = min(low, 0.0), max(high, 0.0)
        if factor * (high - low) <= relative_accuracy * max(1.0, float(np.abs(backed_up).max())):
            values = backed_up + factor * (high + low) / 2
            q = r + gamma * (dyn.matrix @ values).reshape(n_actions, n_states)
            return ValueIterationResult(q.T, iteration, factor * (high - low) / 2)
        # Jacobi: from the same product, take each action's self-loop out and solve for it
        values = ((q - gamma * loops * values) / denominator).max(axis=0) if jacobi else backed_up
    raise NotConvergedError(
        f"value iteration did not converge in {max_iterations} backups (gamma={gamma}); "
        "raise max_iterations or use a finite horizon"
    )


def backward_induction(
    continuation: Dynamics | sp.sparray | sp.spmatrix,
    rewards_at: Callable[[int], np.ndarray],
    gamma: float,
    horizon: int,
    *,
    final_values: np.ndarray | None = None,
) -> Iterator[tuple[int, np.ndarray]]:
    """Yield ``(t, Q_t)`` for ``t = horizon−1, …, 0`` of a finite-horizon MDP.

    Args:
        continuation: ``C`` as for :func:`value_iteration`, or its :class:`Dynamics`.
        rewards_at: ``t -> r_t``, the expected reward of a step taken at time ``t`` (from ``t``
            to ``t + 1``), shape ``(n_states, n_actions)``.
        gamma: the discount, 0 ≤ γ ≤ 1.
        horizon: ``H`` ≥ 1, the number of steps.
        final_values: ``V_H`` (zeros by default: the episode ends at ``H``).
    """
    if horizon < 1:
        raise BadInputError(f"the horizon must be at least 1 step, not {horizon}")
    _check_gamma(gamma, 1.0)
    first = rewards_at(horizon - 1)
    n_states, n_actions = first.shape
    dyn = _dynamics(continuation, n_actions)
    values = np.zeros(n_states) if final_values is None else np.asarray(final_values, float)
    for t in range(horizon - 1, -1, -1):
        rewards = first if t == horizon - 1 else rewards_at(t)
        q = rewards.T + gamma * (dyn.matrix @ values).reshape(n_actions, n_states)
        yield t, q.T
        values = q.max(axis=0)
