"""Statistics: pure functions on arrays of run scores (as rliable's ``metrics.py``).

Arrays in, numbers out: no rows, no printing, no files. The definitions follow rliable
(Agarwal et al., 2021, "Deep RL at the edge of the statistical precipice"), reimplemented with
numpy/scipy because rliable 1.2 does not import next to pandas 3:

* :func:`iqm` — interquartile mean over all runs of all tasks (``scipy.stats.trim_mean(x, 0.25)``
  over the flattened scores); :func:`mean`, :func:`optimality_gap`;
* :func:`stratified_bootstrap_ci` — percentile interval of a statistic under the stratified
  bootstrap: runs are resampled with replacement *within* each task;
* :func:`probability_of_improvement` — the Mann-Whitney form, averaged over tasks:
  ``P(X > Y) = mean over tasks of P(X_i > Y_j) + 0.5 P(X_i = Y_j)``, with
  :func:`probability_of_improvement_ci` resampling X and Y independently within each task;
* :func:`normalized_score`, :func:`curve_area`, :func:`learning_curve`.

Scores are an array of run scores (one task) or a mapping task -> run scores (:data:`Scores`).

Why not ``scipy.stats.bootstrap`` (measured on the committed leaderboards, 2000 resamples, seed
0): across tasks it cannot stratify — resampling the pooled runs instead of the runs within each
task moves the bounds of the IQM of normalized success by up to 0.667 on the 23 across-task rows
of two or more tasks. Within one task its percentile interval draws the very same resamples
(``rng=np.random.default_rng(seed)``, ``method="percentile"``; for P(improve) ``paired=False``),
and the bounds of IQM and mean final success and of P(improve over sparse) agree exactly on all
177 cells of two or more seeds; but its percentile arithmetic differs in the last bits, so that
21 of the 6409 numbers of the four ``summary.json`` change, by at most 4.6e-15 (none visible
at the leaderboard's 2-3 decimals). The intervals are therefore computed here, as before.

Example:
    >>> float(iqm([0.0, 0.5, 0.6, 1.0]))
    0.55
    >>> ci = stratified_bootstrap_ci({"reach": [0.8, 0.9, 1.0], "push": [0.1, 0.2, 0.3]}, iqm)
    >>> round(ci.value, 3), ci.low <= ci.value <= ci.high
    (0.55, True)
    >>> probability_of_improvement({"reach": [1.0, 1.0]}, {"reach": [0.0, 1.0]})
    0.75
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping, Sequence
from typing import Any, NamedTuple

import numpy as np
import scipy.stats

from planshape.errors import BadInputError

__all__ = [
    "Interval",
    "Scores",
    "by_task",
    "curve_area",
    "iqm",
    "learning_curve",
    "mean",
    "normalized_score",
    "optimality_gap",
    "percentile_interval",
    "probability_of_improvement",
    "probability_of_improvement_ci",
    "stratified_bootstrap",
    "stratified_bootstrap_ci",
]

Scores = Mapping[str, "Sequence[float] | np.ndarray"] | Sequence[float] | np.ndarray


class Interval(NamedTuple):
    """A point estimate with its confidence interval (all plain floats; NaN when undefined)."""

    value: float
    low: float
    high: float


def _flat(x: Scores) -> np.ndarray:
    if isinstance(x, Mapping):
        parts = [np.asarray(x[k], dtype=float).ravel() for k in sorted(x)]
        return np.concatenate(parts) if parts else np.empty(0)
    return np.asarray(x, dtype=float)


def iqm(x: Scores, axis: int | None = None) -> Any:
    """Interquartile mean: the mean of the middle 50% of scores (rliable's ``aggregate_iqm``).

    ``x`` is an array of run scores (any shape, flattened when ``axis`` is None) or a mapping
    task -> scores, whose runs are pooled. It is ``scipy.stats.trim_mean(x, 0.25)``: with n
    scores, ``int(n / 4)`` are cut from each end, so up to three scores it is the mean. NaN in
    the input gives NaN (instead of being silently trimmed); no scores give NaN.

    Example:
        >>> float(iqm([1, 2, 3, 4])), float(iqm([1, 1, 1, 100])), float(iqm(range(8)))
        (2.5, 1.0, 3.5)
        >>> iqm(np.array([[0, 1, 2, 3], [4, 4, 4, 40]]), axis=-1).tolist()
        [1.5, 4.0]
    """
    a = _flat(x)
    if axis is None:
        a = a.ravel()
        if a.size == 0 or np.isnan(a).any():
            return math.nan
        return float(scipy.stats.trim_mean(a, 0.25))
    if a.shape[axis] == 0:
        return np.full(np.delete(a.shape, axis), np.nan)
    out = np.asarray(scipy.stats.trim_mean(a, 0.25, axis=axis), dtype=float)
    return np.where(np.isnan(a).any(axis=axis), np.nan, out)


def optimality_gap(x: Scores, axis: int | None = None, threshold: float = 1.0) -> Any:
    """How far runs fall short of ``threshold`` on average: mean of max(0, threshold − score)
    (rliable's ``aggregate_optimality_gap``; with normalized scores, 1 = dense's level).

    Example:
        >>> float(optimality_gap({"reach": [1.2, 0.5], "push": [0.0]}))
        0.5
    """
    if isinstance(x, Mapping):
        x = _flat(x)
    values = np.asarray(x, dtype=float)
    if values.size == 0:
        return math.nan
    return np.mean(np.maximum(threshold - values, 0.0), axis=axis)


def mean(x: Scores, axis: int | None = None) -> Any:
    """Arithmetic mean over all runs (pooled over tasks for a mapping); NaN when empty.

    Example:
        >>> mean({"reach": [1.0, 0.0], "push": [0.5]})
        0.5
    """
    a = _flat(x)
    if axis is None:
        return float(a.mean()) if a.size else math.nan
    if a.shape[axis] == 0:
        return np.full(np.delete(a.shape, axis), np.nan)
    return a.mean(axis=axis)


def percentile_interval(
    samples: Sequence[float] | np.ndarray, confidence: float = 0.95
) -> tuple[float, float]:
    """The central ``confidence`` percentile interval of bootstrap samples (rliable's default).

    Example:
        >>> percentile_interval(np.arange(101), 0.5)
        (25.0, 75.0)
    """
    if not 0 < confidence < 1:
        raise BadInputError(f"confidence must lie in (0, 1), got {confidence}")
    s = np.asarray(samples, dtype=float).ravel()
    if s.size == 0 or np.isnan(s).any():
        return math.nan, math.nan
    tail = 100 * (1 - confidence) / 2
    low, high = np.percentile(s, [tail, 100 - tail])
    return float(low), float(high)


def by_task(scores: Scores) -> dict[str, np.ndarray]:
    """Task -> 1-D float array, non-empty tasks only, in sorted task order (a plain array is
    the one task ``""``).

    Example:
        >>> {t: a.tolist() for t, a in by_task({"b": [1], "a": [], "c": [[2, 3]]}).items()}
        {'b': [1.0], 'c': [2.0, 3.0]}
    """
    if not isinstance(scores, Mapping):
        scores = {"": scores}
    out = {}
    for task in sorted(scores):
        a = np.asarray(scores[task], dtype=float).ravel()
        if a.size:
            out[task] = a
    return out


def stratified_bootstrap(
    scores: Scores, statistic: Callable[..., Any], reps: int = 2000, seed: int = 0
) -> np.ndarray:
    """``reps`` bootstrap replicates of ``statistic`` under rliable's stratified bootstrap.

    Each replicate resamples the runs of every task with replacement, keeping each task's number
    of runs, and pools them. ``statistic`` is called once, vectorized, as
    ``statistic(samples, axis=-1)`` with ``samples`` of shape ``(reps, total runs)`` (the
    columns grouped by task, tasks in sorted order); :func:`iqm`, :func:`mean` and ``np.median``
    all qualify. A plain array is one task.

    Example:
        >>> stratified_bootstrap({"a": [1.0, 1.0], "b": [3.0]}, mean, reps=3).tolist()
        [1.6666666666666667, 1.6666666666666667, 1.6666666666666667]
    """
    tasks = by_task(scores)
    if not tasks:
        return np.full(reps, np.nan)
    rng = np.random.default_rng(seed)
    samples = np.concatenate(
        [a[rng.integers(0, a.size, size=(reps, a.size))] for a in tasks.values()], axis=1
    )
    return np.asarray(statistic(samples, axis=-1), dtype=float).reshape(reps)


def stratified_bootstrap_ci(
    scores: Scores,
    statistic: Callable[..., Any],
    reps: int = 2000,
    confidence: float = 0.95,
    seed: int = 0,
) -> Interval:
    """``statistic`` over all runs with its stratified-bootstrap percentile interval.

    ``scores`` maps task -> run scores (the runs of a task are its seeds); a plain array is one
    task. The point estimate is ``statistic`` of the pooled scores; the interval is the central
    ``confidence`` percentile interval of :func:`stratified_bootstrap`. The same ``seed`` gives
    the same interval. With one run per task the interval collapses to the estimate; with no
    runs everything is NaN.

    Example:
        >>> ci = stratified_bootstrap_ci([0.2, 0.4, 0.6, 0.8, 1.0], mean, seed=1)
        >>> round(ci.value, 2), ci.low < ci.value < ci.high
        (0.6, True)
        >>> ci == stratified_bootstrap_ci([0.2, 0.4, 0.6, 0.8, 1.0], mean, seed=1)
        True
    """
    tasks = by_task(scores)
    if not tasks:
        return Interval(math.nan, math.nan, math.nan)
    pooled = np.concatenate(list(tasks.values()))
    value = float(np.asarray(statistic(pooled[None, :], axis=-1), dtype=float).reshape(()))
    low, high = percentile_interval(stratified_bootstrap(tasks, statistic, reps, seed), confidence)
    return Interval(value, low, high)


def normalized_score(entry: Any, sparse: Any, dense: Any) -> Any:
    """``(entry - sparse) / (dense - sparse)``: 0 = as good as sparse, 1 = as good as dense.

    Works on success rates and, unchanged, on final distances (lower is better: the signs of
    numerator and denominator flip together, so reaching the dense reward's distance still
    scores 1). Above 1 beats the hand-crafted dense reward; below 0 is worse than sparse.

    Where the references tie (``|dense - sparse| <= 1e-12``, e.g. both at 0% or both at 100%
    success) the score is undefined and the result is NaN, without a warning; a NaN reference
    also gives NaN. Scalars give a float, arrays an array.

    Example:
        >>> normalized_score(0.75, 0.5, 1.0), normalized_score(0.3, 0.5, 0.1)
        (0.5, 0.5)
        >>> normalized_score(0.7, 1.0, 1.0)
        nan
    """
    e, s, d = (np.asarray(v, dtype=float) for v in (entry, sparse, dense))
    denominator = d - s
    undefined = ~(np.abs(denominator) > 1e-12)  # also catches NaN
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(undefined, np.nan, (e - s) / np.where(undefined, 1.0, denominator))
    return float(out) if out.ndim == 0 else out


def _poi(x: np.ndarray, y: np.ndarray) -> Any:
    """P(X > Y) + 0.5 P(X = Y) over all pairs of the last axes (batched over leading axes)."""
    greater = (x[..., :, None] > y[..., None, :]).mean(axis=(-2, -1))
    equal = (x[..., :, None] == y[..., None, :]).mean(axis=(-2, -1))
    return greater + 0.5 * equal


def _paired_tasks(x: Scores, y: Scores) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray]]:
    tx, ty = by_task(x), by_task(y)
    if set(tx) != set(ty):
        only = sorted(set(tx) ^ set(ty))
        raise BadInputError(
            f"probability of improvement needs both score sets on the same tasks; only one has "
            f"{', '.join(only)}"
        )
    return tx, ty


def probability_of_improvement(x: Scores, y: Scores) -> float:
    """P(X > Y): the chance that a run of X beats a run of Y on a task, averaged over tasks.

    rliable's definition: per task, the Mann-Whitney U statistic over ``n * m``, i.e.
    ``P(X_i > Y_j) + 0.5 P(X_i = Y_j)`` over all pairs of runs; then the mean over tasks.
    1 when X always wins, 0.5 when the two are indistinguishable, 0 when Y always wins.
    ``x`` and ``y`` map task -> run scores (or are plain arrays, one task); NaN with no tasks.

    Example:
        >>> probability_of_improvement([0.9, 1.0], [0.1, 0.2])
        1.0
        >>> probability_of_improvement({"a": [1, 0], "b": [1]}, {"a": [1, 0], "b": [0]})
        0.75
    """
    tx, ty = _paired_tasks(x, y)
    if not tx:
        return math.nan
    return float(np.mean([_poi(tx[t], ty[t]) for t in tx]))


def probability_of_improvement_ci(
    x: Scores, y: Scores, reps: int = 2000, confidence: float = 0.95, seed: int = 0
) -> Interval:
    """:func:`probability_of_improvement` with a percentile interval from rliable's stratified
    *independent* bootstrap: the runs of X and of Y are resampled separately within each task.

    Example:
        >>> probability_of_improvement_ci([1.0, 1.0, 1.0], [0.0, 0.0])
        Interval(value=1.0, low=1.0, high=1.0)
    """
    tx, ty = _paired_tasks(x, y)
    if not tx:
        return Interval(math.nan, math.nan, math.nan)
    rng = np.random.default_rng(seed)
    per_task = []
    for task in tx:
        a, b = tx[task], ty[task]
        xa = a[rng.integers(0, a.size, size=(reps, a.size))]
        yb = b[rng.integers(0, b.size, size=(reps, b.size))]
        per_task.append(_poi(xa, yb))
    low, high = percentile_interval(np.mean(per_task, axis=0), confidence)
    return Interval(probability_of_improvement(tx, ty), low, high)


def curve_area(
    steps: Sequence[float] | np.ndarray, values: Sequence[float] | np.ndarray, budget: float
) -> float:
    """Normalized area under a learning curve: trapezoid of ``values`` over ``steps`` / budget.

    For success rates in [0, 1] the area lies in [0, 1]: 1 means solved from the first
    evaluation on. The curve is cut at ``budget`` (interpolated there, when a learner overshoots
    the budget by part of a rollout); nothing is counted before the first evaluation point or
    after the last (the runner evaluates at step 0 and at the end, so the area spans the whole
    budget). One evaluation point gives 0.

    Example:
        >>> curve_area([0, 50, 100], [0.0, 1.0, 1.0], budget=100)
        0.75
        >>> curve_area([0, 50, 120], [0.0, 1.0, 1.0], budget=100)
        0.75
    """
    if budget <= 0:
        raise BadInputError(f"budget must be positive, got {budget}")
    x = np.asarray(steps, dtype=float)
    y = np.asarray(values, dtype=float)
    if x.shape != y.shape or x.ndim != 1:
        raise BadInputError("steps and values must be 1-D arrays of the same length")
    order = np.argsort(x, kind="stable")
    x, y = x[order], y[order]
    if x.size and x[-1] > budget:
        inside = x < budget
        at_budget = np.interp(budget, x, y)
        x = np.append(x[inside], budget)
        y = np.append(y[inside], at_budget)
    if x.size < 2:
        return 0.0
    return float(np.trapezoid(y, x) / budget)


def learning_curve(
    curves: Sequence[tuple[Sequence[float], Sequence[float]]],
    reps: int = 2000,
    confidence: float = 0.95,
    seed: int = 0,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Mean learning curve over runs, with a bootstrap interval at every step.

    ``curves`` holds one (steps, values) pair per run (seed). The common grid is the union of
    evaluation steps; each run is interpolated linearly on the grid inside its own range (no
    extrapolation). Returns ``(grid, mean, low, high)``; the interval resamples whole runs.

    Example:
        >>> grid, m, lo, hi = learning_curve([([0, 10], [0.0, 1.0]), ([0, 10], [0.0, 0.5])])
        >>> grid.tolist(), m.tolist()
        ([0.0, 10.0], [0.0, 0.75])
    """
    if not curves:
        empty = np.empty(0)
        return empty, empty, empty, empty
    grid = np.unique(np.concatenate([np.asarray(s, dtype=float) for s, _ in curves]))
    matrix = np.full((len(curves), grid.size), np.nan)
    for i, (steps, values) in enumerate(curves):
        s, v = np.asarray(steps, dtype=float), np.asarray(values, dtype=float)
        order = np.argsort(s, kind="stable")
        s, v = s[order], v[order]
        inside = (grid >= s[0]) & (grid <= s[-1])
        matrix[i, inside] = np.interp(grid[inside], s, v)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # all-NaN columns are legitimately NaN
        average = np.nanmean(matrix, axis=0)
        rng = np.random.default_rng(seed)
        resampled = matrix[rng.integers(0, len(curves), size=(reps, len(curves)))]
        replicates = np.nanmean(resampled, axis=1)
        tail = 100 * (1 - confidence) / 2
        low, high = np.nanpercentile(replicates, [tail, 100 - tail], axis=0)
    return grid, average, low, high
