"""Probes of what a table of φ cannot show: whether φ is a function of the augmented state at
all, and whether a time-dependent φ vanishes under discounting.

The checker solves the shaped MDP from a table of φ(x, t), filled once per state in one order.
Two kinds of potential pass that test while changing what a learner optimizes:

* **hidden state** — φ depends on its own earlier calls (a counter, a running total, the
  previous output), so what the shaping wrapper computes along an episode is not the table:
  a disguised bonus. :func:`hidden_state` calls φ along simulated episodes, in the wrapper's
  order, then on the same states again in reverse order and in the table's, and reports the
  first state where the answers differ.
* **growth faster than 1/γ** — the discounted guarantee needs γ^t·φ(·, t) → 0; the checker
  caps a time-dependent φ's time index at the horizon H, which hides a φ ∝ c^t with c·γ > 1.
  :func:`growth` evaluates φ at t = H, 2H, … 32H and reports a γ^t·max|φ| that still grows.

A third probe, :func:`step_function_mismatch`, compares the step function a potential gives the
shaping wrapper (``specialize``) with the table, so that what trains is what was checked.

Each returns ``""`` when nothing was found, else one sentence with the counterexample.

Example:
    >>> from planshape.invariance.toys import make_toy
    >>> from planshape.shaping.potentials import make_potential
    >>> aug = make_toy("random-episodic").augmented
    >>> hidden_state(make_potential("plan-based"), aug, horizon=10)
    ''
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from planshape.invariance.augment import AugmentedMDP
from planshape.shaping.potentials import Potential

__all__ = ["growth", "hidden_state", "step_function_mismatch"]

#: simulated episodes, states re-evaluated in a shuffled order, and the probes' random seed
EPISODES, SHUFFLED, SEED = 8, 512, 0
#: doublings of the horizon at which a time-dependent φ is probed for growth
DOUBLINGS = 5


def _phi(potential: Potential, aug: AugmentedMDP, x: int, t: int) -> float:
    return potential(aug.context(x, t))


def _episodes(aug: AugmentedMDP, horizon: int, rng: np.random.Generator) -> list[list[int]]:
    """Random walks of the augmented MDP from reset states, as the wrapper would see them."""
    mdp, n_s = aug.mdp, aug.base.n_states
    transitions = mdp.transitions
    walks = []
    for _ in range(EPISODES):
        s = int(rng.integers(n_s))
        x = int(aug.reset_progress[s]) * n_s + s
        walk = [x]
        for _ in range(horizon):
            if mdp.terminal[x]:
                break
            row = x * mdp.n_actions + int(rng.integers(mdp.n_actions))
            start, end = transitions.indptr[row], transitions.indptr[row + 1]
            probabilities = transitions.data[start:end]
            x = int(
                rng.choice(transitions.indices[start:end], p=probabilities / probabilities.sum())
            )
            if not mdp.terminal[x]:  # the wrapper takes φ = 0 there without calling it
                walk.append(x)
        walks.append(walk)
    return walks


def hidden_state(
    potential: Potential, aug: AugmentedMDP, horizon: int, table: np.ndarray | None = None
) -> str:
    """The first augmented state where φ's answer depends on what was asked before, or ``""``.

    ``table`` is φ(·, 0) as the checker tabulated it (compared for a time-free potential)."""
    rng = np.random.default_rng(SEED)
    dynamic = potential.time_dependent
    asked: list[tuple[int, int]] = []
    for walk in _episodes(aug, horizon, rng):
        asked += [(x, t if dynamic else 0) for t, x in enumerate(walk)]
    reachable = np.flatnonzero(aug.reachable & ~aug.mdp.terminal)
    if reachable.size:
        sample = rng.choice(reachable, size=min(SHUFFLED, reachable.size), replace=False)
        asked += [(int(x), 0) for x in sample]
    first = [_phi(potential, aug, x, t) for x, t in asked]
    again = [_phi(potential, aug, x, t) for x, t in reversed(asked)][::-1]
    for (x, t), a, b in zip(asked, first, again, strict=True):
        c = table[x] if table is not None and not dynamic else b
        if not (
            np.isclose(a, b, rtol=1e-9, atol=1e-12) and np.isclose(a, c, rtol=1e-9, atol=1e-12)
        ):
            return _inconsistent(potential, aug, x, t, (a, b, c), table is not None and not dynamic)
    return ""


def step_function_mismatch(
    potential: Potential, aug: AugmentedMDP, table: np.ndarray, t: int = 0
) -> str:
    """The first augmented state where the potential's step function (what the shaping wrapper
    trains with, :meth:`planshape.shaping.potentials.Potential.specialize`) disagrees with
    ``table``, φ(·, t) as the checker tabulated it from ``potential(ctx)`` (a time-dependent
    potential's step function is given ``t``); ``""`` if none does or the potential has no step
    function."""
    reachable = np.flatnonzero(aug.reachable & ~aug.mdp.terminal)
    if not reachable.size:
        return ""
    step = potential.step_function(aug.context(int(reachable[0]), 0))
    if step is None:
        return ""
    timed = potential.time_dependent
    for x in reachable.tolist():
        obs, progress = aug.observation(x), int(aug.plan_progress[x])
        fast = potential.scale * (step(obs, progress, t) if timed else step(obs, progress))
        if not _same(fast, table[x]):
            at = f", t {t}" if timed else ""
            return (
                f"potential {potential.name!r}: its specialize() gives φ = {fast:.6g} at state "
                f"{int(aug.state[x])} (progress {progress}{at}) where potential() "
                f"gives {table[x]:.6g}; the shaping wrapper trains with specialize(), so it "
                "would train another φ than the one checked. Make them agree, or remove "
                "specialize"
            )
    return ""


def _same(a: float, b: float) -> bool:
    return bool(np.isclose(a, b, rtol=1e-9, atol=1e-12))


def _inconsistent(
    potential: Potential, aug: AugmentedMDP, x: int, t: int, values: Sequence[float], tabled: bool
) -> str:
    s, p = int(aug.state[x]), int(aug.plan_progress[x])
    a, b, c = values
    table = f", {c:.6g} in the checker's table" if tabled else ""
    return (
        f"potential {potential.name!r} is not a function of the augmented state (s, max_idx, t):"
        f" at state {s} (observation {np.round(aug.observation(x), 4).tolist()}, progress {p}, "
        f"t {t}) it returned {a:.6g} along an episode and {b:.6g} when asked again{table}; it "
        "keeps state across calls, so the wrapper's shaping is not a potential difference"
    )


def growth(potential: Potential, aug: AugmentedMDP, gamma: float, horizon: int) -> str:
    """A γ^t·max|φ(·, t)| that still grows at t = 32H, or ``""`` (time-dependent φ only)."""
    if not potential.time_dependent:
        return ""
    rng = np.random.default_rng(SEED)
    reachable = np.flatnonzero(aug.reachable & ~aug.mdp.terminal)
    if not reachable.size:
        return ""
    sample = rng.choice(reachable, size=min(SHUFFLED, reachable.size), replace=False)
    times = [horizon * 2**k for k in range(DOUBLINGS + 1)]
    weighted = []
    for t in times:
        values = np.array([_phi(potential, aug, int(x), t) for x in sample])
        weighted.append(float(gamma**t * np.abs(values).max()))
    if weighted[-1] > weighted[-2] and weighted[-1] > 1e-9:
        listed = ", ".join(f"t={t}: {w:.3g}" for t, w in zip(times, weighted, strict=True))
        return (
            f"potential {potential.name!r} grows faster than 1/γ (γ={gamma:g}): "
            f"γ^t·max|φ(·, t)| is {listed}; the discounted guarantee needs γ^t·φ → 0, so "
            "never reaching the goal can pay more than reaching it"
        )
    return ""
