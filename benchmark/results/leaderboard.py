"""Rendering the leaderboard from tidy result rows.

:func:`render_leaderboard` writes, into one folder:

* ``LEADERBOARD.md`` — a header (profile, command, budgets, seeds, evaluation episodes, code and
  package versions, caveats), then per task and algorithm a table ranked by IQM final success;
* ``index.html`` — the same as a static page that works offline: inline CSS, a few lines of
  vanilla JavaScript to sort a table by clicking its header, plots inlined as base64 PNG;
* ``plots/curves_<task>.png`` (success rate over training steps, one line per entry, one panel
  per algorithm) and ``plots/final_distance_<task>.png`` (final distance per entry, as in the
  source paper's Figures 3–5);
* ``summary.json`` — :func:`planshape.results.scoring.summarize`,
:func:`planshape.results.scoring.aggregate` and
  the provenance, for machines (NaN written as ``null``).

The same rows always give byte-identical files (fixed bootstrap seed, sorted keys, PNGs without
timestamps or version strings), so re-rendering does not churn the git diff.
:func:`summary_table` is the plain-text table printed at the end of a benchmark run.

Example:
    >>> from planshape.results.scoring import load_rows
    >>> rows = load_rows("leaderboard")  # doctest: +SKIP
    >>> paths = render_leaderboard(rows, "leaderboard", {"profile": "default",
    ...     "command": "planshape bench", "caveats": []})  # doctest: +SKIP
    >>> print(summary_table(rows))  # doctest: +SKIP
"""

from __future__ import annotations

import base64
import html
import json
import math
import re
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from planshape.errors import ResultsError
from planshape.harness.store import write_atomic
from planshape.results.figures import save_png, style
from planshape.results.scoring import (
    DENSE,
    MIN_CI_SEEDS,
    SPARSE,
    aggregate,
    describe_runs,
    json_ready,
    learning_curve,
    normalized_scores,
    run_curves,
    summarize,
)

__all__ = ["render_leaderboard", "slug", "summary_table"]

PLOTS_DIR = "plots"
_PLOT_PREFIXES = ("curves_", "final_distance_", "aggregate_")
_DPI = 100
#: Matplotlib settings for every plot, applied on top of matplotlib's defaults (never the
#: user's matplotlibrc), so the PNGs are the same on every machine with the pinned matplotlib.
_STYLE = {
    "font.size": 9,
    "axes.titlesize": 10,
    "axes.labelsize": 9,
    "legend.fontsize": 7,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.spines.top": False,
    "axes.spines.right": False,
}


def slug(task: str) -> str:
    """A file-name-safe form of a task id.

    Example:
        >>> slug("planshape/Reach-v0")
        'planshape-Reach-v0'
    """
    return re.sub(r"[^A-Za-z0-9._-]+", "-", task).strip("-") or "task"


# --------------------------------------------------------------------------------------------
# Formatting numbers (only here do numbers become strings)
# --------------------------------------------------------------------------------------------


def _missing(x: Any) -> bool:
    return x is None or (isinstance(x, float) and math.isnan(x))


def _num(x: Any, digits: int = 3) -> str:
    if _missing(x):
        return "n/a"
    text = f"{x:.{digits}f}"
    return text[1:] if text.startswith("-") and not text.strip("-0.") else text  # no "-0.00"


def _ci(row: Mapping[str, Any], column: str, digits: int = 3) -> str:
    """``value [low, high]``; with fewer than :data:`MIN_CI_SEEDS` seeds (per task, for an
    aggregate) the interval is not shown but marked ``(n=2: no CI)``."""
    value, low, high = row[column], row[f"{column}_low"], row[f"{column}_high"]
    if _missing(value):
        return "n/a"
    seeds = row.get("n_seeds", row.get("min_seeds"))
    if seeds is not None and seeds < MIN_CI_SEEDS:
        return f"{_num(value, digits)} (n={seeds}: no CI)"
    if _missing(low) or _missing(high):
        return _num(value, digits)
    return f"{_num(value, digits)} [{_num(low, digits)}, {_num(high, digits)}]"


def _sort_key(x: Any, descending: bool) -> float:
    if _missing(x):
        return math.inf
    return -x if descending else x


def _entry_order(entries: Iterable[str]) -> list[str]:
    """sparse, dense, then the shaped entries alphabetically."""
    unique = set(entries)
    return [e for e in (SPARSE, DENSE) if e in unique] + sorted(unique - {SPARSE, DENSE})


def _ranked(summary: Iterable[Mapping[str, Any]]) -> list[Mapping[str, Any]]:
    """By IQM final success (high first), then IQM final distance (low first), then name."""
    return sorted(
        summary,
        key=lambda r: (
            _sort_key(r["success_iqm"], True),
            _sort_key(r["distance_iqm"], False),
            r["entry"],
        ),
    )


def _ranked_aggregate(rows: Iterable[Mapping[str, Any]]) -> list[Mapping[str, Any]]:
    return sorted(
        rows,
        key=lambda r: (
            _sort_key(r["normalized_success_iqm"], True),
            _sort_key(r["normalized_distance_iqm"], True),
            r["entry"],
        ),
    )


# --------------------------------------------------------------------------------------------
# The tables, as (column heading, cell text, sort value) cells
# --------------------------------------------------------------------------------------------

Cell = tuple[str, str, "float | None"]
_CI_LABEL = "[95% CI]"


def _task_cells(row: Mapping[str, Any], ci_label: str) -> list[Cell]:
    def value(column: str) -> float | None:
        v = row[column]
        return None if _missing(v) else float(v)

    return [
        ("Entry", row["entry"], None),
        ("Seeds", str(row["n_seeds"]), float(row["n_seeds"])),
        (f"IQM success {ci_label}", _ci(row, "success_iqm"), value("success_iqm")),
        ("Mean success", _num(row["success_mean"]), value("success_mean")),
        (f"Final distance, IQM (m) {ci_label}", _ci(row, "distance_iqm"), value("distance_iqm")),
        ("Norm. success", _num(row["normalized_success"], 2), value("normalized_success")),
        ("Norm. distance", _num(row["normalized_distance"], 2), value("normalized_distance")),
        (f"P(improve over sparse) {ci_label}", _ci(row, "p_improve", 2), value("p_improve")),
        ("Curve area", _num(row["curve_area_mean"]), value("curve_area_mean")),
        ("Invariance", row["invariance"], None),
    ]


def _aggregate_cells(row: Mapping[str, Any], ci_label: str) -> list[Cell]:
    def value(column: str) -> float | None:
        v = row[column]
        return None if _missing(v) else float(v)

    return [
        ("Entry", row["entry"], None),
        ("Tasks", str(row["n_tasks"]), float(row["n_tasks"])),
        ("Runs", str(row["n_runs"]), float(row["n_runs"])),
        (
            f"IQM norm. success {ci_label}",
            _ci(row, "normalized_success_iqm", 2),
            value("normalized_success_iqm"),
        ),
        (
            f"IQM norm. distance {ci_label}",
            _ci(row, "normalized_distance_iqm", 2),
            value("normalized_distance_iqm"),
        ),
        (f"P(improve over sparse) {ci_label}", _ci(row, "p_improve", 2), value("p_improve")),
        ("Curve area", _num(row["curve_area_mean"]), value("curve_area_mean")),
        (
            "Not normalized on (dense no better than sparse)",
            ", ".join(_short_task(t) for t in row.get("normalized_success_tasks_excluded", ()))
            or "none",
            None,
        ),
        ("Invariance", row["invariance"], None),
    ]


def _short_task(task: str) -> str:
    return task.split("/", 1)[-1]


def _by_task_and_algo(
    summary: Sequence[Mapping[str, Any]],
) -> dict[str, dict[str, list[Mapping[str, Any]]]]:
    out: dict[str, dict[str, list[Mapping[str, Any]]]] = {}
    for row in summary:
        out.setdefault(row["task"], {}).setdefault(row["algo"], []).append(row)
    return {
        t: {a: _ranked(rows) for a, rows in sorted(by.items())} for t, by in sorted(out.items())
    }


# --------------------------------------------------------------------------------------------
# Header
# --------------------------------------------------------------------------------------------


#: Header keys with a place of their own; ``eval_episodes`` comes from the rows, which are
#: authoritative. Any other key is one more line of the setup table.
_HEADER_KEYS_SHOWN = frozenset(
    {"profile", "command", "caveats", "description", "eval_every", "eval_episodes"}
)


def _setup_items(header: Mapping[str, Any], info: Mapping[str, Any]) -> list[tuple[str, str]]:
    """(label, text) pairs describing how the results were produced."""
    per_entry = info["seeds_per_entry"] or [0, 0]
    if per_entry[0] != per_entry[1]:
        per_entry_text = f"{per_entry[0]} to {per_entry[1]} per entry"
    else:
        per_entry_text = f"{per_entry[0]} per entry"
    items = [
        ("Profile", str(header.get("profile") or ", ".join(info["profiles"]) or "n/a")),
        ("Command", str(header.get("command", "n/a"))),
    ]
    if "description" in header:
        items.append(("Description", str(header["description"])))
    items += [
        ("Runs", f"{info['n_runs']} finished runs, {info['n_rows']} evaluation rows"),
        ("Seeds", f"{', '.join(map(str, info['seeds'])) or 'none'} ({per_entry_text})"),
    ]
    evaluations = info.get("evaluations") or {}
    texts = {text for by_task in evaluations.values() for text in by_task}
    if len(texts) == 1:
        items.append(("Evaluation (deterministic policy)", f"each point: {texts.pop()}"))
    else:
        items += [
            (f"Evaluation of {task} (deterministic policy)", f"each point: {'; '.join(by_task)}")
            for task, by_task in evaluations.items()
        ]
    if isinstance(header.get("eval_every"), int):
        items.append(("Evaluated every", f"{header['eval_every']:,} environment steps"))
    items += [
        ("Discount γ", ", ".join(f"{g:g}" for g in info["gammas"]) or "n/a"),
        ("Code version", ", ".join(info["code_versions"]) or "n/a"),
        ("Total run time", f"{info['wall_time_s'] / 3600:.2f} h (sum over runs)"),
    ]
    for key in sorted(header):
        if key not in _HEADER_KEYS_SHOWN:
            items.append((key.replace("_", " ").capitalize(), str(header[key])))
    return items


def _budget_table(info: Mapping[str, Any]) -> tuple[list[str], list[list[str]]]:
    algos = sorted({a for by_algo in info["budgets"].values() for a in by_algo})
    rows = [
        [task, *(f"{by_algo[a]:,}" if a in by_algo else "–" for a in algos)]
        for task, by_algo in info["budgets"].items()
    ]
    return ["Task", *algos], rows


def _packages_text(info: Mapping[str, Any]) -> str:
    return ", ".join(f"{name} {'/'.join(v)}" for name, v in info["packages"].items()) or "n/a"


def _caveats(header: Mapping[str, Any], info: Mapping[str, Any]) -> list[str]:
    given = header.get("caveats") or []
    if isinstance(given, str):
        given = [given]
    return [str(c) for c in given] + list(info["caveats"])


_HOW_TO_READ = (
    "**IQM**: interquartile mean over seeds (the mean of the middle 50% of runs; rliable). "
    "**[95% CI]**: percentile interval of the stratified bootstrap ({reps} resamples of the "
    "seeds, fixed seed). With fewer than 5 seeds in a cell no interval is shown, only "
    "marked (n=2: no CI): a percentile bootstrap of 2-4 seeds returns [min, max] or a "
    "zero-width interval, which says nothing about how much the seeds tell.",
    "**Success** and **final distance** are the task's own metrics at the end of training, over "
    "deterministic evaluation episodes; never the shaped return.",
    "**Norm. success / distance**: (entry − sparse) / (dense − sparse) of the mean over seeds: "
    "0 = as good as the sparse reward, 1 = as good as the hand-crafted dense reward, above 1 "
    "better; n/a where dense is no better than sparse (the scale would invert).",
    "**P(improve over sparse)**: probability that a run of the entry ends with a higher success "
    "rate than a run of the sparse reward (Mann-Whitney; ties count half; 0.5 = no difference).",
    "**Curve area**: area under success rate over training steps divided by the budget (1 = "
    "solved from the start); it rewards learning early.",
    "**Invariance**: whether the invariance check (exact value iteration on toy MDPs) found the "
    "optimal policy preserved or violated, was not run, or does not apply (no potential).",
)


# --------------------------------------------------------------------------------------------
# Markdown
# --------------------------------------------------------------------------------------------


def _md_escape(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _md_table(headings: Sequence[str], rows: Sequence[Sequence[str]]) -> list[str]:
    lines = ["| " + " | ".join(_md_escape(h) for h in headings) + " |"]
    lines.append("|" + "|".join("---" for _ in headings) + "|")
    lines += ["| " + " | ".join(_md_escape(c) for c in row) + " |" for row in rows]
    return lines


def _md_cells_table(cells: list[list[Cell]]) -> list[str]:
    headings = [h for h, _, _ in cells[0]]
    rows = [[f"`{t}`" if h == "Entry" else t for h, t, _ in row] for row in cells]
    return _md_table(headings, rows)


def _render_markdown(
    summary: Sequence[Mapping[str, Any]],
    overall: Sequence[Mapping[str, Any]],
    info: Mapping[str, Any],
    header: Mapping[str, Any],
    plots: Mapping[str, list[tuple[str, Path]]],
    videos: Mapping[str, list[tuple[str, Path]]],
    out_dir: Path,
    reps: int,
) -> str:
    lines = ["# planshape leaderboard", "", "## Setup", ""]
    setup = _setup_items(header, info)
    lines += _md_table(
        ["", ""], [[label, f"`{text}`" if label == "Command" else text] for label, text in setup]
    )
    lines += [
        "",
        "**Packages**: " + _packages_text(info),
        "",
        "### Budgets (environment steps)",
        "",
    ]
    lines += _md_table(*_budget_table(info))
    lines += ["", "### Caveats", ""]
    lines += [f"- {c}" for c in _caveats(header, info)] or ["- none"]
    lines += ["", "### How to read the tables", ""]
    lines += [f"- {text}".replace("{reps}", str(reps)) for text in _HOW_TO_READ]
    tasks = _by_task_and_algo(summary)
    if len(tasks) > 1 and overall:
        lines += ["", "## Across tasks", ""]
        lines.append(
            "IQM over every run's task-normalized score, pooled over the tasks each entry ran on "
            "(stratified bootstrap over seeds within tasks)."
        )
        for algo in sorted({r["algo"] for r in overall}):
            ranked = _ranked_aggregate(r for r in overall if r["algo"] == algo)
            lines += ["", f"### {algo}", ""]
            lines += _md_cells_table([_aggregate_cells(r, _CI_LABEL) for r in ranked])
        for caption, path in plots.get(ACROSS, []):
            lines += ["", f"![{caption}]({path.relative_to(out_dir).as_posix()})"]
    for task, by_algo in tasks.items():
        lines += ["", f"## {task}"]
        for algo, rows in by_algo.items():
            lines += ["", f"### {algo} — budget {rows[0]['budget']:,} steps", ""]
            lines += _md_cells_table([_task_cells(r, _CI_LABEL) for r in rows])
        for caption, path in [*plots.get(task, []), *videos.get(task, [])]:
            lines += ["", f"![{caption}]({path.relative_to(out_dir).as_posix()})"]
    hyper = info["hyperparameters"]
    if hyper:
        lines += ["", "## Hyperparameters", ""]
        table = [
            [task, algo, f"`{json.dumps(s, sort_keys=True)}`"]
            for task, by_algo in hyper.items()
            for algo, settings in by_algo.items()
            for s in settings
        ]
        lines += _md_table(["Task", "Algorithm", "Settings"], table)
    return "\n".join(lines) + "\n"


# --------------------------------------------------------------------------------------------
# HTML
# --------------------------------------------------------------------------------------------

_CSS = """
body { font-family: system-ui, sans-serif; margin: 2em auto; max-width: 80em; padding: 0 1em;
       color: #222; }
table { border-collapse: collapse; margin: 0.5em 0 1.5em; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: left; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
table.sortable th { cursor: pointer; background: #f3f3f3; user-select: none; }
table.sortable th[aria-sort=ascending]::after { content: " \\25B2"; }
table.sortable th[aria-sort=descending]::after { content: " \\25BC"; }
code { background: #f3f3f3; padding: 0 0.2em; }
img { max-width: 100%; }
"""

# Click a heading to sort by it; click again to reverse. Numeric cells sort by data-value,
# "n/a" cells (empty data-value) always last.
_JS = """
document.querySelectorAll("table.sortable").forEach(function (table) {
  function key(cell) {
    var v = cell.getAttribute("data-value");
    if (v === null) return cell.textContent;
    return v === "" ? null : parseFloat(v);
  }
  table.querySelectorAll("th").forEach(function (th) {
    th.addEventListener("click", function () {
      var col = th.cellIndex, body = table.tBodies[0];
      var asc = th.getAttribute("aria-sort") !== "ascending";
      table.querySelectorAll("th").forEach(function (h) { h.removeAttribute("aria-sort"); });
      th.setAttribute("aria-sort", asc ? "ascending" : "descending");
      var rows = Array.prototype.slice.call(body.rows);
      rows.sort(function (a, b) {
        var x = key(a.cells[col]), y = key(b.cells[col]);
        if (x === null || y === null) return (x === null) - (y === null);
        var c = typeof x === "number" ? x - y : String(x).localeCompare(String(y));
        return asc ? c : -c;
      });
      rows.forEach(function (r) { body.appendChild(r); });
    });
  });
});
"""


def _e(text: Any) -> str:
    return html.escape(str(text), quote=True)


def _html_table(headings: Sequence[str], rows: Sequence[Sequence[Cell]], sortable: bool) -> str:
    head = "".join(f"<th>{_e(h)}</th>" for h in headings)
    body = []
    for row in rows:
        cells = []
        for heading, text, value in row:
            if heading == "Entry":
                cells.append(f"<td><code>{_e(text)}</code></td>")
            elif value is None and text in ("n/a", "–"):
                cells.append(f'<td class="num" data-value="">{_e(text)}</td>')
            elif value is None:
                cells.append(f"<td>{_e(text)}</td>")
            else:
                cells.append(f'<td class="num" data-value="{value!r}">{_e(text)}</td>')
        body.append("<tr>" + "".join(cells) + "</tr>")
    css = ' class="sortable"' if sortable else ""
    return (
        f"<table{css}><thead><tr>{head}</tr></thead><tbody>\n"
        + "\n".join(body)
        + "\n</tbody></table>"
    )


def _html_cells_table(cells: list[list[Cell]]) -> str:
    return _html_table([h for h, _, _ in cells[0]], cells, sortable=True)


def _png_data_uri(path: Path) -> str:
    kind = "gif" if path.suffix == ".gif" else "png"
    return f"data:image/{kind};base64," + base64.b64encode(path.read_bytes()).decode("ascii")


def _html_figure(caption: str, path: Path) -> str:
    """An image inlined as a data URI, with its caption."""
    return (
        f'<figure><img alt="{_e(caption)}" src="{_png_data_uri(path)}">'
        f"<figcaption>{_e(caption)}</figcaption></figure>"
    )


def _videos(out_dir: Path, tasks: Iterable[str]) -> dict[str, list[tuple[str, Path]]]:
    """The policy animations in ``<out>/videos/`` (``planshape render``), by task."""
    folder = out_dir / "videos"
    found: dict[str, list[tuple[str, Path]]] = {}
    for task in tasks:
        for path in sorted(folder.glob(f"{slug(task)}__*.gif")) if folder.is_dir() else ():
            _, entry, algo, seed = path.stem.split("__")
            caption = f"{task}: final policy of {entry.replace('-', '/', 1)} ({algo}, {seed})"
            found.setdefault(task, []).append((caption, path))
    return found


def _render_html(
    summary: Sequence[Mapping[str, Any]],
    overall: Sequence[Mapping[str, Any]],
    info: Mapping[str, Any],
    header: Mapping[str, Any],
    plots: Mapping[str, list[tuple[str, Path]]],
    videos: Mapping[str, list[tuple[str, Path]]],
    reps: int,
) -> str:
    parts = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        '<meta name="viewport" content="width=device-width, initial-scale=1">',
        "<title>planshape leaderboard</title>",
        f"<style>{_CSS}</style></head><body>",
        "<h1>planshape leaderboard</h1>",
        "<h2>Setup</h2>",
    ]
    setup = [[("", label, None), ("", text, None)] for label, text in _setup_items(header, info)]
    rows = "".join(
        f"<tr><th>{_e(label)}</th><td>{_e(text)}</td></tr>" for (_, label, _), (_, text, _) in setup
    )
    parts.append(f"<table>{rows}</table>")
    parts.append(f"<p><strong>Packages</strong>: {_e(_packages_text(info))}</p>")
    parts.append("<h3>Budgets (environment steps)</h3>")
    headings, budget_rows = _budget_table(info)
    parts.append(
        _html_table(
            headings,
            [[(h, t, None) for h, t in zip(headings, r, strict=True)] for r in budget_rows],
            sortable=False,
        )
    )
    parts.append("<h3>Caveats</h3><ul>")
    parts += [f"<li>{_e(c)}</li>" for c in _caveats(header, info)] or ["<li>none</li>"]
    parts.append("</ul><h3>How to read the tables</h3><ul>")
    for text in _HOW_TO_READ:
        text = _e(text.replace("{reps}", str(reps)))
        parts.append("<li>" + re.sub(r"\*\*(.+?)\*\*", r"<strong>\1</strong>", text) + "</li>")
    parts.append("</ul><p>Click a column heading to sort a table.</p>")
    tasks = _by_task_and_algo(summary)
    if len(tasks) > 1 and overall:
        parts.append("<h2>Across tasks</h2>")
        parts.append(
            "<p>IQM over every run's task-normalized score, pooled over the tasks each entry ran "
            "on (stratified bootstrap over seeds within tasks).</p>"
        )
        for algo in sorted({r["algo"] for r in overall}):
            ranked = _ranked_aggregate(r for r in overall if r["algo"] == algo)
            parts.append(f"<h3>{_e(algo)}</h3>")
            parts.append(_html_cells_table([_aggregate_cells(r, _CI_LABEL) for r in ranked]))
        parts += [_html_figure(caption, path) for caption, path in plots.get(ACROSS, [])]
    for task, by_algo in tasks.items():
        parts.append(f'<h2 id="{_e(slug(task))}">{_e(task)}</h2>')
        for algo, rows_ in by_algo.items():
            parts.append(f"<h3>{_e(algo)} — budget {rows_[0]['budget']:,} steps</h3>")
            parts.append(_html_cells_table([_task_cells(r, _CI_LABEL) for r in rows_]))
        figures = [*plots.get(task, []), *videos.get(task, [])]
        parts += [_html_figure(caption, path) for caption, path in figures]
    parts.append(f"<script>{_JS}</script>")
    parts.append("</body></html>")
    return "\n".join(parts) + "\n"


# --------------------------------------------------------------------------------------------
# Plots
# --------------------------------------------------------------------------------------------


def _plot_curves(
    task: str,
    runs_by_algo: Mapping[str, Mapping[str, list[tuple[np.ndarray, np.ndarray]]]],
    budgets: Mapping[str, int],
    path: Path,
    reps: int,
    seed: int,
) -> None:
    """Small multiples: a row per algorithm, a panel per potential family (its models in
    line styles), with sparse and dense drawn thin in every panel for reference."""
    from matplotlib.figure import Figure
    from matplotlib.ticker import MaxNLocator

    algos = sorted(runs_by_algo)
    families = sorted(
        {e.split("/")[0] for by in runs_by_algo.values() for e in by if e not in (SPARSE, DENSE)}
    ) or ["references"]
    columns = min(len(families), 4)
    rows_per_algo = math.ceil(len(families) / columns)
    fig = Figure(
        figsize=(3.1 * columns + 0.6, 2.3 * rows_per_algo * len(algos) + 0.9),
        layout="constrained",
    )
    grid = fig.subplots(rows_per_algo * len(algos), columns, squeeze=False, sharex="row")
    for a, algo in enumerate(algos):
        curves_of = runs_by_algo[algo]
        for f, family in enumerate(families):
            ax = grid[a * rows_per_algo + f // columns][f % columns]
            ax.xaxis.set_major_locator(MaxNLocator(4))
            if family != "references" and not any(
                e.split("/")[0] == family for e in curves_of if e not in (SPARSE, DENSE)
            ):
                ax.set_visible(False)  # this algorithm did not run that family
                continue
            for entry in _entry_order(curves_of):
                reference = entry in (SPARSE, DENSE)
                if not reference and entry.split("/")[0] != family:
                    continue
                grid_x, avg, low, high = learning_curve(curves_of[entry], reps=reps, seed=seed)
                look = style(entry)
                ax.plot(
                    grid_x,
                    avg,
                    color=look["color"],
                    linestyle=look["linestyle"],
                    linewidth=0.9 if reference else 1.5,
                    label=entry,
                )
                if not reference:
                    ax.fill_between(grid_x, low, high, color=look["color"], alpha=0.15, lw=0)
            ax.set_title(f"{algo}: {family}", fontsize=8)
            ax.set_ylim(-0.03, 1.03)
            ax.set_xlim(0, budgets[algo])
            ax.tick_params(labelsize=7)
            ax.legend(fontsize=6, loc="upper left")
        for f in range(len(families), rows_per_algo * columns):
            grid[a * rows_per_algo + f // columns][f % columns].set_visible(False)
    for ax in grid[:, 0]:
        ax.set_ylabel("success rate", fontsize=8)
    for ax in grid[-1]:
        ax.set_xlabel("environment steps", fontsize=8)
    fig.suptitle(
        f"{task}: success rate during training (mean over seeds, 95% bootstrap CI; "
        "sparse black, dense grey)"
    )
    save_png(fig, path, dpi=_DPI)


def _plot_final_distance(
    task: str,
    rows_by_algo: Mapping[str, list[Mapping[str, Any]]],
    path: Path,
    seeds: Mapping[tuple[str, str], list[float]] | None = None,
) -> None:
    """Bars of the mean final distance per entry with its CI, and every seed as a point."""
    from matplotlib.figure import Figure

    algos = sorted(rows_by_algo)
    width = max(len(rows) for rows in rows_by_algo.values())
    fig = Figure(figsize=(max(3.0, 0.45 * width + 1.2) * len(algos), 3.6), layout="constrained")
    axes = fig.subplots(1, len(algos), sharey=True, squeeze=False)[0]
    for ax, algo in zip(axes, algos, strict=True):
        by_entry = {r["entry"]: r for r in rows_by_algo[algo]}
        entries = _entry_order(by_entry)
        x = np.arange(len(entries))
        height = np.array([by_entry[e]["distance_mean"] for e in entries], dtype=float)
        low = np.array([by_entry[e]["distance_mean_low"] for e in entries], dtype=float)
        high = np.array([by_entry[e]["distance_mean_high"] for e in entries], dtype=float)
        shown = ~np.isnan(height)
        errors = np.nan_to_num(np.vstack([height - low, high - height]), nan=0.0)
        ax.bar(
            x[shown],
            height[shown],
            yerr=errors[:, shown],
            color=[style(e)["color"] for e, s in zip(entries, shown, strict=True) if s],
            alpha=0.55,
            capsize=3,
            error_kw={"linewidth": 1},
        )
        for xi, entry in zip(x, entries, strict=True):
            values = (seeds or {}).get((algo, entry), [])
            if values:
                jitter = np.linspace(-0.18, 0.18, len(values)) if len(values) > 1 else [0.0]
                ax.plot(
                    xi + np.asarray(jitter),
                    values,
                    linestyle="none",
                    marker=style(entry)["marker"],
                    markersize=3.5,
                    color="#222222",
                )
        ax.set_xticks(x, entries, rotation=35, ha="right", fontsize=7)
        ax.set_title(algo)
        ax.grid(axis="x", visible=False)
    axes[0].set_ylabel("final distance to goal (m)")
    fig.suptitle(
        f"{task}: final distance to the goal\n(lower is better; bars: mean over seeds with 95% "
        "bootstrap CI; points: each seed)"
    )
    save_png(fig, path, dpi=_DPI)


def _render_plots(
    rows: Sequence[Mapping[str, Any]],
    summary: Sequence[Mapping[str, Any]],
    overall: Sequence[Mapping[str, Any]],
    plots_dir: Path,
    reps: int,
    seed: int,
) -> dict[str, list[tuple[str, Path]]]:
    import matplotlib

    curves = run_curves(rows)
    identity = {r["run_id"]: (r["task"], r["algo"], r["entry"]) for r in rows if r["final"]}
    runs: dict[str, dict[str, dict[str, list[tuple[np.ndarray, np.ndarray]]]]] = {}
    for run_id, curve in curves.items():
        task, algo, entry = identity[run_id]
        runs.setdefault(task, {}).setdefault(algo, {}).setdefault(entry, []).append(curve)
    tasks = _by_task_and_algo(summary)
    seeds_of: dict[str, dict[tuple[str, str], list[float]]] = {}
    for r in sorted((r for r in rows if r["final"]), key=lambda r: (r["seed"], r["run_id"])):
        by_entry = seeds_of.setdefault(r["task"], {})
        by_entry.setdefault((r["algo"], r["entry"]), []).append(float(r["final_distance"]))
    written: dict[str, list[tuple[str, Path]]] = {}
    with matplotlib.rc_context():
        matplotlib.rcdefaults()
        matplotlib.rcParams.update(_STYLE)
        for task, by_algo in tasks.items():
            budgets = {algo: rows_[0]["budget"] for algo, rows_ in by_algo.items()}
            curves_path = plots_dir / f"curves_{slug(task)}.png"
            _plot_curves(task, runs[task], budgets, curves_path, reps, seed)
            bars_path = plots_dir / f"final_distance_{slug(task)}.png"
            _plot_final_distance(task, by_algo, bars_path, seeds_of.get(task, {}))
            written[task] = [
                (f"{task}: learning curves", curves_path),
                (f"{task}: final distance per entry", bars_path),
            ]
        if len(tasks) > 1:
            written[ACROSS] = _across_task_figures(rows, overall, plots_dir, seed)
    return written


#: the key of the across-task figures among the plots of each task
ACROSS = ""


def _across_task_figures(
    rows: Sequence[Mapping[str, Any]],
    overall: Sequence[Mapping[str, Any]],
    plots_dir: Path,
    seed: int,
) -> list[tuple[str, Path]]:
    """rliable's aggregate figures (:mod:`planshape.results.figures`), pooled over tasks."""
    from planshape.results import figures

    made = [
        (
            "interval estimates: IQM, mean and optimality gap of the normalized success",
            figures.plot_interval_estimates(overall, plots_dir / "aggregate_intervals.png"),
        ),
        (
            "performance profiles: fraction of runs above each normalized success",
            figures.plot_performance_profiles(
                normalized_scores(rows), plots_dir / "aggregate_profiles.png", seed=seed
            ),
        ),
        (
            "probability of improvement over sparse and over dense",
            figures.plot_probability_of_improvement(
                overall, plots_dir / "aggregate_improvement.png"
            ),
        ),
    ]
    return [(caption, path) for caption, path in made if path is not None]


# --------------------------------------------------------------------------------------------
# Entry points
# --------------------------------------------------------------------------------------------


def render_leaderboard(
    rows: Iterable[Mapping[str, Any]],
    out_dir: str | Path,
    header: Mapping[str, Any],
    *,
    reps: int = 2000,
    seed: int = 0,
) -> list[Path]:
    """Write ``LEADERBOARD.md``, ``index.html``, ``summary.json`` and the plots into ``out_dir``.

    ``header`` gives what the rows cannot: ``profile`` (the profile's name), ``command`` (the
    command that produced the results) and ``caveats`` (a list of sentences); any other key is
    shown as one more line of the setup table (keep it free of dates, or every re-render
    changes the file). Budgets, seeds, evaluation episodes, code and package versions,
    hyperparameters and derived caveats come from the rows
    (:func:`planshape.results.scoring.describe_runs`).

    Plots go to ``out_dir/plots/``; plot files of tasks no longer in the rows are removed from
    there. Returns the written files, sorted. Raises :class:`planshape.errors.ResultsError`
    when there is no finished run to render.

    Example:
        >>> render_leaderboard([], "/tmp/lb", {"profile": "smoke"})
        Traceback (most recent call last):
        ...
        planshape.errors.ResultsError: no finished runs to render; run `planshape bench` first
    """
    rows = list(rows)
    summary = summarize(rows, reps=reps, seed=seed)
    if not summary:
        raise ResultsError("no finished runs to render; run `planshape bench` first")
    overall = aggregate(rows, reps=reps, seed=seed)
    info = describe_runs(rows, profile=header.get("profile"))
    out = Path(out_dir)
    plots_dir = out / PLOTS_DIR
    plots_dir.mkdir(parents=True, exist_ok=True)
    plots = _render_plots(rows, summary, overall, plots_dir, reps, seed)
    pngs = {path for task_plots in plots.values() for _, path in task_plots}
    for stale in sorted(plots_dir.glob("*.png")):
        if stale.name.startswith(_PLOT_PREFIXES) and stale not in pngs:
            stale.unlink()

    videos = _videos(out, {r["task"] for r in summary})
    markdown = _render_markdown(summary, overall, info, header, plots, videos, out, reps)
    page = _render_html(summary, overall, info, header, plots, videos, reps)
    machine = {
        "header": {**header, "caveats": _caveats(header, info)},
        "provenance": {k: v for k, v in info.items() if k != "caveats"},
        "per_task": summary,
        "aggregate": overall,
        "statistics": {"bootstrap_reps": reps, "bootstrap_seed": seed, "confidence": 0.95},
    }
    text = json.dumps(json_ready(machine), sort_keys=True, indent=2, allow_nan=False, default=str)
    files = {
        out / "LEADERBOARD.md": markdown,
        out / "index.html": page,
        out / "summary.json": text + "\n",
    }
    for path, content in files.items():
        write_atomic(path, content)
    return sorted([*files, *pngs])


def summary_table(rows: Iterable[Mapping[str, Any]], *, reps: int = 2000, seed: int = 0) -> str:
    """A plain-text table of every task, algorithm and entry, ranked as on the leaderboard.

    Example:
        >>> summary_table([])
        'no finished runs'
    """
    summary = summarize(rows, reps=reps, seed=seed)
    if not summary:
        return "no finished runs"
    headings = [
        "task", "algo", "entry", "seeds", "IQM success [95% CI]", "final dist (m)",
        "norm. success", "P(>sparse)", "curve area", "invariance",
    ]  # fmt: skip
    table = []
    for task, by_algo in _by_task_and_algo(summary).items():
        for algo, ranked in by_algo.items():
            for r in ranked:
                table.append(
                    [
                        task,
                        algo,
                        r["entry"],
                        str(r["n_seeds"]),
                        _ci(r, "success_iqm", 2),
                        _num(r["distance_iqm"]),
                        _num(r["normalized_success"], 2),
                        _num(r["p_improve"], 2),
                        _num(r["curve_area_mean"], 2),
                        r["invariance"],
                    ]
                )
    widths = [max(len(h), *(len(row[i]) for row in table)) for i, h in enumerate(headings)]
    numeric = {3, 4, 5, 6, 7, 8}

    def line(cells: Sequence[str]) -> str:
        return "  ".join(
            c.rjust(w) if i in numeric else c.ljust(w)
            for i, (c, w) in enumerate(zip(cells, widths, strict=True))
        ).rstrip()

    out = [line(headings), "  ".join("-" * w for w in widths)]
    previous = None
    for row in table:
        if previous is not None and row[:2] != previous:
            out.append("")
        out.append(line(row))
        previous = row[:2]
    return "\n".join(out)
