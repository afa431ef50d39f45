"""Cells: the checked rows grouped into runs and cells, and each cell's numbers.

A *run* is the rows of one training run (:class:`Run`: its final row and its learning curve);
a *cell* is the runs of one task, algorithm and entry, one per seed (:func:`cells`). The tables
are :func:`summarize` (one row per cell) and :func:`aggregate` (one row per entry and
algorithm, over tasks, on task-normalized scores); the statistics come from
:mod:`planshape.results.stats`. Every function is pure: rows in, numbers out.

Example:
    >>> summarize([]), aggregate([]), final_rows([])
    ([], [], [])
    >>> combine_invariance(["preserved", "not-checked"])
    'not-checked'
"""

from __future__ import annotations

import math
from collections import defaultdict
from collections.abc import Iterable, Mapping
from typing import Any, NamedTuple

import numpy as np

from planshape.errors import ResultsError
from planshape.results.rows import Row, eval_protocol, validate_row
from planshape.results.stats import (
    Interval,
    by_task,
    curve_area,
    iqm,
    mean,
    normalized_score,
    optimality_gap,
    probability_of_improvement_ci,
    stratified_bootstrap_ci,
)

__all__ = [
    "DENSE",
    "REFERENCE_ENTRIES",
    "SPARSE",
    "Cells",
    "Run",
    "aggregate",
    "cells",
    "combine_invariance",
    "final_rows",
    "finished_runs",
    "normalized_scores",
    "references",
    "run_curves",
    "summarize",
]

#: The two reference entries every shaped entry is compared with.
SPARSE, DENSE = "sparse", "dense"
REFERENCE_ENTRIES: tuple[str, str] = (SPARSE, DENSE)


class Run(NamedTuple):
    """One finished run: its id, its final row and its success rate over steps."""

    run_id: str
    final: dict[str, Any]
    steps: np.ndarray
    success: np.ndarray


#: (task, algo, entry) -> the runs of that cell
Cells = dict[tuple[str, str, str], list[Run]]


# --------------------------------------------------------------------------------------------
# From rows to runs and cells
# --------------------------------------------------------------------------------------------


def _checked_by_run(rows: Iterable[Row]) -> dict[str, list[dict[str, Any]]]:
    if hasattr(rows, "to_dict") and hasattr(rows, "columns"):  # a planshape.results.load frame
        from planshape.results.frame import records

        rows = records(rows)
    by_run: dict[str, list[dict[str, Any]]] = defaultdict(list)
    for row in rows:
        where = f"row of run {row.get('run_id', '?')!r}" if isinstance(row, Mapping) else "row"
        checked = validate_row(row, where)
        by_run[checked["run_id"]].append(checked)
    return by_run


def _run(run_id: str, group: list[dict[str, Any]]) -> Run | None:
    """The run of ``group`` (its rows sorted by step), or None without a final row."""
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
        return None
    steps = np.array([r["step"] for r in group], dtype=float)
    return Run(run_id, finals[0], steps, np.array([r["success_rate"] for r in group], dtype=float))


def finished_runs(rows: Iterable[Row]) -> tuple[list[Run], list[str]]:
    """Runs with a final row (sorted by task, algo, entry, seed), and the ids without one.

    Example:
        >>> finished_runs([])
        ([], [])
    """
    runs, incomplete = [], []
    for run_id, group in sorted(_checked_by_run(rows).items()):
        run = _run(run_id, sorted(group, key=lambda r: r["step"]))
        if run is None:
            incomplete.append(run_id)
        else:
            runs.append(run)
    runs.sort(key=lambda r: (r.final["task"], r.final["algo"], r.final["entry"], r.final["seed"]))
    return runs, incomplete


def _check_cell(key: tuple[str, str, str], group: list[Run]) -> None:
    """One budget, one evaluation protocol and one run per seed in a cell."""
    task, algo, entry = key
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


def cells(runs: list[Run]) -> Cells:
    """(task, algo, entry) -> runs, checking one budget per cell and one run per seed.

    Example:
        >>> len(cells([]))
        0
    """
    groups: Cells = defaultdict(list)
    for run in runs:
        f = run.final
        groups[(f["task"], f["algo"], f["entry"])].append(run)
    for key, group in groups.items():
        _check_cell(key, group)
    return groups


def _cells_of(rows: Iterable[Row]) -> Cells:
    return cells(finished_runs(rows)[0])


def final_rows(rows: Iterable[Row]) -> list[dict[str, Any]]:
    """The final evaluation row of every finished run, sorted by task, algo, entry and seed."""
    return [run.final for run in finished_runs(rows)[0]]


def run_curves(rows: Iterable[Row]) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """run_id -> (steps, success rates) of every finished run, sorted by step.

    Example:
        >>> run_curves([])
        {}
    """
    return {run.run_id: (run.steps, run.success) for run in finished_runs(rows)[0]}


def references(groups: Cells, task: str, algo: str, metric: str) -> tuple[float, float]:
    """Mean final ``metric`` of the sparse and dense entries of (task, algo); NaN if absent.

    Both are NaN when dense is no better than sparse (success not higher, distance not
    lower): the scale (entry − sparse) / (dense − sparse) would then invert or divide by
    zero, e.g. −4 for an entry that solves a task where sparse solves more than dense."""
    sparse, dense = (
        mean([r.final[metric] for r in groups.get((task, algo, entry), [])])
        for entry in REFERENCE_ENTRIES
    )
    better = dense > sparse if metric == "success_rate" else dense < sparse
    if not better and not (math.isnan(sparse) or math.isnan(dense)):
        return math.nan, math.nan
    return sparse, dense


def _normalized(groups: Cells, task: str, algo: str, entry: str, metric: str) -> np.ndarray:
    values = [r.final[metric] for r in groups[(task, algo, entry)]]
    return normalized_score(values, *references(groups, task, algo, metric))


def normalized_scores(
    rows: Iterable[Row], metric: str = "success_rate"
) -> dict[tuple[str, str], dict[str, np.ndarray]]:
    """(algo, entry) -> task -> each run's final ``metric`` normalized with its task's sparse
    and dense means (:func:`~planshape.results.stats.normalized_score`); tasks where those tie
    are left out. What :func:`aggregate` pools, for figures such as performance profiles.

    Example:
        >>> normalized_scores([])
        {}
    """
    groups = _cells_of(rows)
    out: dict[tuple[str, str], dict[str, np.ndarray]] = {}
    for task, algo, entry in sorted(groups):
        scores = _normalized(groups, task, algo, entry, metric)
        if not np.isnan(scores).all():
            out.setdefault((algo, entry), {})[task] = np.asarray(scores, dtype=float)
    return out


# --------------------------------------------------------------------------------------------
# Columns
# --------------------------------------------------------------------------------------------


def combine_invariance(verdicts: Iterable[str]) -> str:
    """One verdict for several runs: ``violated`` if any run says so; else ``not-checked`` if
    any run was not checked; else ``preserved`` if any run was checked; else
    ``not-applicable``."""
    seen = set(verdicts)
    for verdict in ("violated", "not-checked", "preserved"):
        if verdict in seen:
            return verdict
    return "not-applicable"


def _interval_columns(prefix: str, interval: Interval, *samples: Any) -> dict[str, float]:
    """``prefix``, ``prefix_low``, ``prefix_high``. The bounds are NaN unless every one of
    ``samples`` (arrays, or mappings task -> array) has at least two runs in some task:
    resampling a single run gives a zero-width interval that would claim certainty."""
    if not all(any(len(v) >= 2 for v in by_task(x).values()) for x in samples):
        interval = Interval(interval.value, math.nan, math.nan)
    return {prefix: interval.value, f"{prefix}_low": interval.low, f"{prefix}_high": interval.high}


class _Bootstrap(NamedTuple):
    """The bootstrap settings of every interval of a table."""

    reps: int
    confidence: float
    seed: int

    def ci(self, prefix: str, scores: Any, statistic: Any) -> dict[str, float]:
        """:func:`_interval_columns` of ``statistic``'s stratified-bootstrap interval."""
        interval = stratified_bootstrap_ci(scores, statistic, *self)
        return _interval_columns(prefix, interval, scores)

    def improvement(self, prefix: str, x: Any, y: Any) -> dict[str, float]:
        """:func:`_interval_columns` of P(X > Y) with its interval."""
        return _interval_columns(prefix, probability_of_improvement_ci(x, y, *self), x, y)


_NO_INTERVAL = Interval(math.nan, math.nan, math.nan)


# --------------------------------------------------------------------------------------------
# One row per cell
# --------------------------------------------------------------------------------------------


def _cell_identity(key: tuple[str, str, str], finals: list[dict[str, Any]]) -> dict[str, Any]:
    task, algo, entry = key
    return {
        "task": task,
        "entry": entry,
        "potential": finals[0]["potential"],
        "model": finals[0]["model"],
        "algo": algo,
        "budget": finals[0]["budget"],
        "n_seeds": len(finals),
        "seeds": sorted(f["seed"] for f in finals),
    }


def _improvement_over_references(
    groups: Cells, key: tuple[str, str, str], boot: _Bootstrap
) -> dict[str, float]:
    """``p_improve`` (final success) and ``p_improve_distance`` (lower final distance) over
    sparse, and ``p_improve_dense`` (final success) over dense."""
    task, algo, _ = key
    finals = [r.final for r in groups[key]]
    success = np.array([f["success_rate"] for f in finals])
    distance = np.array([f["final_distance"] for f in finals])
    sparse_runs = groups.get((task, algo, SPARSE), [])
    sparse_success = [r.final["success_rate"] for r in sparse_runs]
    sparse_distance = [r.final["final_distance"] for r in sparse_runs]
    if sparse_runs:
        poi = probability_of_improvement_ci(success, sparse_success, *boot)
        poi_distance = probability_of_improvement_ci(-distance, -np.asarray(sparse_distance), *boot)
    else:
        poi = poi_distance = _NO_INTERVAL
    dense_success = [r.final["success_rate"] for r in groups.get((task, algo, DENSE), [])]
    poi_dense = (
        probability_of_improvement_ci(success, dense_success, *boot)
        if dense_success
        else _NO_INTERVAL
    )
    return (
        _interval_columns("p_improve", poi, success, sparse_success)
        | _interval_columns("p_improve_distance", poi_distance, distance, sparse_distance)
        | _interval_columns("p_improve_dense", poi_dense, success, dense_success)
    )


def _cell_row(groups: Cells, key: tuple[str, str, str], boot: _Bootstrap) -> dict[str, Any]:
    task, algo, _ = key
    group = groups[key]
    finals = [r.final for r in group]
    success = np.array([f["success_rate"] for f in finals])
    distance = np.array([f["final_distance"] for f in finals])
    areas = [curve_area(r.steps, r.success, r.final["budget"]) for r in group]
    row = _cell_identity(key, finals)
    row |= boot.ci("success_iqm", success, iqm) | boot.ci("success_mean", success, mean)
    row |= boot.ci("distance_iqm", distance, iqm) | boot.ci("distance_mean", distance, mean)
    row["sparse_return_mean"] = mean([f["sparse_return"] for f in finals])
    for column in ("success_any", "success_end"):
        rates = [f.get(f"{column}_rate", math.nan) for f in finals]
        row[f"{column}_mean"] = math.nan if any(map(math.isnan, rates)) else mean(rates)
    row["normalized_success"] = normalized_score(
        row["success_mean"], *references(groups, task, algo, "success_rate")
    )
    row["normalized_distance"] = normalized_score(
        row["distance_mean"], *references(groups, task, algo, "final_distance")
    )
    row |= _improvement_over_references(groups, key, boot)
    row |= boot.ci("curve_area_mean", areas, mean)
    row["invariance"] = combine_invariance(f["invariance"] for f in finals)
    row["steps_per_s"] = mean([f["steps_per_s"] for f in finals])
    row["wall_time_s"] = mean([f["wall_time_s"] for f in finals])
    row["eval_episodes"] = max(f["eval_episodes"] for f in finals)
    return row


def summarize(
    rows: Iterable[Row], reps: int = 2000, confidence: float = 0.95, seed: int = 0
) -> list[dict[str, Any]]:
    """One row per (task, entry, algo) of finished runs, sorted by task, algo and entry.

    Columns (numbers are floats, NaN where undefined; ``*_low``/``*_high`` bound the
    ``confidence`` stratified-bootstrap percentile interval of the column they extend, NaN
    with a single seed, where resampling cannot show any spread):

    * ``task``, ``entry``, ``potential``, ``model``, ``algo``, ``budget``, ``n_seeds``, ``seeds``;
    * ``success_iqm``, ``success_mean`` — final success rate over seeds;
    * ``success_any_mean`` — mean over seeds of the final success rate at any step of the
      episodes (MetaWorld's own protocol); NaN unless every run recorded it;
    * ``success_end_mean`` — where rows count success at any step
      (:func:`planshape.results.measure.measured`), the mean final success rate at the
      episode's end; NaN otherwise;
    * ``distance_iqm``, ``distance_mean`` — final distance to the goal (lower is better);
    * ``sparse_return_mean`` — final undiscounted return under the task's sparse reward;
    * ``normalized_success``, ``normalized_distance`` — ``normalized_score`` of the mean
      final success / distance against the means of the ``sparse`` and ``dense`` entries of the
      same task and algorithm (NaN when a reference is missing or the references tie);
    * ``p_improve`` — ``probability_of_improvement`` of final success over the ``sparse``
      entry of the same task and algorithm; ``p_improve_distance`` the same on final distance
      (a run improves when its distance is *lower*); NaN without a sparse entry;
      ``p_improve_dense`` — the same of final success over the ``dense`` entry (NaN without
      one);
    * ``curve_area_mean`` — mean ``curve_area`` of success rate over steps;
    * ``invariance`` — ``violated`` if any run's check says so, else ``not-checked`` if any run
      was not checked, else ``preserved`` (or ``not-applicable`` for sparse and dense);
    * ``steps_per_s``, ``wall_time_s`` — means over runs; ``eval_episodes`` — the largest count
      used (they agree within a profile).

    Runs without a final row are skipped (see
    :func:`~planshape.results.provenance.describe_runs`). The bootstrap uses ``seed`` for every
    interval, so the same rows always give the same numbers.
    """
    groups = _cells_of(rows)
    boot = _Bootstrap(reps, confidence, seed)
    return [_cell_row(groups, key, boot) for key in sorted(groups)]


# --------------------------------------------------------------------------------------------
# One row per entry and algorithm, over tasks
# --------------------------------------------------------------------------------------------


def _normalized_columns(
    groups: Cells, algo: str, entry: str, tasks: list[str], metric: str, boot: _Bootstrap
) -> dict[str, Any]:
    """IQM, mean and optimality gap of the runs' normalized ``metric``, pooled over tasks."""
    normalized: dict[str, np.ndarray] = {}
    excluded = []
    for task in tasks:
        scores = _normalized(groups, task, algo, entry, metric)
        if np.isnan(scores).all():
            excluded.append(task)
        else:
            normalized[task] = scores
    column = "normalized_" + ("success" if metric == "success_rate" else "distance")
    out = boot.ci(f"{column}_iqm", normalized, iqm) | boot.ci(f"{column}_mean", normalized, mean)
    out |= boot.ci(f"{column}_gap", normalized, optimality_gap)
    return out | {f"{column}_tasks_excluded": excluded}


def _final_scores(
    groups: Cells, algo: str, entry: str, tasks: list[str], metric: str, sign: float = 1.0
) -> dict[str, list[float]]:
    return {t: [sign * r.final[metric] for r in groups[(t, algo, entry)]] for t in tasks}


def _improvement_columns(
    groups: Cells, algo: str, entry: str, tasks: list[str], boot: _Bootstrap
) -> dict[str, float]:
    """P(improve) over sparse (success, and lower distance) and over dense (success)."""
    out: dict[str, float] = {}
    with_sparse = [t for t in tasks if (t, algo, SPARSE) in groups]
    for metric, column, sign in (
        ("success_rate", "p_improve", 1.0),
        ("final_distance", "p_improve_distance", -1.0),
    ):
        x, y = (_final_scores(groups, algo, e, with_sparse, metric, sign) for e in (entry, SPARSE))
        out |= boot.improvement(column, x, y)
    with_dense = [t for t in tasks if (t, algo, DENSE) in groups]
    x, y = (_final_scores(groups, algo, e, with_dense, "success_rate") for e in (entry, DENSE))
    return out | boot.improvement("p_improve_dense", x, y)


def _aggregate_row(
    groups: Cells, algo: str, entry: str, tasks: list[str], boot: _Bootstrap
) -> dict[str, Any]:
    runs = [r for t in tasks for r in groups[(t, algo, entry)]]
    row: dict[str, Any] = {
        "entry": entry,
        "algo": algo,
        "tasks": tasks,
        "n_tasks": len(tasks),
        "n_runs": len(runs),
        "min_seeds": min(len(groups[(t, algo, entry)]) for t in tasks),
    }
    for metric in ("success_rate", "final_distance"):
        row |= _normalized_columns(groups, algo, entry, tasks, metric, boot)
    row |= _improvement_columns(groups, algo, entry, tasks, boot)
    areas = {
        t: [curve_area(r.steps, r.success, r.final["budget"]) for r in groups[(t, algo, entry)]]
        for t in tasks
    }
    row |= boot.ci("curve_area_mean", areas, mean)
    row["invariance"] = combine_invariance(r.final["invariance"] for r in runs)
    return row


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
    ``normalized_success_gap`` (the optimality gap below dense's level, ``optimality_gap``),
    ``normalized_success_tasks_excluded``; the same for ``normalized_distance``;
    ``p_improve_dense`` (P(entry's success > dense's)), ``p_improve`` and
    ``p_improve_distance`` (over the tasks that have a sparse entry, with the
    stratified independent bootstrap); ``curve_area_mean``; ``invariance`` (combined as in
    :func:`summarize`).
    """
    groups = _cells_of(rows)
    by_entry: dict[tuple[str, str], list[str]] = defaultdict(list)
    for task, algo, entry in sorted(groups):
        by_entry[(algo, entry)].append(task)
    boot = _Bootstrap(reps, confidence, seed)
    return [
        _aggregate_row(groups, algo, entry, tasks, boot)
        for (algo, entry), tasks in sorted(by_entry.items())
    ]
