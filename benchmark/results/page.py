"""The page model: a leaderboard page as data, from which Markdown and HTML are both written.

A :class:`Page` is a title and a flat sequence of blocks — :class:`Heading`,
:class:`Paragraph`, :class:`Bullets`, :class:`~planshape.results.tables.Table` and
:class:`Figure` — in reading order. :func:`build_page` makes the leaderboard's page from the
scored cells; :mod:`planshape.results.render` writes any page as ``LEADERBOARD.md`` and
``index.html``, so the two files cannot say different things. Text in paragraphs and bullets
may hold ``**bold**``; a block with ``only`` set appears in that medium alone (the HTML page's
note on sorting its tables; the Markdown page's table of hyperparameters).

Example:
    >>> page = Page("results", (Heading(2, "Setup"), Bullets(("one", "two"))))
    >>> [block.kind for block in page.blocks]
    ['heading', 'bullets']
    >>> page.blocks_for("html") == page.blocks
    True
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, ClassVar, Literal

from planshape.results import tables
from planshape.results.outcome import tally
from planshape.results.tables import Table
from planshape.results.verdict import budget_checks

__all__ = [
    "ACROSS",
    "HOW_TO_READ",
    "Block",
    "Bullets",
    "Figure",
    "Heading",
    "Page",
    "Paragraph",
    "build_page",
]

Medium = Literal["markdown", "html"]
#: caption and file of each figure, by task; :data:`ACROSS` holds the across-task figures
Figures = Mapping[str, Sequence[tuple[str, Path]]]
#: the key of the across-task figures among the figures of each task
ACROSS = ""


@dataclass(frozen=True, kw_only=True)
class _Block:
    #: the one medium this block appears in (None: both)
    only: Medium | None = None


@dataclass(frozen=True)
class Heading(_Block):
    """A section heading (level 2 or 3; the page's title is level 1); ``anchor`` is its HTML
    id."""

    kind: ClassVar[str] = "heading"
    level: int
    text: str
    anchor: str | None = None


@dataclass(frozen=True)
class Paragraph(_Block):
    """A paragraph of text (``**bold**`` allowed)."""

    kind: ClassVar[str] = "paragraph"
    text: str


@dataclass(frozen=True)
class Bullets(_Block):
    """A bulleted list (``**bold**`` allowed in items)."""

    kind: ClassVar[str] = "bullets"
    items: tuple[str, ...]


@dataclass(frozen=True)
class Figure(_Block):
    """An image: its caption and its file, relative to the page's folder."""

    kind: ClassVar[str] = "figure"
    caption: str
    src: str


Block = Heading | Paragraph | Bullets | Table | Figure


@dataclass(frozen=True)
class Page:
    """A page: its title and its blocks in reading order."""

    title: str
    blocks: tuple[Block, ...]

    def blocks_for(self, medium: Medium) -> tuple[Block, ...]:
        """The blocks shown in ``medium``."""
        return tuple(b for b in self.blocks if b.only in (None, medium))


HOW_TO_READ = (
    "**IQM**: interquartile mean over seeds (the mean of the middle 50% of runs; rliable). "
    "**[95% CI]**: percentile interval of the stratified bootstrap ({reps} resamples of the "
    "seeds, fixed seed). With fewer than 5 seeds in a cell no interval is shown, only "
    "marked (n=2: no CI): a percentile bootstrap of 2-4 seeds returns [min, max] or a "
    "zero-width interval, which says nothing about how much the seeds tell.",
    "**Success** and **final distance** are the task's own metrics at the end of training, over "
    "deterministic evaluation episodes; never the shaped return. Success is the task's flag at "
    "the episode's end, except in cells whose budget check says it counts the flag at **any "
    "step** (MetaWorld's own protocol: set at some step of the episode); where runs recorded "
    "both, the other count has its own column.",
    "**Norm. success / distance**: (entry − sparse) / (dense − sparse) of the mean over seeds: "
    "0 = as good as the sparse reward, 1 = as good as the hand-crafted dense reward, above 1 "
    "better; n/a where dense is no better than sparse (the scale would invert).",
    "**P(improve over sparse)**: probability that a run of the entry ends with a higher success "
    "rate than a run of the sparse reward (Mann-Whitney; ties count half; 0.5 = no difference).",
    "**Curve area**: area under success rate over training steps divided by the budget (1 = "
    "solved from the start); it rewards learning early.",
    "**Invariance**: whether the invariance check (exact value iteration on toy MDPs) found the "
    "optimal policy preserved or violated, was not run, or does not apply (no potential).",
    "**Budget check**: what a task's cell can decide. *decides*: every entry has 5 seeds or "
    "more, and dense reaches 0.8 mean success while sparse does not (or dense fails and a "
    "shaped entry solves the task, as on maze-reach); *separates little*: sparse reaches 0.8 "
    "too; *no verdict*: fewer than 5 seeds, no dense or no sparse entry, or no entry reaches "
    "0.8, so the "
    "budget cannot show whether shaping helps.",
    "**Shaping outcome**: whether a planning-derived potential (any shaped entry but the "
    "control `goal-distance`) reaches dense's mean final success at equal budget (*at least "
    "dense*), or, where none does, has the larger curve area (*faster*: it learns faster and "
    "ends lower), or neither (*below dense*); **P(entry > dense)** is the probability that a "
    "run of that entry ends with a higher success rate than a dense run (ties count half), "
    "with its interval: how much the seeds say about the difference. Only a cell whose budget "
    "check *decides* can show whether shaping helps.",
)


def _setup(header: Mapping[str, Any], info: Mapping[str, Any], reps: int) -> list[Block]:
    return [
        Heading(2, "Setup"),
        tables.setup_table(header, info),
        Paragraph("**Packages**: " + tables.packages_text(info)),
        Heading(3, "Budgets (environment steps)"),
        tables.budget_table(info),
        Heading(3, "Caveats"),
        Bullets(tuple(tables.caveats(header, info)) or ("none",)),
        Heading(3, "How to read the tables"),
        Bullets(tuple(text.replace("{reps}", str(reps)) for text in HOW_TO_READ)),
        Paragraph("Click a column heading to sort a table.", only="html"),
    ]


def _figures(figures: Sequence[tuple[str, Path]], out_dir: Path) -> list[Block]:
    return [Figure(caption, path.relative_to(out_dir).as_posix()) for caption, path in figures]


def _across_tasks(
    overall: Sequence[Mapping[str, Any]], figures: Figures, out_dir: Path
) -> list[Block]:
    blocks: list[Block] = [
        Heading(2, "Across tasks"),
        Paragraph(
            "IQM over every run's task-normalized score, pooled over the tasks each entry ran on "
            "(stratified bootstrap over seeds within tasks)."
        ),
    ]
    for algo in sorted({r["algo"] for r in overall}):
        blocks += [
            Heading(3, algo),
            tables.aggregate_table(r for r in overall if r["algo"] == algo),
        ]
    return blocks + _figures(figures.get(ACROSS, []), out_dir)


def _verdicts(checks: Sequence[Mapping[str, Any]]) -> list[Block]:
    """Every cell's budget check and shaping outcome in one table, under the count of what the
    deciding cells show."""
    if not checks:
        return []
    return [Heading(2, "Verdicts"), Paragraph(tally(checks)), tables.verdict_table(checks)]


def _measure_note(ranked: Sequence[Mapping[str, Any]]) -> str:
    """Where the cell counts success at any step (:mod:`planshape.results.measure`), the
    sentence that says so; the end of the episode is the default and goes unsaid."""
    if all(tables.missing(r.get("success_end_mean")) for r in ranked):
        return ""
    return (
        ". Success here counts an episode whose success flag is set at any step (MetaWorld's "
        "protocol); the end-of-episode rate is in its own column"
    )


def _task(
    task: str,
    by_algo: Mapping[str, Sequence[Mapping[str, Any]]],
    checks: Mapping[tuple[str, str], Mapping[str, Any]],
    figures: Sequence[tuple[str, Path]],
    out_dir: Path,
) -> list[Block]:
    blocks: list[Block] = [Heading(2, task, anchor=tables.slug(task))]
    for algo, ranked in by_algo.items():
        check = checks[task, algo]
        blocks += [
            Heading(3, f"{algo} — budget {ranked[0]['budget']:,} steps"),
            Paragraph(f"**Budget check**: {check['text']}{_measure_note(ranked)}"),
            Paragraph(f"**Shaping outcome**: {check['outcome_text']}"),
            tables.task_table(ranked),
        ]
    return blocks + _figures(figures, out_dir)


def build_page(
    summary: Sequence[Mapping[str, Any]],
    overall: Sequence[Mapping[str, Any]],
    info: Mapping[str, Any],
    header: Mapping[str, Any],
    figures: Figures,
    out_dir: Path,
    reps: int,
) -> Page:
    """The leaderboard page: setup, caveats and how to read it; every cell's verdict; the
    across-task tables (with more than one task); per task, a ranked table per algorithm under
    its budget check and shaping outcome, and its figures (plots and policy videos, in
    ``figures`` by task); the hyperparameters."""
    checks = budget_checks(summary)
    by_cell = {(c["task"], c["algo"]): c for c in checks}
    blocks = _setup(header, info, reps) + _verdicts(checks)
    by_task = tables.by_task_and_algo(summary)
    if len(by_task) > 1 and overall:
        blocks += _across_tasks(overall, figures, out_dir)
    for task, by_algo in by_task.items():
        blocks += _task(task, by_algo, by_cell, figures.get(task, []), out_dir)
    if info["hyperparameters"]:
        blocks += [
            Heading(2, "Hyperparameters", only="markdown"),
            replace(tables.hyperparameter_table(info), only="markdown"),
        ]
    return Page("planshape leaderboard", tuple(blocks))
