"""The evidence index: every profile's verdicts on one page, read from the rendered summaries.

Each profile's leaderboard says, cell by cell, what its budget can decide and what shaping did
there (:mod:`planshape.results.verdict`, :mod:`planshape.results.outcome`). A question such as
*does a planning-derived potential reach the dense reward?* is asked across profiles, so this
module gathers those verdicts from every ``summary.json`` under a results root (the root's own,
the default profile's, and one folder down, every other profile's) into one page:

* a table of the profiles: whether each is complete, partial or archived, its runs, and how many
  of its cells decide and what those show;
* per profile, the tally sentence of its own page and one row per cell with the mean success of
  the entry that gives the outcome, of dense and of sparse, as the profile's leaderboard counts
  success;
* for profiles that run the same cells (variants of one experiment, such as ``metaworld`` and
  ``metaworld-s10``), each entry's mean success under each of them side by side
  (:mod:`planshape.results.variants`).

Nothing is recomputed: the numbers are the summaries', so the page agrees with every profile's
``LEADERBOARD.md`` by construction. ``planshape evidence leaderboard --to
leaderboard/EVIDENCE.md`` writes the committed page; a test renders it again from the committed
summaries and fails while it is stale.

Example:
    >>> import json, tempfile
    >>> root = Path(tempfile.mkdtemp())
    >>> summary = {
    ...     "header": {"profile": "smoke", "description": "a pipeline check", "caveats": []},
    ...     "provenance": {"n_runs": 10},
    ...     "per_task": [
    ...         {"task": "planshape/Reach-v1", "algo": "PPO", "entry": entry, "success_mean": s}
    ...         for entry, s in (("dense", 1.0), ("sparse", 0.0), ("plan-based/grid", 1.0))
    ...     ],
    ...     "budget_checks": [{
    ...         "task": "planshape/Reach-v1", "algo": "PPO", "budget": 4096, "status": "decides",
    ...         "outcome": "at-least-dense", "outcome_entry": "plan-based/grid",
    ...         "outcome_p_improve_dense": 0.5, "outcome_p_improve_dense_low": 0.5,
    ...         "outcome_p_improve_dense_high": 0.5}],
    ... }
    >>> _ = (root / "summary.json").write_text(json.dumps(summary))
    >>> [(p.name, p.state, len(p.checks)) for p in read_profiles(root)]
    [('smoke', 'complete', 1)]
    >>> print(evidence_markdown(root).splitlines()[0])
    # planshape evidence
"""

from __future__ import annotations

import argparse
import json
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from planshape.commands import Handler, subcommand
from planshape.errors import BadInputError
from planshape.results.outcome import tally
from planshape.results.page import Heading, Page, Paragraph
from planshape.results.tables import Cell, Table, evidence_table, missing
from planshape.results.variants import variants_blocks

__all__ = ["ProfileEvidence", "evidence_markdown", "evidence_page", "read_profiles"]

SUMMARY = "summary.json"
#: the caveat a profile's header opens with while some of its runs are not stored yet
_PARTIAL = "partial: "


@dataclass(frozen=True)
class ProfileEvidence:
    """One profile's verdicts as its rendered summary states them.

    Attributes:
        name: the profile's name (its header's).
        folder: its results folder, relative to the results root (``.`` for the default).
        description: its header's description.
        state: ``archived`` (:attr:`planshape.harness.profiles.Profile.archived`), the header's
            partial caveat (``partial: 105 of the profile's 155 runs are stored; ...``), or
            ``complete``.
        n_runs: the runs its leaderboard was rendered from.
        checks: its cells' budget checks and shaping outcomes (``budget_checks``).
        rows: its summary rows, one per (task, algorithm, entry) (``per_task``).
    """

    name: str
    folder: str
    description: str
    state: str
    n_runs: int
    checks: tuple[Mapping[str, Any], ...]
    rows: tuple[Mapping[str, Any], ...]

    def row(self, task: str, algo: str, entry: str | None) -> Mapping[str, Any] | None:
        """The summary row of ``entry`` in the (``task``, ``algo``) cell, or ``None``."""
        return next(
            (r for r in self.rows if (r["task"], r["algo"], r["entry"]) == (task, algo, entry)),
            None,
        )

    def success(self, task: str, algo: str, entry: str | None) -> float | None:
        """The mean success of ``entry`` in the (``task``, ``algo``) cell, or ``None``."""
        row = self.row(task, algo, entry)
        return None if row is None or missing(row["success_mean"]) else float(row["success_mean"])

    def counts(self) -> dict[str, int]:
        """Its cells: ``cells``, ``decides``, and among the deciding cells each outcome."""
        deciding = [c for c in self.checks if c["status"] == "decides"]
        counts = {"cells": len(self.checks), "decides": len(deciding)}
        for outcome in ("at-least-dense", "faster", "below-dense"):
            counts[outcome] = sum(c["outcome"] == outcome for c in deciding)
        return counts


def _summary_files(root: Path) -> list[Path]:
    files = [root / SUMMARY] if (root / SUMMARY).is_file() else []
    return files + sorted(p for p in root.glob(f"*/{SUMMARY}") if p.is_file())


def _read(path: Path, root: Path) -> ProfileEvidence:
    try:
        summary = json.loads(path.read_text(encoding="utf-8"))
        header = summary["header"]
        name = str(header["profile"])
        caveats = [str(c) for c in header.get("caveats", ())]
        checks = tuple(summary["budget_checks"])
        rows = tuple(summary["per_task"])
        n_runs = int(summary.get("provenance", {}).get("n_runs", 0))
    except (OSError, ValueError, KeyError, TypeError) as err:
        raise BadInputError(
            f"{path}: not a leaderboard summary ({type(err).__name__}: {err}); render it again "
            f"with planshape leaderboard --out {path.parent}"
        ) from err
    partial = next((c[len(_PARTIAL) :] for c in caveats if c.startswith(_PARTIAL)), None)
    return ProfileEvidence(
        name=name,
        folder=path.parent.relative_to(root).as_posix(),
        description=str(header.get("description", "")),
        state="archived" if _archived(name) else (f"partial: {partial}" if partial else "complete"),
        n_runs=n_runs,
        checks=checks,
        rows=rows,
    )


def _archived(name: str) -> bool:
    from planshape.harness.profiles import PROFILES

    return name in PROFILES and bool(PROFILES[name].archived)


def _unrendered(names: set[str]) -> list[str]:
    from planshape.harness.profiles import PROFILES

    return [name for name in PROFILES if name not in names]


def _order(name: str) -> tuple[int, str]:
    from planshape.harness.profiles import PROFILES

    names = list(PROFILES)
    return (names.index(name) if name in names else len(names), name)


def read_profiles(root: str | Path) -> list[ProfileEvidence]:
    """Every profile rendered under ``root`` (its ``summary.json`` and those one folder down),
    in the order of :data:`planshape.harness.profiles.PROFILES`.

    Raises:
        BadInputError: ``root`` holds no summary, or one that is not a leaderboard summary.
    """
    root = Path(root)
    files = _summary_files(root)
    if not files:
        raise BadInputError(
            f"{root}: no {SUMMARY} in it or one folder down; render a profile first with "
            f"planshape leaderboard --out {root}/<profile>"
        )
    return sorted((_read(path, root) for path in files), key=lambda p: _order(p.name))


def _profiles_table(profiles: Sequence[ProfileEvidence]) -> Table:
    def row(p: ProfileEvidence) -> tuple[Cell, ...]:
        n = p.counts()
        state = "complete" if p.state == "complete" else p.state.split(";")[0]
        return (
            Cell(p.name, code=True),
            Cell(state),
            Cell(f"{p.n_runs}", float(p.n_runs)),
            Cell(f"{n['cells']}", float(n["cells"])),
            Cell(f"{n['decides']}", float(n["decides"])),
            *(Cell(f"{n[o]}", float(n[o])) for o in ("at-least-dense", "faster", "below-dense")),
        )

    headings = (
        "Profile",
        "State",
        "Runs",
        "Cells",
        "Cells that decide",
        "At least dense",
        "Faster",
        "Below dense",
    )
    return Table(headings, tuple(row(p) for p in profiles))


def _measure(p: ProfileEvidence) -> str:
    any_step = any(not missing(r.get("success_end_mean")) for r in p.rows)
    return (
        "at any step of an episode (MetaWorld's protocol)" if any_step else "at the episode's end"
    )


def _profile_blocks(p: ProfileEvidence) -> list[Any]:
    page = "LEADERBOARD.md" if p.folder == "." else f"{p.folder}/LEADERBOARD.md"
    about = (
        f"{p.description[:1].upper()}{p.description[1:]}. State: {p.state}. {p.n_runs} runs; "
        f"success counted {_measure(p)}. "
        f"Every number and interval: [{page}]({page})."
    )
    cells = [
        {
            **c,
            "entry_success": p.success(c["task"], c["algo"], c["outcome_entry"]),
            "dense_success": p.success(c["task"], c["algo"], "dense"),
            "sparse_success": p.success(c["task"], c["algo"], "sparse"),
        }
        for c in p.checks
    ]
    return [
        Heading(2, p.name, anchor=p.name),
        Paragraph(about),
        Paragraph(tally(p.checks)),
        evidence_table(cells),
    ]


def evidence_page(profiles: Sequence[ProfileEvidence]) -> Page:
    """The page: how it was made, the table of profiles, each profile's cells, then the
    entries of profiles that run the same cells side by side."""
    intro = (
        "Every profile's verdicts, gathered from the rendered summaries by `planshape "
        "evidence`; "
        "nothing here is recomputed, so each number is its profile's leaderboard's. A cell is "
        "one task and algorithm. Its **budget check** says whether it can show that shaping "
        "helps (*decides*: every entry has 5 seeds or more, and dense reaches 0.8 mean success "
        "while sparse does not, or a shaped entry does where dense fails by design); its "
        "**shaping outcome** whether a planning-derived potential reaches dense's mean success "
        "at equal budget (*at least dense*), learns faster but ends lower (*faster*), or "
        "neither (*below dense*). The outcome columns count deciding cells only. **Entry** "
        "gives the outcome; its success, dense's and sparse's are means over seeds."
    )
    blocks: list[Any] = [Paragraph(intro), _profiles_table(profiles)]
    absent = _unrendered({p.name for p in profiles})
    if absent:
        names = ", ".join(f"`{name}`" for name in absent)
        blocks.append(Paragraph(f"Registered profiles with no rendered results here: {names}."))
    for p in profiles:
        blocks += _profile_blocks(p)
    blocks += variants_blocks(profiles)
    return Page("planshape evidence", tuple(blocks))


def evidence_markdown(root: str | Path) -> str:
    """The evidence page of every profile rendered under ``root``, as Markdown."""
    from planshape.results.render import markdown

    return markdown(evidence_page(read_profiles(root)))


@subcommand("evidence", "gather every profile's verdicts on one page from their summaries")
def _evidence(parser: argparse.ArgumentParser) -> Handler:
    parser.add_argument(
        "root",
        nargs="?",
        type=Path,
        default=Path("leaderboard"),
        help="results root: the default profile's folder, the others one level down "
        "(default: %(default)s)",
    )
    parser.add_argument(
        "--to", type=Path, default=None, help="write the page to FILE.md (default: print it)"
    )
    return _run_evidence


def _run_evidence(args: argparse.Namespace) -> int:
    if args.to is not None and args.to.suffix != ".md":
        raise BadInputError(f"--to {args.to}: name a Markdown file (FILE.md)")
    text = evidence_markdown(args.root)
    if args.to is None:
        print(text, end="")
        return 0
    from planshape.harness.store import write_atomic

    args.to.parent.mkdir(parents=True, exist_ok=True)
    write_atomic(args.to, text)
    print(f"wrote {args.to}")
    return 0
