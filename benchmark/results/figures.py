"""Aggregate figures of a leaderboard, in the style of rliable: interval estimates, performance
profiles and probabilities of improvement, from the stored rows.

Every figure pools each entry's runs over the tasks it ran on, as task-normalized scores
((entry − sparse) / (dense − sparse): 0 = sparse's level, 1 = dense's; tasks where the two tie
are left out), with 95% stratified-bootstrap intervals. Colours are colour-blind safe (the
Okabe-Ito palette), one per potential family, the same in every figure; line and marker styles
tell the models apart (``single`` dotted, ``multi`` dashed, ``grid`` solid, ``grid-diagonal``
dash-dotted).

Example:
    >>> style("plan-based/grid")["linestyle"], style("plan-based/multi")["linestyle"]
    ('-', '--')
    >>> style("plan-based/grid")["color"] == style("plan-based/single")["color"]
    True
"""

from __future__ import annotations

import io
import textwrap
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from planshape.harness.store import write_atomic
from planshape.results.cells import REFERENCE_ENTRIES

__all__ = [
    "FAMILY_COLORS",
    "plot_interval_estimates",
    "plot_performance_profiles",
    "plot_probability_of_improvement",
    "save_png",
    "style",
    "suptitle",
]

#: Okabe & Ito's colour-blind-safe palette, one colour per potential family
FAMILY_COLORS: dict[str, str] = {
    "sparse": "#000000",
    "dense": "#999999",
    "plan-based": "#0072B2",
    "time-varying": "#56B4E9",
    "distance-varying": "#009E73",
    "plan-distance": "#D55E00",
    "plan-path": "#CC79A7",
    "goal-distance": "#E69F00",
    "h-star": "#F0E442",
    "h-star-geodesic": "#7F5F00",
}
_OTHER_COLORS = ("#332288", "#117733", "#882255", "#44AA99", "#AA4499", "#DDCC77")
_LINESTYLES = {"single": ":", "multi": "--", "grid": "-", "grid-diagonal": "-.", "stages": "-"}
_MARKERS = {"single": "^", "multi": "s", "grid": "o", "grid-diagonal": "D", "stages": "o"}
_DPI = 110
#: characters of a figure title per inch of figure width (DejaVu Sans at matplotlib's "large",
#: 12 pt, averages about 0.09 in a character; a little less, so that a line never overflows)
_TITLE_CHARS_PER_INCH = 9.5


def style(entry: str) -> dict[str, Any]:
    """Colour (by potential family), line style and marker (by model) of an entry."""
    family, _, model = entry.partition("/")
    if family in FAMILY_COLORS:
        color = FAMILY_COLORS[family]
    else:  # a submission: a stable colour of its own
        color = _OTHER_COLORS[sum(map(ord, family)) % len(_OTHER_COLORS)]
    return {
        "color": color,
        "linestyle": _LINESTYLES.get(model, "-"),
        "marker": _MARKERS.get(model, "o"),
    }


def save_png(fig: Any, path: Path, dpi: int = _DPI) -> Path:
    """Write ``fig`` as a PNG atomically; no "Software" or date in it, so the bytes depend on
    the data only (re-rendering unchanged results leaves the file as it was)."""
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=dpi, metadata={"Software": None})
    return write_atomic(path, buffer.getvalue())


def suptitle(fig: Any, text: str) -> Any:
    """Give ``fig`` the title ``text``, wrapped to the figure's width (each of its own lines
    separately), so that no title runs past the edges of the saved image; returns the title's
    matplotlib ``Text``. Lines break between words; a word too long for a line of its own (a
    long task id) also breaks at its hyphens.

    Example:
        >>> from matplotlib.figure import Figure
        >>> fig = Figure(figsize=(3.5, 2.0))
        >>> title = suptitle(fig, "planshape/MetaWorld-reach-v4: final distance to the goal")
        >>> print(title.get_text())
        planshape/MetaWorld-reach-v4:
        final distance to the goal
    """
    width = max(int(fig.get_figwidth() * _TITLE_CHARS_PER_INCH), 20)
    lines: list[str] = []
    for line in text.split("\n"):
        for wrapped in textwrap.wrap(
            line, width, break_long_words=False, break_on_hyphens=False
        ) or [""]:
            fits = len(wrapped) <= width
            lines.extend(
                [wrapped] if fits else textwrap.wrap(wrapped, width, break_long_words=False)
            )
    return fig.suptitle("\n".join(lines))


def _ranked(rows: Sequence[Mapping[str, Any]], column: str) -> list[Mapping[str, Any]]:
    def key(r: Mapping[str, Any]) -> tuple[int, float, str]:
        value = r.get(column)
        missing = value is None or not np.isfinite(value)
        return (1 if missing else 0, 0.0 if missing else -float(value), r["entry"])

    return sorted(rows, key=key)


def _finite(row: Mapping[str, Any], column: str) -> bool:
    value = row.get(column)
    return value is not None and bool(np.isfinite(value))


def plot_interval_estimates(overall: Sequence[Mapping[str, Any]], path: Path) -> Path | None:
    """Per algorithm: IQM, mean and optimality gap of the normalized success, with 95% CIs."""
    from matplotlib.figure import Figure

    algos = sorted({r["algo"] for r in overall})
    if not algos:
        return None
    metrics = (
        ("normalized_success_iqm", "IQM"),
        ("normalized_success_mean", "Mean"),
        ("normalized_success_gap", "Optimality gap (below dense)"),
    )
    shown = [r for r in overall if _finite(r, "normalized_success_iqm")]
    algos = sorted({r["algo"] for r in shown})
    if not algos:
        return None
    most = max(sum(r["algo"] == a for r in shown) for a in algos)
    fig = Figure(figsize=(10.5, 0.8 + 0.28 * most * len(algos)), layout="constrained")
    grid = fig.subplots(len(algos), len(metrics), squeeze=False, sharex="col")
    for row_axes, algo in zip(grid, algos, strict=True):
        rows = _ranked(
            [r for r in overall if r["algo"] == algo and _finite(r, "normalized_success_iqm")],
            "normalized_success_iqm",
        )
        y = np.arange(len(rows))[::-1]
        for ax, (column, title) in zip(row_axes, metrics, strict=True):
            for yi, r in zip(y, rows, strict=True):
                value, low, high = (r.get(column + s, np.nan) for s in ("", "_low", "_high"))
                look = style(r["entry"])
                if np.isfinite(low) and np.isfinite(high):
                    ax.hlines(yi, low, high, color=look["color"], linewidth=5, alpha=0.45)
                if np.isfinite(value):
                    ax.plot([value], [yi], marker="|", color=look["color"], markersize=12)
            ax.set_yticks(y, [r["entry"] for r in rows] if ax is row_axes[0] else [])
            ax.axvline(0.0 if column.endswith("_gap") else 1.0, color="#bbbbbb", linewidth=0.8)
            ax.set_title(f"{algo}: {title}", fontsize=9)
            ax.tick_params(labelsize=7)
    for ax in grid[-1]:
        ax.set_xlabel("normalized success (0 = sparse, 1 = dense)", fontsize=8)
    suptitle(fig, "Aggregate interval estimates over tasks (95% stratified bootstrap CIs)")
    return save_png(fig, path)


def plot_performance_profiles(
    scores: Mapping[tuple[str, str], Mapping[str, np.ndarray]],
    path: Path,
    reps: int = 500,
    seed: int = 0,
) -> Path | None:
    """Per algorithm: the fraction of runs whose normalized success exceeds τ, with 95%
    stratified-bootstrap bands (rliable's performance profiles)."""
    from matplotlib.figure import Figure

    algos = sorted({algo for algo, _ in scores})
    if not algos:
        return None
    taus = np.linspace(-0.25, 1.5, 71)
    fig = Figure(figsize=(4.8 * len(algos), 4.0), layout="constrained")
    axes = fig.subplots(1, len(algos), squeeze=False, sharey=True)[0]
    rng = np.random.default_rng(seed)
    for ax, algo in zip(axes, algos, strict=True):
        for (a, entry), by_task in sorted(scores.items()):
            if a != algo:
                continue
            pooled = np.concatenate([np.asarray(v, float) for v in by_task.values()])
            profile = (pooled[:, None] > taus[None, :]).mean(axis=0)
            boot = np.empty((reps, taus.size))
            for i in range(reps):
                drawn = np.concatenate(
                    [rng.choice(np.asarray(v, float), size=len(v)) for v in by_task.values()]
                )
                boot[i] = (drawn[:, None] > taus[None, :]).mean(axis=0)
            low, high = np.percentile(boot, [2.5, 97.5], axis=0)
            look = style(entry)
            ax.plot(taus, profile, color=look["color"], linestyle=look["linestyle"], label=entry)
            ax.fill_between(taus, low, high, color=look["color"], alpha=0.12, linewidth=0)
        ax.set_title(algo)
        ax.set_xlabel("normalized success τ (0 = sparse, 1 = dense)")
        ax.axvline(1.0, color="#bbbbbb", linewidth=0.8)
    axes[0].set_ylabel("fraction of runs with score > τ")
    handles, labels = axes[0].get_legend_handles_labels()
    for ax in axes[1:]:
        for h, label in zip(*ax.get_legend_handles_labels(), strict=True):
            if label not in labels:
                handles.append(h)
                labels.append(label)
    fig.legend(handles, labels, loc="outside right center", fontsize=7)
    suptitle(fig, "Performance profiles over tasks (95% stratified bootstrap bands)")
    return save_png(fig, path)


def plot_probability_of_improvement(
    overall: Sequence[Mapping[str, Any]], path: Path
) -> Path | None:
    """Per algorithm: P(a run of the entry ends with higher success than a run of sparse), and
    of dense, with 95% CIs; 0.5 = no difference."""
    from matplotlib.figure import Figure

    rows = [r for r in overall if r["entry"] not in REFERENCE_ENTRIES]
    algos = sorted({r["algo"] for r in rows})
    if not algos:
        return None
    most = max(sum(r["algo"] == a for r in rows) for a in algos)
    fig = Figure(figsize=(5.2 * len(algos), 1.0 + 0.3 * most), layout="constrained")
    axes = fig.subplots(1, len(algos), squeeze=False)[0]
    for ax, algo in zip(axes, algos, strict=True):
        ranked = _ranked([r for r in rows if r["algo"] == algo], "p_improve_dense")
        y = np.arange(len(ranked))[::-1]
        for column, offset, fill, label in (
            ("p_improve", 0.15, "white", "over sparse"),
            ("p_improve_dense", -0.15, None, "over dense"),
        ):
            for yi, r in zip(y, ranked, strict=True):
                value, low, high = (r.get(column + s, np.nan) for s in ("", "_low", "_high"))
                color = style(r["entry"])["color"]
                if np.isfinite(low) and np.isfinite(high):
                    ax.hlines(yi + offset, low, high, color=color, linewidth=2)
                if np.isfinite(value):
                    ax.plot(
                        [value],
                        [yi + offset],
                        marker="o",
                        color=color,
                        markerfacecolor=fill or color,
                        label=label if yi == y[0] else None,
                    )
        ax.axvline(0.5, color="#bbbbbb", linewidth=0.8)
        ax.set_xlim(-0.02, 1.02)
        ax.set_yticks(y, [r["entry"] for r in ranked], fontsize=7)
        ax.set_title(f"{algo}: P(improvement)  ○ over sparse  ● over dense", fontsize=9)
        ax.set_xlabel("probability that a run of the entry ends with higher success")
    suptitle(fig, "Probability of improvement, pooled over tasks (95% stratified bootstrap CIs)")
    return save_png(fig, path)
