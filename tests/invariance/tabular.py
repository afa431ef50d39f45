"""Test helpers: a Gymnasium view of a toy MDP, table potentials and bonuses, small random toys,
and a brute-force solver that enumerates policies (independent of the checker's solvers)."""

from __future__ import annotations

import itertools
from typing import Any

import gymnasium
import numpy as np

from planshape.invariance.augment import AugmentedMDP
from planshape.invariance.mdp import TabularMDP
from planshape.invariance.shaped import Shaping, Step
from planshape.invariance.toys import ToyProblem, chain_progress
from planshape.shaping.potentials import Potential, ShapingContext


class TabularEnv(gymnasium.Env):
    """Steps a :class:`TabularMDP` like an environment: ``reset`` to ``start``, ``step(a)``
    samples the next state; ``terminated`` when it is terminal. Records the states visited."""

    def __init__(self, mdp: TabularMDP, start: int, seed: int = 0):
        self.mdp = mdp
        self.start = start
        self.rng = np.random.default_rng(seed)
        obs = mdp.observations
        assert obs is not None
        self.observation_space = gymnasium.spaces.Box(-np.inf, np.inf, obs.shape[1:])
        self.action_space = gymnasium.spaces.Discrete(mdp.n_actions)
        self.state = start
        self.visited: list[int] = []

    def reset(self, *, seed: int | None = None, options: Any = None):
        self.state = self.start
        self.visited = [self.state]
        return self.mdp.observations[self.state].copy(), {}

    def step(self, action: int):
        P = self.mdp.transitions
        row = self.state * self.mdp.n_actions + int(action)
        lo, hi = P.indptr[row], P.indptr[row + 1]
        k = lo + self.rng.choice(hi - lo, p=P.data[lo:hi])
        self.state = int(P.indices[k])
        self.visited.append(self.state)
        reward = float(self.mdp.rewards[k])
        terminated = bool(self.mdp.terminal[self.state])
        return self.mdp.observations[self.state].copy(), reward, terminated, False, {}


def entry_index(mdp: TabularMDP, row: int, column: int) -> int:
    """The position in ``mdp.transitions.data`` of entry (row, column)."""
    P = mdp.transitions
    lo, hi = P.indptr[row], P.indptr[row + 1]
    (hits,) = np.nonzero(P.indices[lo:hi] == column)
    assert len(hits) == 1, (row, column)
    return int(lo + hits[0])


class TablePotential(Potential):
    """φ read from a table indexed by the state index ``obs[2]``, progress and time, as ``kind``
    says: ``"state"`` → table[s], ``"progress"`` → table[s, p], ``"time"`` → table[s, p, t]
    (t capped at the table's last index)."""

    def __init__(self, table: np.ndarray, kind: str):
        super().__init__()
        self.table = np.asarray(table, float)
        self.kind = kind
        self.time_dependent = kind == "time"

    def potential(self, ctx: ShapingContext) -> float:
        s = int(ctx.obs[2])
        if self.kind == "state":
            return float(self.table[s])
        if self.kind == "progress":
            return float(self.table[s, ctx.progress])
        return float(self.table[s, ctx.progress, min(ctx.t, self.table.shape[2] - 1)])


class TableBonus(Shaping):
    """An arbitrary bonus per stored transition of the augmented MDP (not potential-based)."""

    name = "table-bonus"

    def __init__(self, values: np.ndarray):
        self.values = np.asarray(values, float)

    def transition_bonus(self, aug: AugmentedMDP, step: Step) -> np.ndarray:
        return self.values


def chain_toy(
    *,
    labels: list[int],
    successors: list[list[list[int]]],
    weights: list[list[list[int]]],
    rewards: list[list[list[float]]],
    terminal: list[bool],
    regions: int,
    gamma: float,
    horizon: int,
) -> ToyProblem:
    """A small toy on a ``regions``-region chain plan: state ``s`` lies at ``(labels[s], 0)``
    (in region ``labels[s]``) or far away when its label is -1; ``successors[s][a]`` with
    integer ``weights`` and ``rewards``. Observations are ``(x, y, s)``."""
    n = len(labels)
    n_a = len(successors[0])
    positions = np.array(
        [(float(label), 0.0) if label >= 0 else (-10.0 - s, 0.0) for s, label in enumerate(labels)]
    )
    centres = np.array([(float(j), 0.0) for j in range(regions)])
    progress, geometry = chain_progress(centres, radius=0.3)
    rows = [
        (s, a, s2, w / sum(weights[s][a]), rewards[s][a][k])
        for s in range(n)
        for a in range(n_a)
        for k, (s2, w) in enumerate(zip(successors[s][a], weights[s][a], strict=True))
    ]
    s_, a_, s2_, p_, r_ = (list(col) for col in zip(*rows, strict=True))
    mdp = TabularMDP.from_transitions(
        n_states=n,
        actions=[f"a{i}" for i in range(n_a)],
        state=s_,
        action=a_,
        next_state=s2_,
        probability=p_,
        reward=r_,
        terminal=terminal,
        observations=np.column_stack([positions, np.arange(n)]),
    )
    return ToyProblem("chain-toy", "a generated test toy", mdp, progress, geometry, gamma, horizon)


# ---- brute force: enumerate deterministic policies -------------------------------------------


def _dense(aug: AugmentedMDP, per_entry: np.ndarray):
    """Dense C (terminal rows/columns zeroed) as (n, n_a, n) and expected rewards (n, n_a)."""
    mdp = aug.mdp
    n, n_a = mdp.n_states, mdp.n_actions
    C = np.zeros((n * n_a, n))
    P = mdp.transitions
    for row in range(n * n_a):
        for k in range(P.indptr[row], P.indptr[row + 1]):
            C[row, P.indices[k]] += P.data[k]
    r = (C * 0).sum(axis=1)
    r = np.zeros(n * n_a)
    np.add.at(r, mdp.entry_rows, P.data * per_entry)
    alive = ~mdp.terminal
    C = C * alive[None, :] * np.repeat(alive, n_a)[:, None]
    return C.reshape(n, n_a, n), r.reshape(n, n_a)


def brute_force_optimal_sets(
    aug: AugmentedMDP, per_entry: np.ndarray, gamma: float, tol: float
) -> np.ndarray:
    """Discounted: ``(n, n_a)`` bool, ``a`` optimal in ``x`` iff some deterministic policy that
    picks ``a`` in ``x`` has the optimal value in every non-terminal state (exact policy
    evaluation by linear solves; no Bellman backup)."""
    C, r = _dense(aug, per_entry)
    n, n_a = r.shape
    alive = np.flatnonzero(~aug.mdp.terminal)
    values = {}
    for choice in itertools.product(range(n_a), repeat=len(alive)):
        pi = np.zeros(n, int)
        pi[alive] = choice
        M = np.eye(n) - gamma * C[np.arange(n), pi]
        values[choice] = np.linalg.solve(M, r[np.arange(n), pi])
    best = np.max(np.stack(list(values.values())), axis=0)
    optimal = np.zeros((n, n_a), bool)
    for choice, v in values.items():
        if np.all(v[alive] >= best[alive] - tol):
            optimal[alive, list(choice)] = True
    return optimal


def brute_force_finite_sets(
    aug: AugmentedMDP, per_entry_at, gamma: float, horizon: int, tol: float
) -> dict[int, np.ndarray]:
    """Finite horizon, deterministic transitions: for every ``t``, ``(n, n_a)`` bool of the
    first actions of the best action sequences from each state (open loop = closed loop)."""
    mdp = aug.mdp
    n, n_a = mdp.n_states, mdp.n_actions
    P = mdp.transitions
    assert np.all(np.diff(P.indptr) == 1), "deterministic MDPs only"
    nxt = P.indices.reshape(n, n_a)
    sets = {}
    for t in range(horizon):
        reward_at = [np.asarray(per_entry_at(k)).reshape(n, n_a) for k in range(t, horizon)]
        optimal = np.zeros((n, n_a), bool)
        for x in range(n):
            if mdp.terminal[x]:
                continue
            returns = {}
            for seq in itertools.product(range(n_a), repeat=horizon - t):
                total, state, discount = 0.0, x, 1.0
                for k, a in enumerate(seq):
                    total += discount * reward_at[k][state, a]
                    state = nxt[state, a]
                    discount *= gamma
                    if mdp.terminal[state]:
                        break
                returns[seq] = total
            best = max(returns.values())
            for seq, value in returns.items():
                if value >= best - tol:
                    optimal[x, seq[0]] = True
        sets[t] = optimal
    return sets
