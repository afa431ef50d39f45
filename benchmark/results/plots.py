"""The leaderboard's plots, written into ``<out>/plots/``: per task, the learning curves and
the final distances; across tasks, :mod:`planshape.results.figures`' aggregate figures.

* ``curves_<task>.png`` — success rate over training steps: a row per algorithm, a panel per
  potential family (its models in line styles), sparse and dense thin in every panel;
* ``final_distance_<task>.png`` — final distance per entry (bars with CIs, every seed a point),
  as in the source paper's Figures 3–5;
* ``aggregate_*.png`` — interval estimates, performance profiles, probability of improvement.

Every plot is drawn on matplotlib's defaults plus :data:`STYLE` (never the user's
matplotlibrc) and saved without timestamps, so the same rows give the same bytes.

Example:
    >>> sorted(STYLE)[:2]
    ['axes.grid', 'axes.labelsize']
    >>> render_plots([], [], [], Path("/tmp/none"), reps=10, seed=0)
    {}
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from planshape.results import figures
from planshape.results.cells import DENSE, SPARSE, normalized_scores, run_curves
from planshape.results.figures import save_png, style, suptitle
from planshape.results.page import ACROSS
from planshape.results.stats import learning_curve
from planshape.results.tables import by_task_and_algo, entry_order, slug

__all__ = ["PLOTS_DIR", "PLOT_PREFIXES", "STYLE", "render_plots"]

PLOTS_DIR = "plots"
#: the names of the plot files this module writes start with one of these
PLOT_PREFIXES = ("curves_", "final_distance_", "aggregate_")
_DPI = 100
#: Matplotlib settings for every plot, applied on top of matplotlib's defaults (never the
#: user's matplotlibrc), so the PNGs are the same on every machine with the pinned matplotlib.
STYLE = {
    "font.size": 9,
    "axes.titlesize": 10,
    "axes.labelsize": 9,
    "legend.fontsize": 7,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.spines.top": False,
    "axes.spines.right": False,
}

Curves = list[tuple[np.ndarray, np.ndarray]]


def _curve_panel(
    ax: Any,
    algo: str,
    family: str,
    curves_of: Mapping[str, Curves],
    budget: int,
    reps: int,
    seed: int,
) -> None:
    """One panel: the mean curve of each entry of ``family`` with its band, sparse and dense
    thin; hidden when ``algo`` did not run that family."""
    if family != "references" and not any(
        e.split("/")[0] == family for e in curves_of if e not in (SPARSE, DENSE)
    ):
        ax.set_visible(False)
        return
    for entry in entry_order(curves_of):
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
    ax.set_xlim(0, budget)
    ax.tick_params(labelsize=7)
    ax.legend(fontsize=6, loc="upper left")


def _plot_curves(
    task: str,
    runs_by_algo: Mapping[str, Mapping[str, Curves]],
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
        for f, family in enumerate(families):
            ax = grid[a * rows_per_algo + f // columns][f % columns]
            ax.xaxis.set_major_locator(MaxNLocator(4))
            _curve_panel(ax, algo, family, runs_by_algo[algo], budgets[algo], reps, seed)
        for f in range(len(families), rows_per_algo * columns):
            grid[a * rows_per_algo + f // columns][f % columns].set_visible(False)
    for ax in grid[:, 0]:
        ax.set_ylabel("success rate", fontsize=8)
    for ax in grid[-1]:
        ax.set_xlabel("environment steps", fontsize=8)
    suptitle(
        fig,
        f"{task}: success rate during training\n(mean over seeds, 95% bootstrap CI; "
        "sparse black, dense grey)",
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
    fig = Figure(figsize=(max(4.0, 0.45 * width + 1.2) * len(algos), 3.6), layout="constrained")
    axes = fig.subplots(1, len(algos), sharey=True, squeeze=False)[0]
    for ax, algo in zip(axes, algos, strict=True):
        by_entry = {r["entry"]: r for r in rows_by_algo[algo]}
        entries = entry_order(by_entry)
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
    suptitle(
        fig,
        f"{task}: final distance to the goal\n(lower is better; bars: mean over seeds with 95% "
        "bootstrap CI; points: each seed)",
    )
    save_png(fig, path, dpi=_DPI)


def _curves_by_cell(rows: Sequence[Mapping[str, Any]]) -> dict[str, dict[str, dict[str, Curves]]]:
    """task -> algo -> entry -> the (steps, success) curve of every finished run."""
    identity = {r["run_id"]: (r["task"], r["algo"], r["entry"]) for r in rows if r["final"]}
    runs: dict[str, dict[str, dict[str, Curves]]] = {}
    for run_id, curve in run_curves(rows).items():
        task, algo, entry = identity[run_id]
        runs.setdefault(task, {}).setdefault(algo, {}).setdefault(entry, []).append(curve)
    return runs


def _seed_distances(
    rows: Sequence[Mapping[str, Any]],
) -> dict[str, dict[tuple[str, str], list[float]]]:
    """task -> (algo, entry) -> every run's final distance, by seed."""
    out: dict[str, dict[tuple[str, str], list[float]]] = {}
    for r in sorted((r for r in rows if r["final"]), key=lambda r: (r["seed"], r["run_id"])):
        by_entry = out.setdefault(r["task"], {})
        by_entry.setdefault((r["algo"], r["entry"]), []).append(float(r["final_distance"]))
    return out


def render_plots(
    rows: Sequence[Mapping[str, Any]],
    summary: Sequence[Mapping[str, Any]],
    overall: Sequence[Mapping[str, Any]],
    plots_dir: Path,
    reps: int,
    seed: int,
) -> dict[str, list[tuple[str, Path]]]:
    """Write every plot of the rows' tasks into ``plots_dir``, remove the plot files of tasks
    no longer in the rows, and return (caption, file) of each plot, by task (the across-task
    figures under :data:`~planshape.results.page.ACROSS`, with more than one task)."""
    import matplotlib

    plots_dir.mkdir(parents=True, exist_ok=True)
    runs = _curves_by_cell(rows)
    seeds_of = _seed_distances(rows)
    tasks = by_task_and_algo(summary)
    written: dict[str, list[tuple[str, Path]]] = {}
    with matplotlib.rc_context():
        matplotlib.rcdefaults()
        matplotlib.rcParams.update(STYLE)
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
    _remove_stale(plots_dir, written)
    return written


def _remove_stale(plots_dir: Path, written: Mapping[str, list[tuple[str, Path]]]) -> None:
    """Remove the plot files in ``plots_dir`` that this rendering did not write."""
    pngs = {path for task_plots in written.values() for _, path in task_plots}
    for stale in sorted(plots_dir.glob("*.png")):
        if stale.name.startswith(PLOT_PREFIXES) and stale not in pngs:
            stale.unlink()


def _across_task_figures(
    rows: Sequence[Mapping[str, Any]],
    overall: Sequence[Mapping[str, Any]],
    plots_dir: Path,
    seed: int,
) -> list[tuple[str, Path]]:
    """rliable's aggregate figures (:mod:`planshape.results.figures`), pooled over tasks."""
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
