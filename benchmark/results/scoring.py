"""Scoring: tidy result rows in, numbers out (IQM, bootstrap intervals, normalized scores).

Every function here is pure: arrays or rows in, numbers out, no printing and no files except
:func:`load_rows`. Results stay numbers until :mod:`planshape.results.leaderboard` renders them.

The statistics follow rliable (Agarwal et al., 2021, "Deep RL at the edge of the statistical
precipice"), reimplemented with numpy/scipy because rliable 1.2 does not import next to pandas 3:

* :func:`iqm` — interquartile mean over all runs of all tasks (``scipy.stats.trim_mean(x, 0.25)``
  over the flattened scores);
* :func:`stratified_bootstrap_ci` — percentile interval of a statistic under the stratified
  bootstrap: runs are resampled with replacement *within* each task;
* :func:`probability_of_improvement` — the Mann-Whitney form, averaged over tasks:
  ``P(X > Y) = mean over tasks of P(X_i > Y_j) + 0.5 P(X_i = Y_j)``, with
  :func:`probability_of_improvement_ci` resampling X and Y independently within each task.

Input rows are the benchmark's tidy rows (one per training run and evaluation point), see
:data:`COLUMNS`. The tables are :func:`summarize` (one row per task, entry and algorithm) and
:func:`aggregate` (one row per entry and algorithm, over tasks).

Example:
    >>> import numpy as np
    >>> float(iqm([0.0, 0.5, 0.6, 1.0]))
    0.55
    >>> ci = stratified_bootstrap_ci({"reach": [0.8, 0.9, 1.0], "push": [0.1, 0.2, 0.3]}, iqm)
    >>> round(ci.value, 3), ci.low <= ci.value <= ci.high
    (0.55, True)
    >>> probability_of_improvement({"reach": [1.0, 1.0]}, {"reach": [0.0, 1.0]})
    0.75
"""

from __future__ import annotations

import json
import math
import warnings
from collections import defaultdict
from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
import scipy.stats

from planshape.errors import BadInputError, ResultsError

__all__ = [
    "COLUMNS",
    "FLOAT_COLUMNS",
    "INT_COLUMNS",
    "MIN_CI_SEEDS",
    "REFERENCE_ENTRIES",
    "Interval",
    "ResultsError",
    "aggregate",
    "curve_area",
    "describe_runs",
    "final_rows",
    "iqm",
    "json_ready",
    "learning_curve",
    "load_rows",
    "mean",
    "normalized_score",
    "normalized_scores",
    "optimality_gap",
    "percentile_interval",
    "probability_of_improvement",
    "probability_of_improvement_ci",
    "read_run",
    "run_curves",
    "stratified_bootstrap",
    "stratified_bootstrap_ci",
    "summarize",
    "validate_row",
]

#: Every column of a result row (the benchmark runner writes them all; extra columns are kept).
COLUMNS: tuple[str, ...] = (
    "run_id",
    "task",
    "entry",
    "potential",
    "model",
    "algo",
    "seed",
    "step",
    "budget",
    "final",
    "success_rate",
    "final_distance",
    "sparse_return",
    "eval_episodes",
    "profile",
    "invariance",
    "wall_time_s",
    "steps_per_s",
    "code_version",
    "packages",
    "hyperparameters",
    "gamma",
)

#: The two reference entries every shaped entry is compared with.
SPARSE, DENSE = "sparse", "dense"
REFERENCE_ENTRIES: tuple[str, str] = (SPARSE, DENSE)

#: Invariance verdicts a row may carry (``not-applicable``: sparse and dense have no potential).
INVARIANCE_VERDICTS: tuple[str, ...] = ("preserved", "violated", "not-checked", "not-applicable")
#: the fewest seeds whose bootstrap interval is shown: with 2-4 seeds a percentile bootstrap
#: returns [min, max] or a zero-width interval, which says nothing about the uncertainty
MIN_CI_SEEDS = 5

#: the typed columns of a row (the rest of :data:`COLUMNS` are strings, a flag and mappings)
INT_COLUMNS = ("seed", "step", "budget", "eval_episodes")
FLOAT_COLUMNS = (
    "success_rate",
    "final_distance",
    "sparse_return",
    "wall_time_s",
    "steps_per_s",
    "gamma",
)
_STR_COLUMNS = ("run_id", "task", "entry", "algo", "profile", "invariance", "code_version")

Scores = Mapping[str, "Sequence[float] | np.ndarray"] | Sequence[float] | np.ndarray
Row = Mapping[str, Any]


class Interval(NamedTuple):
    """A point estimate with its confidence interval (all plain floats; NaN when undefined)."""

    value: float
    low: float
    high: float


# --------------------------------------------------------------------------------------------
# Loading and validating rows
# --------------------------------------------------------------------------------------------


class _RowProblem(ValueError):
    """Why a row is unusable; the caller adds where the row came from."""


def _checked(row: Any) -> dict[str, Any]:
    if not isinstance(row, Mapping):
        raise _RowProblem(f"a result row must be a JSON object, got {type(row).__name__}")
    missing = [c for c in COLUMNS if c not in row]
    if missing:
        raise _RowProblem(
            f"missing columns {', '.join(missing)}; rows written by an older planshape? "
            "Re-run those runs (delete their files under runs/)"
        )
    out = dict(row)
    for column in INT_COLUMNS:
        value = out[column]
        if isinstance(value, bool) or not isinstance(value, int | float) or value != int(value):
            raise _RowProblem(f"column {column!r} must be an integer, got {value!r}")
        out[column] = int(value)
    for column in FLOAT_COLUMNS:
        value = out[column]
        if value is None:
            out[column] = math.nan
        elif isinstance(value, bool) or not isinstance(value, int | float):
            raise _RowProblem(f"column {column!r} must be a number, got {value!r}")
        else:
            out[column] = float(value)
    for column in _STR_COLUMNS:
        if not isinstance(out[column], str):
            raise _RowProblem(f"column {column!r} must be a string, got {out[column]!r}")
    if not isinstance(out["final"], bool):
        raise _RowProblem(f"column 'final' must be true or false, got {out['final']!r}")
    if out["invariance"] not in INVARIANCE_VERDICTS:
        raise _RowProblem(
            f"invariance {out['invariance']!r} is not one of {', '.join(INVARIANCE_VERDICTS)}"
        )
    if out["budget"] <= 0:
        raise _RowProblem(f"budget must be positive, got {out['budget']}")
    return out


def validate_row(row: Any, where: str = "row") -> dict[str, Any]:
    """Check that ``row`` has every column of :data:`COLUMNS` with a usable type.

    Returns a copy of the row (integers as ``int``, metrics as ``float``, ``null`` metrics as
    NaN); otherwise raises :class:`ResultsError` whose message starts with ``where``.

    Example:
        >>> validate_row({"task": "t"}, "runs/a.jsonl:1")  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        planshape.errors.ResultsError: runs/a.jsonl:1: missing columns run_id, entry, ...
    """
    try:
        return _checked(row)
    except _RowProblem as exc:
        raise ResultsError(f"{where}: {exc}") from None


def read_run(path: str | Path) -> list[dict[str, Any]]:
    """The rows of one stored run file, checked to be a whole run.

    A run file is finished only if it is UTF-8 JSON Lines, every row has every column of
    :data:`COLUMNS`, every row names the same run, and exactly its last row is
    ``final``: an empty file, or one cut short while it was written, is not a run. Anything
    else raises :class:`ResultsError` naming the file (and the line) and what to do.

    Example:
        >>> import tempfile, pathlib
        >>> path = pathlib.Path(tempfile.mkdtemp()) / "abc.jsonl"
        >>> _ = path.write_text("")
        >>> read_run(path)  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        planshape.errors.ResultsError: .../abc.jsonl: empty: ...
    """
    path = Path(path)
    redo = "move the file out of runs/ (or delete it) and run the benchmark again to retrain it"
    try:
        text = path.read_bytes().decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ResultsError(
            f"not UTF-8 text (byte {exc.start}): not a result file, or a damaged one; {redo}",
            path,
        ) from None
    except OSError as exc:
        raise ResultsError(f"cannot be read ({exc.strerror}); {redo}", path) from None
    rows: list[dict[str, Any]] = []
    last_line = 0
    for number, line in enumerate(text.splitlines(), start=1):
        if not line.strip():
            continue
        try:
            row = _checked(json.loads(line))
        except json.JSONDecodeError as exc:
            raise ResultsError(
                f"not a JSON row ({exc.msg}, column {exc.colno}); {redo}", path, number
            ) from None
        except _RowProblem as exc:
            raise ResultsError(str(exc), path, number) from None
        if rows and row["run_id"] != rows[0]["run_id"]:
            raise ResultsError(
                f"the row is of run {row['run_id']!r}, the file's first row of run "
                f"{rows[0]['run_id']!r}; {redo}",
                path,
                number,
            )
        if rows and rows[-1]["final"]:
            raise ResultsError(f"a row after the run's final row; {redo}", path, number)
        rows.append(row)
        last_line = number
    if not rows:
        raise ResultsError(f"empty: no result rows, so not a finished run; {redo}", path)
    if not rows[-1]["final"]:
        raise ResultsError(
            f"truncated: the last row (step {rows[-1]['step']} of a budget of "
            f"{rows[-1]['budget']}) is not the run's final row; {redo}",
            path,
            last_line,
        )
    return rows


def load_rows(out_dir: str | Path) -> list[dict[str, Any]]:
    """Every result row under ``<out_dir>/runs/*.jsonl``, by file name, then line.

    Each file is read with :func:`read_run`, so a damaged or unfinished run file raises
    :class:`ResultsError` naming it (and the line; also in its ``file`` and ``line``
    attributes). Temporary files (``.*.tmp``, written while a run is being stored) are ignored.
    A missing ``runs/`` folder is an error; an empty one gives no rows.

    Example:
        >>> import tempfile, pathlib
        >>> out = pathlib.Path(tempfile.mkdtemp()); (out / "runs").mkdir()
        >>> _ = (out / "runs" / "a.jsonl").write_text("{not json\\n")
        >>> load_rows(out)  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        planshape.errors.ResultsError: .../runs/a.jsonl:1: not a JSON row (...); ...
    """
    runs = Path(out_dir) / "runs"
    if not runs.is_dir():
        raise ResultsError(f"no results folder {runs}; run `planshape bench --out {out_dir}` first")
    rows: list[dict[str, Any]] = []
    for path in sorted(runs.glob("*.jsonl")):
        if path.is_file():
            rows += read_run(path)
    return rows


# --------------------------------------------------------------------------------------------
# Statistics (rliable definitions)
# --------------------------------------------------------------------------------------------


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


def normalized_scores(
    rows: Iterable[Row], metric: str = "success_rate"
) -> dict[tuple[str, str], dict[str, np.ndarray]]:
    """(algo, entry) -> task -> each run's final ``metric`` normalized with its task's sparse
    and dense means (:func:`normalized_score`); tasks where those tie are left out. What
    :func:`aggregate` pools, for figures such as performance profiles.

    Example:
        >>> normalized_scores([])
        {}
    """
    runs, _ = _group_runs(rows)
    groups = _groups(runs)
    out: dict[tuple[str, str], dict[str, np.ndarray]] = {}
    for task, algo, entry in sorted(groups):
        values = [r.final[metric] for r in groups[(task, algo, entry)]]
        scores = normalized_score(values, *_references(groups, task, algo, metric))
        if not np.isnan(scores).all():
            out.setdefault((algo, entry), {})[task] = np.asarray(scores, dtype=float)
    return out


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


def _tasks(scores: Scores) -> dict[str, np.ndarray]:
    """Task -> 1-D float array, non-empty tasks only, in sorted task order."""
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
    tasks = _tasks(scores)
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
    tasks = _tasks(scores)
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
    tx, ty = _tasks(x), _tasks(y)
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


# --------------------------------------------------------------------------------------------
# From rows to runs
# --------------------------------------------------------------------------------------------


class _Run(NamedTuple):
    run_id: str
    final: dict[str, Any]
    steps: np.ndarray
    success: np.ndarray


def _group_runs(rows: Iterable[Row]) -> tuple[list[_Run], list[str]]:
    """Runs with a final row (sorted by task, algo, entry, seed), and the ids without one."""
    by_run: dict[str, list[dict[str, Any]]] = defaultdict(list)
    for row in rows:
        where = f"row of run {row.get('run_id', '?')!r}" if isinstance(row, Mapping) else "row"
        checked = validate_row(row, where)
        by_run[checked["run_id"]].append(checked)
    runs, incomplete = [], []
    for run_id in sorted(by_run):
        group = sorted(by_run[run_id], key=lambda r: r["step"])
        identity = {(r["task"], r["entry"], r["algo"], r["seed"], r["budget"]) for r in group}
        if len(identity) > 1:
            raise ResultsError(
                f"run {run_id!r} mixes tasks, entries, algorithms, seeds or budgets "
                f"{sorted(identity)}; run ids must be unique per run"
            )
        finals = [r for r in group if r["final"]]
        if len(finals) > 1:
            raise ResultsError(f"run {run_id!r} has {len(finals)} rows marked final; expected one")
        if not finals:
            incomplete.append(run_id)
            continue
        runs.append(
            _Run(
                run_id,
                finals[0],
                np.array([r["step"] for r in group], dtype=float),
                np.array([r["success_rate"] for r in group], dtype=float),
            )
        )
    runs.sort(key=lambda r: (r.final["task"], r.final["algo"], r.final["entry"], r.final["seed"]))
    return runs, incomplete


def final_rows(rows: Iterable[Row]) -> list[dict[str, Any]]:
    """The final evaluation row of every finished run, sorted by task, algo, entry and seed.

    Example:
        >>> final_rows([])
        []
    """
    return [run.final for run in _group_runs(rows)[0]]


def run_curves(rows: Iterable[Row]) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """run_id -> (steps, success rates) of every finished run, sorted by step.

    Example:
        >>> run_curves([])
        {}
    """
    return {run.run_id: (run.steps, run.success) for run in _group_runs(rows)[0]}


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


# --------------------------------------------------------------------------------------------
# Tables
# --------------------------------------------------------------------------------------------


def _combine_invariance(verdicts: Iterable[str]) -> str:
    """One verdict for several runs: ``violated`` if any run says so; else ``not-checked`` if
    any run was not checked; else ``preserved`` if any run was checked; else
    ``not-applicable``.

    Example:
        >>> _combine_invariance(["preserved", "not-checked"])
        'not-checked'
    """
    seen = set(verdicts)
    for verdict in ("violated", "not-checked", "preserved"):
        if verdict in seen:
            return verdict
    return "not-applicable"


def _interval_columns(prefix: str, interval: Interval, *samples: Any) -> dict[str, float]:
    """``prefix``, ``prefix_low``, ``prefix_high``. The bounds are NaN unless every one of
    ``samples`` (arrays, or mappings task -> array) has at least two runs in some task:
    resampling a single run gives a zero-width interval that would claim certainty."""
    if not all(any(len(v) >= 2 for v in _tasks(x).values()) for x in samples):
        interval = Interval(interval.value, math.nan, math.nan)
    return {prefix: interval.value, f"{prefix}_low": interval.low, f"{prefix}_high": interval.high}


def eval_protocol(row: Mapping[str, Any]) -> int:
    """The evaluation protocol of a row (see :mod:`planshape.harness.runner`); rows stored before
    the field existed were made with protocol 1."""
    return int(row.get("eval_protocol", 1))


def evaluation_text(row: Mapping[str, Any]) -> str:
    """What a row's evaluation point measured."""
    if "evaluation" in row:
        return str(row["evaluation"])
    return (
        f"{row['eval_episodes']} deterministic episodes (protocol 1: recorded at the callback's "
        "step, for PPO before that rollout's update)"
    )


def _groups(runs: list[_Run]) -> dict[tuple[str, str, str], list[_Run]]:
    """(task, algo, entry) -> runs, checking one budget per group and one run per seed."""
    groups: dict[tuple[str, str, str], list[_Run]] = defaultdict(list)
    for run in runs:
        f = run.final
        groups[(f["task"], f["algo"], f["entry"])].append(run)
    for (task, algo, entry), group in groups.items():
        budgets = sorted({r.final["budget"] for r in group})
        if len(budgets) > 1:
            raise ResultsError(
                f"{task} / {entry} / {algo} mixes budgets {budgets}; results of different "
                "profiles cannot share a leaderboard — render them from separate --out folders"
            )
        protocols = sorted({eval_protocol(r.final) for r in group})
        if len(protocols) > 1:
            raise ResultsError(
                f"{task} / {entry} / {algo} mixes evaluation protocols {protocols}; runs "
                "evaluated differently cannot share a cell — render them from separate --out "
                "folders"
            )
        by_seed: dict[int, list[str]] = defaultdict(list)
        for r in group:
            by_seed[r.final["seed"]].append(r.run_id)
        duplicated = {s: ids for s, ids in by_seed.items() if len(ids) > 1}
        if duplicated:
            seed, ids = min(duplicated.items())
            raise ResultsError(
                f"{task} / {entry} / {algo} has seed {seed} more than once (runs "
                f"{', '.join(ids)}); delete the stale run files so each seed counts once"
            )
    return groups


def _references(
    groups: Mapping[tuple[str, str, str], list[_Run]], task: str, algo: str, metric: str
) -> tuple[float, float]:
    """Mean final ``metric`` of the sparse and dense entries of (task, algo); NaN if absent.

    Both are NaN when dense is no better than sparse (success not higher, distance not
    lower): the scale (entry − sparse) / (dense − sparse) would then invert or divide by
    zero, e.g. −4 for an entry that solves a task where sparse solves more than dense."""
    out = []
    for entry in REFERENCE_ENTRIES:
        runs = groups.get((task, algo, entry), [])
        out.append(mean([r.final[metric] for r in runs]))
    sparse, dense = out
    better = dense > sparse if metric == "success_rate" else dense < sparse
    if not better and not (math.isnan(sparse) or math.isnan(dense)):
        return math.nan, math.nan
    return sparse, dense


def summarize(
    rows: Iterable[Row], reps: int = 2000, confidence: float = 0.95, seed: int = 0
) -> list[dict[str, Any]]:
    """One row per (task, entry, algo) of finished runs, sorted by task, algo and entry.

    Columns (numbers are floats, NaN where undefined; ``*_low``/``*_high`` bound the
    ``confidence`` stratified-bootstrap percentile interval of the column they extend, NaN
    with a single seed, where resampling cannot show any spread):

    * ``task``, ``entry``, ``potential``, ``model``, ``algo``, ``budget``, ``n_seeds``, ``seeds``;
    * ``success_iqm``, ``success_mean`` — final success rate over seeds;
    * ``distance_iqm``, ``distance_mean`` — final distance to the goal (lower is better);
    * ``sparse_return_mean`` — final undiscounted return under the task's sparse reward;
    * ``normalized_success``, ``normalized_distance`` — :func:`normalized_score` of the mean
      final success / distance against the means of the ``sparse`` and ``dense`` entries of the
      same task and algorithm (NaN when a reference is missing or the references tie);
    * ``p_improve`` — :func:`probability_of_improvement` of final success over the ``sparse``
      entry of the same task and algorithm; ``p_improve_distance`` the same on final distance
      (a run improves when its distance is *lower*); NaN without a sparse entry;
    * ``curve_area_mean`` — mean :func:`curve_area` of success rate over steps;
    * ``invariance`` — ``violated`` if any run's check says so, else ``not-checked`` if any run
      was not checked, else ``preserved`` (or ``not-applicable`` for sparse and dense);
    * ``steps_per_s``, ``wall_time_s`` — means over runs; ``eval_episodes`` — the largest count
      used (they agree within a profile).

    Runs without a final row are skipped (see :func:`describe_runs`). The bootstrap uses
    ``seed`` for every interval, so the same rows always give the same numbers.

    Example:
        >>> summarize([])
        []
    """
    runs, _ = _group_runs(rows)
    groups = _groups(runs)
    table = []
    for (task, algo, entry), group in sorted(groups.items()):
        finals = [r.final for r in group]
        success = np.array([f["success_rate"] for f in finals])
        distance = np.array([f["final_distance"] for f in finals])
        sparse_runs = groups.get((task, algo, SPARSE), [])
        sparse_success = [r.final["success_rate"] for r in sparse_runs]
        sparse_distance = [r.final["final_distance"] for r in sparse_runs]
        areas = [curve_area(r.steps, r.success, r.final["budget"]) for r in group]
        row: dict[str, Any] = {
            "task": task,
            "entry": entry,
            "potential": finals[0]["potential"],
            "model": finals[0]["model"],
            "algo": algo,
            "budget": finals[0]["budget"],
            "n_seeds": len(group),
            "seeds": sorted(f["seed"] for f in finals),
        }
        ci = dict(reps=reps, confidence=confidence, seed=seed)
        row |= _interval_columns(
            "success_iqm", stratified_bootstrap_ci(success, iqm, **ci), success
        )
        row |= _interval_columns(
            "success_mean", stratified_bootstrap_ci(success, mean, **ci), success
        )
        row |= _interval_columns(
            "distance_iqm", stratified_bootstrap_ci(distance, iqm, **ci), distance
        )
        row |= _interval_columns(
            "distance_mean", stratified_bootstrap_ci(distance, mean, **ci), distance
        )
        row["sparse_return_mean"] = mean([f["sparse_return"] for f in finals])
        row["normalized_success"] = normalized_score(
            row["success_mean"], *_references(groups, task, algo, "success_rate")
        )
        row["normalized_distance"] = normalized_score(
            row["distance_mean"], *_references(groups, task, algo, "final_distance")
        )
        if sparse_runs:
            poi = probability_of_improvement_ci(success, sparse_success, **ci)
            poi_distance = probability_of_improvement_ci(
                -distance, -np.asarray(sparse_distance), **ci
            )
        else:
            poi = poi_distance = Interval(math.nan, math.nan, math.nan)
        row |= _interval_columns("p_improve", poi, success, sparse_success)
        row |= _interval_columns("p_improve_distance", poi_distance, distance, sparse_distance)
        row |= _interval_columns(
            "curve_area_mean", stratified_bootstrap_ci(areas, mean, **ci), areas
        )
        row["invariance"] = _combine_invariance(f["invariance"] for f in finals)
        row["steps_per_s"] = mean([f["steps_per_s"] for f in finals])
        row["wall_time_s"] = mean([f["wall_time_s"] for f in finals])
        row["eval_episodes"] = max(f["eval_episodes"] for f in finals)
        table.append(row)
    return table


def aggregate(
    rows: Iterable[Row], reps: int = 2000, confidence: float = 0.95, seed: int = 0
) -> list[dict[str, Any]]:
    """One row per (entry, algo) over the tasks it ran on, sorted by algo and entry.

    Scores from different tasks are only comparable once normalized, so the aggregate is over
    per-run normalized scores: each run's final success (distance) normalized with the mean
    sparse and dense results of its task and algorithm (the references are fixed, not
    resampled). Tasks whose normalization is undefined (a reference is missing or the
    references tie) are left out of that column and listed in ``*_tasks_excluded``.

    Columns: ``entry``, ``algo``, ``tasks`` (every task the entry ran on), ``n_tasks``,
    ``n_runs``; ``normalized_success_iqm`` and ``normalized_success_mean`` (IQM/mean over the
    pooled runs with stratified-bootstrap intervals, ``*_low``/``*_high``),
    ``normalized_success_gap`` (the optimality gap below dense's level, :func:`optimality_gap`),
    ``normalized_success_tasks_excluded``; the same for ``normalized_distance``;
    ``p_improve_dense`` (P(entry's success > dense's)), ``p_improve`` and
    ``p_improve_distance`` (over the tasks that have a sparse entry, with the
    stratified independent bootstrap); ``curve_area_mean``; ``invariance`` (combined as in
    :func:`summarize`).

    Example:
        >>> aggregate([])
        []
    """
    runs, _ = _group_runs(rows)
    groups = _groups(runs)
    by_entry: dict[tuple[str, str], list[str]] = defaultdict(list)
    for task, algo, entry in sorted(groups):
        by_entry[(algo, entry)].append(task)
    ci = dict(reps=reps, confidence=confidence, seed=seed)
    table = []
    for (algo, entry), tasks in sorted(by_entry.items()):
        row: dict[str, Any] = {
            "entry": entry,
            "algo": algo,
            "tasks": tasks,
            "n_tasks": len(tasks),
            "n_runs": sum(len(groups[(t, algo, entry)]) for t in tasks),
            "min_seeds": min(len(groups[(t, algo, entry)]) for t in tasks),
        }
        for metric, name in (("success_rate", "success"), ("final_distance", "distance")):
            normalized: dict[str, np.ndarray] = {}
            excluded = []
            for task in tasks:
                values = [r.final[metric] for r in groups[(task, algo, entry)]]
                scores = normalized_score(values, *_references(groups, task, algo, metric))
                if np.isnan(scores).all():
                    excluded.append(task)
                else:
                    normalized[task] = scores
            column = f"normalized_{name}"
            row |= _interval_columns(
                f"{column}_iqm", stratified_bootstrap_ci(normalized, iqm, **ci), normalized
            )
            row |= _interval_columns(
                f"{column}_mean", stratified_bootstrap_ci(normalized, mean, **ci), normalized
            )
            row |= _interval_columns(
                f"{column}_gap",
                stratified_bootstrap_ci(normalized, optimality_gap, **ci),
                normalized,
            )
            row[f"{column}_tasks_excluded"] = excluded
        with_sparse = [t for t in tasks if (t, algo, SPARSE) in groups]
        for metric, column, sign in (
            ("success_rate", "p_improve", 1.0),
            ("final_distance", "p_improve_distance", -1.0),
        ):
            x, y = (
                {t: [sign * r.final[metric] for r in groups[(t, algo, e)]] for t in with_sparse}
                for e in (entry, SPARSE)
            )
            row |= _interval_columns(column, probability_of_improvement_ci(x, y, **ci), x, y)
        with_dense = [t for t in tasks if (t, algo, DENSE) in groups]
        x, y = (
            {t: [r.final["success_rate"] for r in groups[(t, algo, e)]] for t in with_dense}
            for e in (entry, DENSE)
        )
        row |= _interval_columns("p_improve_dense", probability_of_improvement_ci(x, y, **ci), x, y)
        areas = {
            t: [curve_area(r.steps, r.success, r.final["budget"]) for r in groups[(t, algo, entry)]]
            for t in tasks
        }
        row |= _interval_columns(
            "curve_area_mean", stratified_bootstrap_ci(areas, mean, **ci), areas
        )
        row["invariance"] = _combine_invariance(
            r.final["invariance"] for t in tasks for r in groups[(t, algo, entry)]
        )
        table.append(row)
    return table


def describe_runs(rows: Iterable[Row], profile: str | None = None) -> dict[str, Any]:
    """Provenance of the results, for a leaderboard header, and caveats derived from it.

    Returns a dict with ``n_runs``, ``n_rows``, ``profiles``, ``budgets`` (task -> algo ->
    steps), ``seeds`` (every seed), ``seeds_per_entry`` ([fewest, most] seeds of any
    task/entry/algo), ``eval_episodes``, ``code_versions``, ``packages`` (name -> versions seen),
    ``gammas``, ``hyperparameters`` (task -> algo -> distinct settings), ``wall_time_s`` (the
    sum over runs), ``incomplete_runs`` (run ids without a final row) and ``caveats``: plain
    sentences about anything that weakens a comparison (mixed code or package versions, a
    profile other than ``profile``, unequal seed counts, missing references, references that
    tie, invariance violations, uncommitted code).

    Example:
        >>> describe_runs([])["n_runs"]
        0
    """
    rows = list(rows)
    runs, incomplete = _group_runs(rows)
    groups = _groups(runs)
    finals = [r.final for r in runs]
    budgets: dict[str, dict[str, int]] = defaultdict(dict)
    hyper: dict[str, dict[str, list[Any]]] = defaultdict(lambda: defaultdict(list))
    packages: dict[str, set[str]] = defaultdict(set)
    for f in finals:
        budgets[f["task"]][f["algo"]] = f["budget"]
        settings = hyper[f["task"]][f["algo"]]
        if f["hyperparameters"] not in settings:
            settings.append(f["hyperparameters"])
        for name, version in (f["packages"] or {}).items():
            packages[str(name)].add(str(version))
    seed_counts = [len(g) for g in groups.values()]
    info: dict[str, Any] = {
        "n_runs": len(runs),
        "n_rows": len(rows),
        "profiles": sorted({f["profile"] for f in finals}),
        "budgets": {t: dict(sorted(b.items())) for t, b in sorted(budgets.items())},
        "seeds": sorted({f["seed"] for f in finals}),
        "seeds_per_entry": [min(seed_counts), max(seed_counts)] if seed_counts else [],
        "eval_episodes": sorted({f["eval_episodes"] for f in finals}),
        "evaluations": {
            t: sorted({evaluation_text(f) for f in finals if f["task"] == t})
            for t in sorted({f["task"] for f in finals})
        },
        "code_versions": sorted({f["code_version"] for f in finals}),
        "packages": {name: sorted(v) for name, v in sorted(packages.items())},
        "gammas": sorted({f["gamma"] for f in finals}),
        "hyperparameters": {
            t: {a: settings for a, settings in sorted(by_algo.items())}
            for t, by_algo in sorted(hyper.items())
        },
        "wall_time_s": float(sum(f["wall_time_s"] for f in finals)),
        "incomplete_runs": incomplete,
    }
    caveats = []
    if incomplete:
        caveats.append(
            f"{len(incomplete)} run(s) have no final evaluation row and are left out: "
            f"{', '.join(incomplete)}"
        )
    if seed_counts and min(seed_counts) < 2:
        caveats.append(
            "some entries have a single seed: they get no confidence interval, and one seed says "
            "little about an RL method"
        )
    if len(info["code_versions"]) > 1:
        versions = ", ".join(info["code_versions"])
        caveats.append(f"results come from several code versions: {versions}")
    if any(v.endswith("-dirty") for v in info["code_versions"]):
        caveats.append("some runs ran on a working tree with uncommitted changes (-dirty)")
    other_profile = profile is not None and info["profiles"] not in ([profile], [])
    if len(info["profiles"]) > 1 or other_profile:
        caveats.append(
            f"rows come from profile(s) {', '.join(info['profiles'])}"
            + (f", not only {profile!r}" if profile is not None else "")
        )
    mixed = {n: v for n, v in info["packages"].items() if len(v) > 1}
    for name, versions in mixed.items():
        caveats.append(f"runs used different versions of {name}: {', '.join(versions)}")
    if len(info["gammas"]) > 1:
        caveats.append(f"runs used different discounts: {', '.join(map(str, info['gammas']))}")
    for task, algo in sorted({(t, a) for t, a, _ in groups}):
        counts = {e: len(g) for (t, a, e), g in groups.items() if (t, a) == (task, algo)}
        if len(set(counts.values())) > 1:
            caveats.append(
                f"{task} / {algo}: entries have unequal numbers of seeds "
                f"({min(counts.values())} to {max(counts.values())})"
            )
        missing = [e for e in REFERENCE_ENTRIES if e not in counts]
        if missing:
            caveats.append(
                f"{task} / {algo}: no {' or '.join(missing)} entry, so normalized scores"
                + (" and P(improve over sparse)" if SPARSE in missing else "")
                + " are n/a"
            )
            continue
        for metric, label in (("success_rate", "success"), ("final_distance", "final distance")):
            sparse, dense = _references(groups, task, algo, metric)
            if np.isnan(normalized_score(sparse, sparse, dense)):
                caveats.append(
                    f"{task} / {algo}: dense is no better than sparse on mean final {label}, "
                    f"so normalized {label} is n/a there"
                )
    violated = sorted(
        {
            (t, e)
            for (t, _, e), g in groups.items()
            for r in g
            if r.final["invariance"] == "violated"
        }
    )
    if violated:
        caveats.append(
            "the invariance check found a changed optimal policy for: "
            + ", ".join(f"{e} on {t}" for t, e in violated)
            + "; those entries are not policy-invariant shaping"
        )
    info["caveats"] = caveats
    return info


def json_ready(value: Any) -> Any:
    """``value`` with NaN and infinities as ``None`` (JSON ``null``), numpy scalars as Python
    numbers and tuples as lists, so that ``json.dumps(..., allow_nan=False)`` accepts it.

    Example:
        >>> json.dumps(json_ready({"iqm": float("nan"), "ci": (np.float64(0.5), 1.0)}))
        '{"iqm": null, "ci": [0.5, 1.0]}'
    """
    if isinstance(value, Mapping):
        return {str(k): json_ready(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [json_ready(v) for v in value]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value
