"""The augmented MDP over (s, max_idx): the state the shaping wrapper actually shapes.

Appendix 8.1 of the source paper: let ``x = (s, n)`` with ``n`` the plan progress; a step
``s → s'`` moves ``n`` to ``max(n, furthest subgoal reached in s')`` and the reward stays
``R(s, a, s')``. This module builds that MDP from a :class:`TabularMDP` and the task's
:class:`PlanProgress`, with one batched call of :meth:`PlanProgress.advance` over every
``(progress, next observation)`` pair — the same classifiers and reached test the wrapper uses —
and evaluates potentials through :class:`ShapingContext`, exactly as the wrapper builds it.

Layout: ``x = p · n_states + s``, so the transition rows of progress ``p`` are the base MDP's
rows with next states relabelled ``(s', advance(p, s'))``. Every combination ``(s, p)`` is a
state of the augmented MDP, but the wrapper only ever visits some: a reset in ``s0`` puts it in
``(s0, max(0, furthest(s0)))``, and progress then grows along the transitions.
:attr:`AugmentedMDP.reachable` marks the states reachable from a reset in *any* state (a breadth-
first search over the transition graph); only those are compared. (Unreachable combinations
matter: in an episodic task, full progress is only reached in the terminal goal, so a
non-terminal state with full progress never occurs.)

Example:
    >>> from planshape.invariance.toys import make_toy
    >>> toy = make_toy("random-episodic")
    >>> aug = toy.augmented
    >>> aug.n_states == toy.mdp.n_states * aug.n_progress
    True
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from scipy.sparse import csgraph

from planshape.errors import BadInputError, PlanshapeError, PotentialValueError
from planshape.invariance.mdp import TabularMDP
from planshape.shaping.potentials import Geometry, Potential, ShapingContext, read_only
from planshape.shaping.progress import PlanProgress

__all__ = ["AugmentedMDP", "augment"]


@dataclass(eq=False)
class AugmentedMDP:
    """A base MDP with plan progress folded into its state (build with :func:`augment`).

    Attributes:
        base: the original MDP.
        progress: the plan's subgoals and the reached test.
        geometry: the task's ``locate``/``positions`` hooks, handed to potentials.
        mdp: the augmented MDP, state ``x = p · base.n_states + s``.
        state: ``(n_x,)`` the base state ``s`` of each ``x``.
        plan_progress: ``(n_x,)`` the progress ``p`` of each ``x``.
        reset_progress: ``(base.n_states,)`` the progress after a reset in ``s``:
            ``max(0, furthest subgoal reached in s)``.
        reachable: ``(n_x,)`` whether the wrapper can be in ``x``: reachable from a reset in
            some state (a reset state itself included).
    """

    base: TabularMDP
    progress: PlanProgress
    geometry: Geometry | None
    mdp: TabularMDP
    state: np.ndarray
    plan_progress: np.ndarray
    reset_progress: np.ndarray
    reachable: np.ndarray

    @property
    def n_progress(self) -> int:
        return self.progress.final + 1

    @property
    def n_states(self) -> int:
        return self.mdp.n_states

    @functools.cached_property
    def entry_actions(self) -> np.ndarray:
        """The action of every stored transition of :attr:`mdp`."""
        return self.mdp.entry_rows % self.mdp.n_actions

    @functools.cached_property
    def entry_states(self) -> np.ndarray:
        """The augmented state ``x`` every stored transition of :attr:`mdp` leaves."""
        return self.mdp.entry_rows // self.mdp.n_actions

    @property
    def entry_next(self) -> np.ndarray:
        """The augmented state ``x'`` every stored transition enters."""
        return self.mdp.transitions.indices

    @functools.cached_property
    def entry_terminates(self) -> np.ndarray:
        """Whether every stored transition enters a terminal state."""
        return self.mdp.terminal[self.entry_next]

    @functools.cached_property
    def observations(self) -> np.ndarray:
        """The base MDP's observations, read-only (its rows too: a potential is handed one
        without a view per call)."""
        if self.base.observations is None:
            raise BadInputError("the base MDP has no observations to evaluate a potential on")
        return read_only(self.base.observations)

    def observation(self, x: int) -> np.ndarray:
        """The observation of augmented state ``x`` (read-only)."""
        return self.observations[self.state[x]]

    def context(self, x: int, t: int) -> ShapingContext:
        """The context the shaping wrapper builds for augmented state ``x`` at time ``t``."""
        return ShapingContext(
            obs=self.observation(x),
            progress=int(self.plan_progress[x]),
            t=t,
            subgoals=self.progress.subgoals,
            geometry=self.geometry,
            abstraction=self.progress.abstraction,
        )

    def lift(self, base_values: np.ndarray) -> np.ndarray:
        """Per-base-state values (``(n_states, …)``) repeated for every progress value."""
        return base_values[self.state]

    def potential_values(self, potential: Potential, t: int) -> np.ndarray:
        """φ(x, t) of every augmented state, with the context the wrapper would build.

        Raises :class:`BadInputError` naming the state when the potential fails on it (a
        submitted potential that raises or returns NaN is bad input).
        """
        observations = self.observations
        subgoals, abstraction = self.progress.subgoals, self.progress.abstraction
        values = np.empty(self.n_states)
        x = 0
        try:
            # the context of :meth:`context`, built inline: this loop visits every state
            for x, (s, p) in enumerate(
                zip(self.state.tolist(), self.plan_progress.tolist(), strict=True)
            ):
                values[x] = potential(
                    ShapingContext(
                        obs=observations[s],
                        progress=p,
                        t=t,
                        subgoals=subgoals,
                        geometry=self.geometry,
                        abstraction=abstraction,
                    )
                )
        except BadInputError as exc:
            if not isinstance(exc, PotentialValueError):
                raise
            s, p = int(self.state[x]), int(self.plan_progress[x])
            raise PotentialValueError(
                f"{exc} (at state {s} of the toy: observation "
                f"{np.round(observations[s], 4).tolist()}, progress {p}, t {t})"
            ) from None
        except Exception as exc:  # a submitted potential's own failure is bad input
            s, p = int(self.state[x]), int(self.plan_progress[x])
            kind = "failed" if isinstance(exc, PlanshapeError) else f"raised {type(exc).__name__}"
            raise BadInputError(
                f"potential {potential.name!r} {kind} at state {s} (observation "
                f"{np.round(observations[s], 4).tolist()}, progress {p}, t {t}): {exc}"
            ) from exc
        return values


def augment(base: TabularMDP, progress: PlanProgress, geometry: Any = None) -> AugmentedMDP:
    """Fold plan progress into ``base``'s state (see the module docstring)."""
    if base.observations is None:
        raise BadInputError("augmenting needs the base MDP's observations (what classifiers see)")
    n_s, n_a, n_p = base.n_states, base.n_actions, progress.final + 1
    observations = base.observations
    # one batched call: advanced[p, s'] = max(p, furthest subgoal reached in s')
    advanced = np.asarray(progress.advance(np.arange(n_p)[:, None], observations), np.int64)
    advanced = np.broadcast_to(advanced, (n_p, n_s))
    reset = np.asarray(progress.initial(observations), np.int64).reshape(n_s)
    P = base.transitions
    nnz = P.nnz
    indices = (advanced[:, P.indices] * n_s + P.indices[None, :]).ravel()
    indptr = (P.indptr[None, :-1] + nnz * np.arange(n_p)[:, None]).ravel()
    indptr = np.concatenate([indptr, [n_p * nnz]])
    transitions = sp.csr_array(
        (np.tile(P.data, n_p), indices, indptr), shape=(n_p * n_s * n_a, n_p * n_s)
    )
    mdp = TabularMDP(
        transitions=transitions,
        rewards=np.tile(base.rewards, n_p),
        terminal=np.tile(base.terminal, n_p),
        actions=base.actions,
    )
    state = np.tile(np.arange(n_s), n_p)
    plan_progress = np.repeat(np.arange(n_p), n_s)
    return AugmentedMDP(
        base=base,
        progress=progress,
        geometry=geometry,
        mdp=mdp,
        state=state,
        plan_progress=plan_progress,
        reset_progress=reset,
        reachable=_reachable(mdp, reset * n_s + np.arange(n_s)),
    )


def _reachable(mdp: TabularMDP, starts: np.ndarray) -> np.ndarray:
    """States reachable from ``starts`` (acting in non-terminal states only)."""
    n = mdp.n_states
    source = mdp.entry_rows // mdp.n_actions
    moves = ~mdp.terminal[source]
    # node n is a virtual root with an edge to every start
    rows = np.concatenate([source[moves], np.full(len(starts), n)])
    cols = np.concatenate([mdp.transitions.indices[moves], starts])
    graph = sp.csr_array((np.ones(len(rows), np.int8), (rows, cols)), shape=(n + 1, n + 1))
    order = csgraph.breadth_first_order(graph, n, directed=True, return_predecessors=False)
    reachable = np.zeros(n + 1, bool)
    reachable[order] = True
    return reachable[:n]
