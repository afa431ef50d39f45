"""Profiles that run the same cells: each entry's numbers side by side across them.

Some profiles are variants of one experiment: ``metaworld-s10`` runs the ``metaworld``
profile's cells with φ scaled by 10, ``metaworld-progress`` the same with plan progress
observed. Which of the two changes moved an entry is read by putting the entry's mean success
under each variant side by side, at the same task, algorithm and budget. This module finds such
profiles among those rendered under a results root (:mod:`planshape.results.evidence`) and
builds that table from their summaries; nothing is recomputed.

A *cell* here is (task, algorithm, budget): two profiles share it when both leaderboards have
it. Profiles are grouped into *families*, the connected groups of profiles that share a cell;
archived profiles are left out (they ran other task versions or protocols). A family's table
has a row for each entry of a shared cell whose runs differ between two or more of its
profiles, and the cell's sparse and dense rows for reference; one column per profile: the
entry's mean success as that profile counts it, with the mean at the episode's end in brackets
where the profile counts success at any step, and the number of seeds where it is below five.
Entries whose runs are the same wherever they are stored (a profile that re-executed another's
cells repeats every number) have no row, and a family with no such entry no table.

Example:
    >>> from functools import partial
    >>> from planshape.results.evidence import ProfileEvidence
    >>> Profile = partial(ProfileEvidence, folder=".", description="", n_runs=10)
    >>> def row(entry, success, end, seeds=5):
    ...     return {"task": "planshape/MetaWorld-reach-v4", "algo": "SBX-SAC", "entry": entry,
    ...             "budget": 200000, "seeds": list(range(seeds)), "n_seeds": seeds,
    ...             "success_mean": success, "success_end_mean": end}
    >>> check = {"task": "planshape/MetaWorld-reach-v4", "algo": "SBX-SAC", "budget": 200000}
    >>> base = Profile(name="metaworld", state="complete", checks=(check,),
    ...                rows=(row("dense", 0.94, 0.56), row("plan-distance/stages", 0.58, 0.54)))
    >>> scaled = Profile(name="metaworld-s10", state="partial: ...", checks=(check,),
    ...                  rows=(row("dense", 0.94, 0.56), row("plan-distance/stages", 1.0, 1.0, 2)))
    >>> [[p.name for p in f] for f in families([base, scaled])]
    [['metaworld', 'metaworld-s10']]
    >>> table = variants_table(families([base, scaled])[0])
    >>> for r in table.rows:
    ...     print([c.text for c in r][2:])
    ['dense', '0.94 (0.56)', '0.94 (0.56)']
    ['plan-distance/stages', '0.58 (0.54)', '1.00 (1.00), 2 seeds']
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Mapping, Sequence
from typing import TYPE_CHECKING, Any

from planshape.results.cells import DENSE, SPARSE
from planshape.results.page import Heading, Paragraph
from planshape.results.tables import Cell, Table, entry_order, missing, short_task

if TYPE_CHECKING:
    from planshape.results.evidence import ProfileEvidence

__all__ = ["families", "variants_blocks", "variants_table"]

#: seeds per entry below which a number shows its seed count
_FULL_SEEDS = 5
#: a column's text where the profile has no run of the entry in that cell
_ABSENT = "—"

CellKey = tuple[str, str, int]


def _cells(profile: ProfileEvidence) -> set[CellKey]:
    return {(str(c["task"]), str(c["algo"]), int(c["budget"])) for c in profile.checks}


def families(profiles: Sequence[ProfileEvidence]) -> list[tuple[ProfileEvidence, ...]]:
    """The groups of two or more non-archived profiles connected by shared cells, each in the
    order ``profiles`` gives, ordered by their first member."""
    live = [p for p in profiles if p.state != "archived"]
    groups: list[list[ProfileEvidence]] = []
    for profile in live:
        joined = [g for g in groups if any(_cells(profile) & _cells(q) for q in g)]
        merged = [q for g in joined for q in g] + [profile]
        groups = [g for g in groups if g not in joined] + [merged]
    order = {id(p): i for i, p in enumerate(live)}
    return sorted(
        (tuple(sorted(g, key=lambda p: order[id(p)])) for g in groups if len(g) > 1),
        key=lambda g: order[id(g[0])],
    )


def _shared_cells(family: Sequence[ProfileEvidence]) -> list[CellKey]:
    counts = Counter(cell for profile in family for cell in _cells(profile))
    return sorted(cell for cell, n in counts.items() if n > 1)


def _number_text(row: Mapping[str, Any] | None) -> Cell:
    if row is None or missing(row.get("success_mean")):
        return Cell(_ABSENT)
    success = float(row["success_mean"])
    text = f"{success:.2f}"
    if not missing(row.get("success_end_mean")):
        text += f" ({float(row['success_end_mean']):.2f})"
    seeds = int(row.get("n_seeds", _FULL_SEEDS))
    if seeds < _FULL_SEEDS:
        text += f", {seeds} seed{'s' if seeds != 1 else ''}"
    return Cell(text, success)


def _row_of(profile: ProfileEvidence, cell: CellKey, entry: str) -> Mapping[str, Any] | None:
    task, algo, budget = cell
    row = profile.row(task, algo, entry)
    return row if row is not None and int(row.get("budget", budget)) == budget else None


def _runs_fingerprint(row: Mapping[str, Any] | None) -> tuple[Any, ...] | None:
    """What tells two summaries' rows of an entry apart when their runs trained differently:
    the seeds and every measured mean. Runs are deterministic, so the same runs, or a
    re-execution of them, repeat these to the last digit; runs with other settings do not
    (their final distances alone differ). Wall time is left out: a re-execution repeats
    every number but that one."""
    if row is None:
        return None
    keys = (
        "seeds",
        "success_mean",
        "success_end_mean",
        "curve_area_mean",
        "distance_mean",
        "sparse_return_mean",
    )
    return tuple(str(row.get(k)) for k in keys)


def _differs(family: Sequence[ProfileEvidence], cell: CellKey, entry: str) -> bool:
    """Whether two or more profiles hold runs of ``entry`` in ``cell`` and not all the same."""
    prints = {_runs_fingerprint(_row_of(p, cell, entry)) for p in family} - {None}
    return len(prints) > 1


def _table_rows(family: Sequence[ProfileEvidence]) -> list[tuple[Cell, ...]]:
    rows = []
    for cell in _shared_cells(family):
        task, algo, _ = cell
        entries = entry_order(
            r["entry"] for p in family for r in p.rows if (r["task"], r["algo"]) == (task, algo)
        )
        compared = [e for e in entries if _differs(family, cell, e)]
        if not compared:
            continue
        references = [e for e in (SPARSE, DENSE) if e in entries and e not in compared]
        for entry in entry_order([*references, *compared]):
            numbers = [_number_text(_row_of(p, cell, entry)) for p in family]
            rows.append((Cell(short_task(task)), Cell(algo), Cell(entry, code=True), *numbers))
    return rows


def variants_table(family: Sequence[ProfileEvidence]) -> Table | None:
    """One row per (task, algorithm, entry) whose runs differ between the family's profiles in
    a cell they share, with the cell's sparse and dense rows beside them; one column per
    profile (see the module's docstring). ``None``: no entry's runs differ."""
    rows = _table_rows(family)
    if not rows:
        return None
    headings = ("Task", "Algorithm", "Entry", *(p.name for p in family))
    return Table(headings, tuple(rows), sortable=True)


def _members_text(family: Iterable[ProfileEvidence]) -> str:
    return ", ".join(f"`{p.name}`" for p in family)


def variants_blocks(profiles: Sequence[ProfileEvidence]) -> list[Any]:
    """The evidence page's section on profiles that run the same cells (none: no section)."""
    groups = families(profiles)
    intro = (
        "Profiles that share cells (the same task, algorithm and budget) are variants of one "
        "experiment. Here every entry whose runs differ between such profiles stands under "
        "each of them, with its cell's sparse and dense for reference: the mean success as "
        "its profile counts it, the mean at the episode's end in brackets where success counts "
        "at any step, and the seeds where fewer than five are stored; — : the profile has no "
        "run of the entry there. Entries whose runs are the same wherever they are stored "
        "(a profile that re-executed another's cells repeats every number) are left out."
    )
    blocks: list[Any] = [
        Heading(2, "Profiles that run the same cells", anchor="variants"),
        Paragraph(intro),
    ]
    for family in groups:
        table = variants_table(family)
        if table is not None:
            blocks += [Paragraph(f"{_members_text(family)}:"), table]
    return blocks if len(blocks) > 2 else []
