"""The leaderboard: stored rows in, ``LEADERBOARD.md``, ``index.html``, ``summary.json`` and
plots out.

:func:`render_leaderboard` scores the rows (:mod:`planshape.results.cells`), reads their
provenance (:mod:`planshape.results.provenance`), draws the plots
(:mod:`planshape.results.plots`), builds one page model (:mod:`planshape.results.page`) and
writes it as Markdown and as a static HTML page that works offline
(:mod:`planshape.results.render`), beside ``summary.json``: the per-task and across-task
tables, each cell's budget check (:mod:`planshape.results.verdict`) and the provenance, for
machines (NaN written as ``null``). ``planshape leaderboard`` (:mod:`planshape.harness.bench`)
calls it.

The same rows always give byte-identical files (fixed bootstrap seed, sorted keys, PNGs without
timestamps or version strings), so re-rendering does not churn the git diff.
:func:`summary_table` is the plain-text table printed at the end of a benchmark run.

Example:
    >>> from planshape.results.rows import load_rows
    >>> rows = load_rows("leaderboard")  # doctest: +SKIP
    >>> paths = render_leaderboard(rows, "leaderboard", {"profile": "default",
    ...     "command": "planshape bench", "caveats": []})  # doctest: +SKIP
    >>> print(summary_table(rows))  # doctest: +SKIP
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

from planshape.errors import ResultsError
from planshape.harness.store import write_atomic
from planshape.results import render
from planshape.results.cells import aggregate, summarize
from planshape.results.page import build_page
from planshape.results.plots import PLOTS_DIR, render_plots
from planshape.results.provenance import describe_runs
from planshape.results.tables import by_task_and_algo, caveats, interval, number, slug
from planshape.results.verdict import budget_checks

__all__ = ["render_leaderboard", "summary_table"]


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
    (:func:`planshape.results.provenance.describe_runs`).

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
    plots = render_plots(rows, summary, overall, out / PLOTS_DIR, reps, seed)
    videos = _videos(out, {r["task"] for r in summary})
    figures = {k: [*plots.get(k, []), *videos.get(k, [])] for k in plots.keys() | videos.keys()}
    page = build_page(summary, overall, info, header, figures, out, reps)
    files = {
        out / "LEADERBOARD.md": render.markdown(page),
        out / "index.html": render.html(page, out),
        out / "summary.json": _summary_json(header, info, summary, overall, reps, seed),
    }
    for path, content in files.items():
        write_atomic(path, content)
    pngs = [path for task_plots in plots.values() for _, path in task_plots]
    return sorted([*files, *pngs])


def _summary_json(
    header: Mapping[str, Any],
    info: Mapping[str, Any],
    summary: Sequence[Mapping[str, Any]],
    overall: Sequence[Mapping[str, Any]],
    reps: int,
    seed: int,
) -> str:
    machine = {
        "header": {**header, "caveats": caveats(header, info)},
        "provenance": {k: v for k, v in info.items() if k != "caveats"},
        "per_task": summary,
        "budget_checks": budget_checks(summary),
        "aggregate": overall,
        "statistics": {"bootstrap_reps": reps, "bootstrap_seed": seed, "confidence": 0.95},
    }
    text = json.dumps(
        render.json_ready(machine), sort_keys=True, indent=2, allow_nan=False, default=str
    )
    return text + "\n"


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
    for task, by_algo in by_task_and_algo(summary).items():
        for algo, ranked in by_algo.items():
            for r in ranked:
                table.append(
                    [
                        task,
                        algo,
                        r["entry"],
                        str(r["n_seeds"]),
                        interval(r, "success_iqm", 2),
                        number(r["distance_iqm"]),
                        number(r["normalized_success"], 2),
                        number(r["p_improve"], 2),
                        number(r["curve_area_mean"], 2),
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

    checks = {(c["task"], c["algo"]): c for c in budget_checks(summary)}
    out = [line(headings), "  ".join("-" * w for w in widths)]
    for i, row in enumerate(table):
        out.append(line(row))
        if i + 1 == len(table) or table[i + 1][:2] != row[:2]:
            check = checks[row[0], row[1]]
            out += [
                f"budget check: {check['text']}",
                f"shaping outcome: {check['outcome_text']}",
                "",
            ]
    return "\n".join(out[:-1])
