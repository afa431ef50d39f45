"""Tables: the leaderboard's tables as data, and the one place where numbers become text.

A :class:`Table` is headings and rows of :class:`Cell` (its text, the number it sorts by and
whether it is code); :mod:`planshape.results.render` writes it as Markdown or HTML. The
tables are :func:`task_table` (one cell per entry of a task and algorithm, ranked by IQM final
success), :func:`aggregate_table` (over tasks), :func:`verdict_table` (what every cell decides)
and :func:`evidence_table` (the same with its success means, across profiles),
:func:`setup_table`, :func:`budget_table` and :func:`hyperparameter_table`. Numbers are
formatted by :func:`number` and :func:`interval`.

Example:
    >>> number(0.12345), number(float("nan")), number(-0.0001, 2)
    ('0.123', 'n/a', '0.00')
    >>> interval({"x": 0.5, "x_low": 0.25, "x_high": 0.75, "n_seeds": 5}, "x", 2)
    '0.50 [0.25, 0.75]'
    >>> interval({"x": 0.5, "x_low": 0.25, "x_high": 0.75, "n_seeds": 3}, "x", 2)
    '0.50 (n=3: no CI)'
    >>> slug("planshape/Reach-v0")
    'planshape-Reach-v0'
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar, Literal

from planshape.results.cells import DENSE, SPARSE
from planshape.results.provenance import CPU_NOT_RECORDED

__all__ = [
    "CI_LABEL",
    "MIN_CI_SEEDS",
    "Cell",
    "Table",
    "aggregate_table",
    "budget_table",
    "by_task_and_algo",
    "caveats",
    "entry_order",
    "evidence_table",
    "hyperparameter_table",
    "interval",
    "missing",
    "number",
    "packages_text",
    "ranked_aggregate",
    "setup_table",
    "short_task",
    "slug",
    "task_table",
    "verdict_table",
]

#: the fewest seeds whose bootstrap interval is shown: with 2-4 seeds a percentile bootstrap
#: returns [min, max] or a zero-width interval, which says nothing about the uncertainty
MIN_CI_SEEDS = 5
CI_LABEL = "[95% CI]"

Summary = Mapping[str, Any]


@dataclass(frozen=True)
class Cell:
    """One cell: its text, the number it sorts by (None: sorted as text) and whether the text
    is code (an entry's name, a command)."""

    text: str
    value: float | None = None
    code: bool = False


@dataclass(frozen=True)
class Table:
    """Headings and rows of cells. ``sortable``: the HTML page sorts it by a clicked column;
    ``keyed``: a table of (label, text) pairs, whose labels head their rows. A table is a block
    of a page (:mod:`planshape.results.page`); ``only`` names the one medium it appears in."""

    kind: ClassVar[str] = "table"
    headings: tuple[str, ...]
    rows: tuple[tuple[Cell, ...], ...]
    sortable: bool = False
    keyed: bool = False
    only: Literal["markdown", "html"] | None = None


def slug(task: str) -> str:
    """A file-name-safe form of a task id."""
    return re.sub(r"[^A-Za-z0-9._-]+", "-", task).strip("-") or "task"


# --------------------------------------------------------------------------------------------
# Numbers as text
# --------------------------------------------------------------------------------------------


def missing(x: Any) -> bool:
    """None or NaN: a number that is not there."""
    return x is None or (isinstance(x, float) and math.isnan(x))


def number(x: Any, digits: int = 3) -> str:
    """``x`` with ``digits`` decimals, ``n/a`` when missing, never ``-0.000``."""
    if missing(x):
        return "n/a"
    text = f"{x:.{digits}f}"
    return text[1:] if text.startswith("-") and not text.strip("-0.") else text


def interval(row: Summary, column: str, digits: int = 3) -> str:
    """``value [low, high]``; with fewer than :data:`MIN_CI_SEEDS` seeds (per task, for an
    aggregate) the interval is not shown but marked ``(n=2: no CI)``."""
    value, low, high = row[column], row[f"{column}_low"], row[f"{column}_high"]
    if missing(value):
        return "n/a"
    seeds = row.get("n_seeds", row.get("min_seeds"))
    if seeds is not None and seeds < MIN_CI_SEEDS:
        return f"{number(value, digits)} (n={seeds}: no CI)"
    if missing(low) or missing(high):
        return number(value, digits)
    return f"{number(value, digits)} [{number(low, digits)}, {number(high, digits)}]"


def _value(row: Summary, column: str) -> float | None:
    v = row[column]
    return None if missing(v) else float(v)


def _number_cell(row: Summary, column: str, digits: int = 3) -> Cell:
    return Cell(number(row[column], digits), _value(row, column))


def _interval_cell(row: Summary, column: str, digits: int = 3) -> Cell:
    return Cell(interval(row, column, digits), _value(row, column))


def _count_cell(n: int) -> Cell:
    return Cell(str(n), float(n))


# --------------------------------------------------------------------------------------------
# Order
# --------------------------------------------------------------------------------------------


def _sort_key(x: Any, descending: bool) -> float:
    if missing(x):
        return math.inf
    return -x if descending else x


def entry_order(entries: Iterable[str]) -> list[str]:
    """sparse, dense, then the shaped entries alphabetically.

    Example:
        >>> entry_order(["plan-based/grid", "dense", "sparse"])
        ['sparse', 'dense', 'plan-based/grid']
    """
    unique = set(entries)
    return [e for e in (SPARSE, DENSE) if e in unique] + sorted(unique - {SPARSE, DENSE})


def _ranked_by(
    rows: Iterable[Summary], first: str, second: str, second_descending: bool
) -> list[Summary]:
    return sorted(
        rows,
        key=lambda r: (
            _sort_key(r[first], True),
            _sort_key(r[second], second_descending),
            r["entry"],
        ),
    )


def _ranked(summary: Iterable[Summary]) -> list[Summary]:
    """By IQM final success (high first), then IQM final distance (low first), then name."""
    return _ranked_by(summary, "success_iqm", "distance_iqm", False)


def ranked_aggregate(rows: Iterable[Summary]) -> list[Summary]:
    """By IQM normalized success, then IQM normalized distance (high first), then name."""
    return _ranked_by(rows, "normalized_success_iqm", "normalized_distance_iqm", True)


def by_task_and_algo(summary: Sequence[Summary]) -> dict[str, dict[str, list[Summary]]]:
    """task -> algo -> the summary rows of its cells, ranked as on the leaderboard."""
    out: dict[str, dict[str, list[Summary]]] = {}
    for row in summary:
        out.setdefault(row["task"], {}).setdefault(row["algo"], []).append(row)
    return {
        t: {a: _ranked(rows) for a, rows in sorted(by.items())} for t, by in sorted(out.items())
    }


# --------------------------------------------------------------------------------------------
# The result tables
# --------------------------------------------------------------------------------------------


def _cells_table(headings: Sequence[str], rows: Iterable[Sequence[Cell]]) -> Table:
    return Table(tuple(headings), tuple(tuple(r) for r in rows), sortable=True)


_TASK_HEADINGS = (
    "Entry",
    "Seeds",
    f"IQM success {CI_LABEL}",
    "Mean success",
    f"Final distance, IQM (m) {CI_LABEL}",
    "Norm. success",
    "Norm. distance",
    f"P(improve over sparse) {CI_LABEL}",
    "Curve area",
    "Invariance",
)


def _task_cells(row: Summary) -> tuple[Cell, ...]:
    return (
        Cell(row["entry"], code=True),
        _count_cell(row["n_seeds"]),
        _interval_cell(row, "success_iqm"),
        _number_cell(row, "success_mean"),
        _interval_cell(row, "distance_iqm"),
        _number_cell(row, "normalized_success", 2),
        _number_cell(row, "normalized_distance", 2),
        _interval_cell(row, "p_improve", 2),
        _number_cell(row, "curve_area_mean"),
        Cell(row["invariance"]),
    )


#: the columns of success counted the other way, after "Mean success": at any step of the
#: episodes where success counts at the end, at the end where it counts at any step
#: (:mod:`planshape.results.measure`)
_OTHER_SUCCESS_HEADINGS = {
    "success_any_mean": "Mean success, any step",
    "success_end_mean": "Mean success, episode end",
}


def task_table(ranked: Iterable[Summary]) -> Table:
    """The cells of one task and algorithm, ranked (:func:`by_task_and_algo`). Where some entry's
    runs recorded success counted the other way too (``success_any_mean`` or
    ``success_end_mean``), a column shows it after the mean success."""
    ranked = list(ranked)
    column = next(
        (c for c in _OTHER_SUCCESS_HEADINGS if not all(missing(r.get(c)) for r in ranked)), None
    )
    if column is None:
        return _cells_table(_TASK_HEADINGS, (_task_cells(r) for r in ranked))
    at = _TASK_HEADINGS.index("Mean success") + 1
    headings = (*_TASK_HEADINGS[:at], _OTHER_SUCCESS_HEADINGS[column], *_TASK_HEADINGS[at:])
    rows = (
        (*cells[:at], _number_cell(r, column), *cells[at:])
        for r, cells in ((r, _task_cells(r)) for r in ranked)
    )
    return _cells_table(headings, rows)


_AGGREGATE_HEADINGS = (
    "Entry",
    "Tasks",
    "Runs",
    f"IQM norm. success {CI_LABEL}",
    f"IQM norm. distance {CI_LABEL}",
    f"P(improve over sparse) {CI_LABEL}",
    "Curve area",
    "Not normalized on (dense no better than sparse)",
    "Invariance",
)


def short_task(task: str) -> str:
    """A task id without its namespace.

    Example:
        >>> short_task("planshape/Reach-v1")
        'Reach-v1'
    """
    return task.split("/", 1)[-1]


def _aggregate_cells(row: Summary) -> tuple[Cell, ...]:
    excluded = row.get("normalized_success_tasks_excluded", ())
    return (
        Cell(row["entry"], code=True),
        _count_cell(row["n_tasks"]),
        _count_cell(row["n_runs"]),
        _interval_cell(row, "normalized_success_iqm", 2),
        _interval_cell(row, "normalized_distance_iqm", 2),
        _interval_cell(row, "p_improve", 2),
        _number_cell(row, "curve_area_mean"),
        Cell(", ".join(short_task(t) for t in excluded) or "none"),
        Cell(row["invariance"]),
    )


def aggregate_table(rows: Iterable[Summary]) -> Table:
    """The entries of one algorithm over tasks, ranked (:func:`ranked_aggregate`)."""
    return _cells_table(_AGGREGATE_HEADINGS, (_aggregate_cells(r) for r in ranked_aggregate(rows)))


_VERDICT_HEADINGS = (
    "Task",
    "Algorithm",
    "Budget",
    "Budget check",
    "Shaping outcome",
    "Entry",
    f"P(entry > dense) {CI_LABEL}",
)


def _words(status: str) -> str:
    return status.replace("-", " ")


def _verdict_cells(check: Mapping[str, Any], *, successes: bool = False) -> tuple[Cell, ...]:
    entry = check["outcome_entry"]
    cells = [
        Cell(short_task(check["task"])),
        Cell(check["algo"]),
        Cell(f"{check['budget']:,}", float(check["budget"])),
        Cell(_words(check["status"])),
        Cell(_words(check["outcome"])),
        Cell(entry or "—", code=entry is not None),
    ]
    if successes:
        cells += [_number_cell(check, f"{who}_success", 2) for who in ("entry", DENSE, SPARSE)]
    return (*cells, _interval_cell(check, "outcome_p_improve_dense", 2))


def verdict_table(checks: Iterable[Mapping[str, Any]]) -> Table:
    """One row per (task, algorithm) cell: its budget, budget check and shaping outcome, from
    :func:`planshape.results.verdict.budget_checks`.

    Example:
        >>> table = verdict_table([{"task": "planshape/Reach-v1", "algo": "PPO", "budget": 4096,
        ...     "status": "decides", "outcome": "at-least-dense", "outcome_entry": "plan/grid",
        ...     "outcome_p_improve_dense": 0.6, "outcome_p_improve_dense_low": 0.3,
        ...     "outcome_p_improve_dense_high": 0.9}])
        >>> [cell.text for cell in table.rows[0]]
        ['Reach-v1', 'PPO', '4,096', 'decides', 'at least dense', 'plan/grid', '0.60 [0.30, 0.90]']
    """
    return _cells_table(_VERDICT_HEADINGS, (_verdict_cells(c) for c in checks))


def evidence_table(checks: Iterable[Mapping[str, Any]]) -> Table:
    """:func:`verdict_table` with the mean success of the outcome's entry, of dense and of
    sparse beside it (``entry_success``, ``dense_success``, ``sparse_success`` of each check;
    ``None``: not in the cell), for the page of every profile's verdicts
    (:mod:`planshape.results.evidence`).

    Example:
        >>> table = evidence_table([{"task": "planshape/Push-v1", "algo": "PPO", "budget": 819200,
        ...     "status": "decides", "outcome": "below-dense", "outcome_entry": "time-varying/grid",
        ...     "entry_success": 0.4, "dense_success": 0.8, "sparse_success": 0.2,
        ...     "outcome_p_improve_dense": 0.3, "outcome_p_improve_dense_low": 0.0,
        ...     "outcome_p_improve_dense_high": 0.6}])
        >>> [cell.text for cell in table.rows[0]][4:]
        ['below dense', 'time-varying/grid', '0.40', '0.80', '0.20', '0.30 [0.00, 0.60]']
    """
    headings = (
        *_VERDICT_HEADINGS[:6],
        "Entry success",
        "Dense success",
        "Sparse success",
        _VERDICT_HEADINGS[6],
    )
    return _cells_table(headings, (_verdict_cells(c, successes=True) for c in checks))


# --------------------------------------------------------------------------------------------
# The setup
# --------------------------------------------------------------------------------------------

#: Header keys with a place of their own; ``eval_episodes`` comes from the rows, which are
#: authoritative. Any other key is one more line of the setup table.
_HEADER_KEYS_SHOWN = frozenset(
    {"profile", "command", "caveats", "description", "eval_every", "eval_episodes"}
)


def _seeds_text(info: Mapping[str, Any]) -> str:
    per_entry = info["seeds_per_entry"] or [0, 0]
    if per_entry[0] != per_entry[1]:
        per_entry_text = f"{per_entry[0]} to {per_entry[1]} per entry"
    else:
        per_entry_text = f"{per_entry[0]} per entry"
    return f"{', '.join(map(str, info['seeds'])) or 'none'} ({per_entry_text})"


def _evaluation_items(info: Mapping[str, Any]) -> list[tuple[str, str]]:
    evaluations = info.get("evaluations") or {}
    texts = {text for by_task in evaluations.values() for text in by_task}
    if len(texts) == 1:
        return [("Evaluation (deterministic policy)", f"each point: {texts.pop()}")]
    return [
        (f"Evaluation of {task} (deterministic policy)", f"each point: {'; '.join(by_task)}")
        for task, by_task in evaluations.items()
    ]


def _cpu_items(info: Mapping[str, Any]) -> list[tuple[str, str]]:
    """The set-up table's CPU row, where some run recorded its CPU: an SBX run re-executes only
    on the CPU type that trained it (README, *Across CPU types an SBX run does not
    re-execute*), so the page says which that was.

    Example:
        >>> _cpu_items({"cpus": {"AMD EPYC (avx2)": 5, "not recorded": 150}})
        [('CPU', 'AMD EPYC (avx2): 5 runs; not recorded: 150 runs')]
        >>> _cpu_items({"cpus": {"not recorded": 150}})
        []
    """
    cpus = info.get("cpus") or {}
    if set(cpus) <= {CPU_NOT_RECORDED}:
        return []
    return [("CPU", "; ".join(f"{cpu}: {n} run{'s' * (n != 1)}" for cpu, n in cpus.items()))]


def _setup_items(header: Mapping[str, Any], info: Mapping[str, Any]) -> list[tuple[str, str]]:
    """(label, text) pairs describing how the results were produced."""
    items = [
        ("Profile", str(header.get("profile") or ", ".join(info["profiles"]) or "n/a")),
        ("Command", str(header.get("command", "n/a"))),
    ]
    if "description" in header:
        items.append(("Description", str(header["description"])))
    items += [
        ("Runs", f"{info['n_runs']} finished runs, {info['n_rows']} evaluation rows"),
        ("Seeds", _seeds_text(info)),
        *_evaluation_items(info),
    ]
    if isinstance(header.get("eval_every"), int):
        items.append(("Evaluated every", f"{header['eval_every']:,} environment steps"))
    items += [
        ("Discount γ", ", ".join(f"{g:g}" for g in info["gammas"]) or "n/a"),
        ("Code version", ", ".join(info["code_versions"]) or "n/a"),
        *_cpu_items(info),
        ("Total run time", f"{info['wall_time_s'] / 3600:.2f} h (sum over runs)"),
    ]
    for key in sorted(header):
        if key not in _HEADER_KEYS_SHOWN:
            items.append((key.replace("_", " ").capitalize(), str(header[key])))
    return items


def setup_table(header: Mapping[str, Any], info: Mapping[str, Any]) -> Table:
    """How the results were produced: profile, command, runs, seeds, evaluation, versions."""
    rows = tuple(
        (Cell(label), Cell(text, code=label == "Command"))
        for label, text in _setup_items(header, info)
    )
    return Table(("", ""), rows, keyed=True)


def budget_table(info: Mapping[str, Any]) -> Table:
    """Environment steps per task and algorithm."""
    algos = sorted({a for by_algo in info["budgets"].values() for a in by_algo})
    rows = tuple(
        (Cell(task), *(Cell(f"{by_algo[a]:,}" if a in by_algo else "–") for a in algos))
        for task, by_algo in info["budgets"].items()
    )
    return Table(("Task", *algos), rows)


def hyperparameter_table(info: Mapping[str, Any]) -> Table:
    """Every distinct setting of every task and algorithm, as JSON."""
    rows = tuple(
        (Cell(task), Cell(algo), Cell(json.dumps(s, sort_keys=True), code=True))
        for task, by_algo in info["hyperparameters"].items()
        for algo, settings in by_algo.items()
        for s in settings
    )
    return Table(("Task", "Algorithm", "Settings"), rows)


def packages_text(info: Mapping[str, Any]) -> str:
    """``name version`` of every package, several versions joined by ``/``."""
    return ", ".join(f"{name} {'/'.join(v)}" for name, v in info["packages"].items()) or "n/a"


def caveats(header: Mapping[str, Any], info: Mapping[str, Any]) -> list[str]:
    """The header's caveats, then those derived from the rows."""
    given = header.get("caveats") or []
    if isinstance(given, str):
        given = [given]
    return [str(c) for c in given] + list(info["caveats"])
