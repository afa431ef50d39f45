"""The README's MetaWorld table says what the three MetaWorld profiles' rendered summaries say:
each task's dense and sparse success and, under each profile, the shaping outcome and the
planning-derived entry that gives it with that entry's mean success. The narratives behind it
live in ``leaderboard/METAWORLD.md``; this keeps the one table a reader sees first from
drifting away from the stored runs when an entry is adopted."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from planshape.results.evidence import ProfileEvidence, read_profiles

ROOT = Path(__file__).resolve().parents[2]
README = ROOT / "README.md"
HEADING = "### MetaWorld with SAC"
PROFILES = ("metaworld", "metaworld-s10", "metaworld-progress")
#: how the table words each :data:`planshape.results.outcome.Status`
LABELS = {"at-least-dense": "at least dense", "faster": "faster", "below-dense": "below dense"}
ALGO = "SBX-SAC"


def _table_rows() -> list[list[str]]:
    text = README.read_text(encoding="utf-8")
    assert HEADING in text, f"README.md has no {HEADING!r} section"
    section = text.split(HEADING, 1)[1].split("\n### ", 1)[0]
    lines = [line for line in section.splitlines() if line.startswith("| ")]
    assert lines and "`metaworld`" in lines[0], "the section's table has moved or lost its header"
    return [[c.strip() for c in line.strip("|").split("|")] for line in lines[1:]]


def _readme_name(task: str) -> str:
    """How the table names a task: its id without namespace, ``MetaWorld-`` or ``-v3``.

    >>> _readme_name("planshape/MetaWorld-drawer-close-v3")
    'drawer-close'
    """
    return task.replace("-v3", "").removeprefix("planshape/MetaWorld-")


def _row_name(row: list[str]) -> str:
    return row[0].split(" (")[0]


def _cell(profile: ProfileEvidence, task: str) -> str:
    check = next(c for c in profile.checks if c["task"] == task and c["algo"] == ALGO)
    entry = check["outcome_entry"]
    success = profile.success(task, ALGO, entry)
    return f"{LABELS[check['outcome']]}: `{entry}` {success:.2f}"


@pytest.fixture(scope="module")
def profiles() -> dict[str, ProfileEvidence]:
    found = {p.name: p for p in read_profiles(ROOT / "leaderboard")}
    return {name: found[name] for name in PROFILES}


def test_the_table_has_one_row_per_task_of_the_profile(profiles):
    tasks = {c["task"] for c in profiles["metaworld"].checks}
    assert {_readme_name(t) for t in tasks} == {_row_name(row) for row in _table_rows()}


@pytest.mark.parametrize("index", range(6))
def test_each_row_reads_as_the_summaries_do(profiles, index):
    row = _table_rows()[index]
    name, budget = re.fullmatch(r"(\S+) \(([\d,]+)\)", row[0]).groups()
    task = next(c["task"] for c in profiles["metaworld"].checks if _readme_name(c["task"]) == name)
    first = profiles["metaworld"]
    check = next(c for c in first.checks if c["task"] == task)
    assert int(budget.replace(",", "")) == check["budget"], row[0]
    assert row[1] == f"{first.success(task, ALGO, 'dense'):.2f}", f"{name}: dense"
    assert row[2] == f"{first.success(task, ALGO, 'sparse'):.2f}", f"{name}: sparse"
    expected = [_cell(profiles[p], task) for p in PROFILES]
    assert row[3:] == expected, f"{name}: the README's cells differ from the summaries"
