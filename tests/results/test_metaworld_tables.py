"""The MetaWorld tables say what the stored runs and rendered summaries say.

The README's table gives each task's dense and sparse success and, under each of the three
MetaWorld profiles, the shaping outcome and the planning-derived entry that gives it with that
entry's mean success. ``leaderboard/METAWORLD.md``'s ``metaworld-s10`` table gives each entry's
final success per seed and its mean, end-of-episode success and curve area at φ × 10 beside the
same numbers at φ × 100 (the ``metaworld`` profile) and dense's; and its ``metaworld`` section
has one table per task with every entry's final success per seed (any step and episode's end),
mean, IQM with its interval and curve area. Both documents also say how many of its runs each
partial profile holds ("150 of its 155 runs"). They are written by hand as entries are adopted;
these tests keep them from drifting away from the runs. Figures are read to two
places, rounding halves up as a person rounding the page's three-place figures does.
"""

from __future__ import annotations

import re
from decimal import ROUND_HALF_UP, Decimal
from pathlib import Path

import pytest

from planshape.results.cells import final_rows
from planshape.results.evidence import ProfileEvidence, read_profiles
from planshape.results.rows import load_rows

ROOT = Path(__file__).resolve().parents[2]
README = ROOT / "README.md"
METAWORLD_DOC = ROOT / "leaderboard" / "METAWORLD.md"
S10_TABLE_HEADER = "| task, entry (5 seeds) | seeds 0–4 at 10 |"
TASK_TABLE_HEADER = "| entry | seeds 0–4, any step"
HEADING = "### MetaWorld with SAC"
PROFILES = ("metaworld", "metaworld-s10", "metaworld-progress")
#: how the table words each :data:`planshape.results.outcome.Status`
LABELS = {"at-least-dense": "at least dense", "faster": "faster", "below-dense": "below dense"}
ALGO = "SBX-SAC"
#: the s10 table's figures after the seeds: mean success, end-of-episode success, curve area
FIGURES = ("success_mean", "success_end_mean", "curve_area_mean")


def _two(value: float) -> str:
    """A figure as the page gives it (three places), then to two, halves rounded up.

    >>> _two(0.615), _two(0.6149999999999999), _two(0.614), _two(1.0)
    ('0.62', '0.62', '0.61', '1.00')
    """
    on_page = Decimal(repr(value)).quantize(Decimal("0.001"), rounding=ROUND_HALF_UP)
    return str(on_page.quantize(Decimal("0.01"), rounding=ROUND_HALF_UP))


def _cells(line: str) -> list[str]:
    """A markdown table line's cells; an escaped pipe, ``\\|``, stays inside its cell."""
    return [c.strip() for c in re.split(r"(?<!\\)\|", line.strip().strip("|"))]


def _readme_table_rows() -> list[list[str]]:
    text = README.read_text(encoding="utf-8")
    assert HEADING in text, f"README.md has no {HEADING!r} section"
    section = text.split(HEADING, 1)[1].split("\n### ", 1)[0]
    lines = [line for line in section.splitlines() if line.startswith("| ")]
    assert lines and "`metaworld`" in lines[0], "the section's table has moved or lost its header"
    return [_cells(line) for line in lines[1:]]


def _doc_tables(header: str) -> list[tuple[str, list[list[str]]]]:
    """Each METAWORLD.md table whose header starts so, after the lead of the paragraph that
    names its task (``**TASK is complete``, or "" if none comes before it), with its rows:
    bold marks removed, header and rule skipped."""
    lines = METAWORLD_DOC.read_text(encoding="utf-8").splitlines()
    tables, lead = [], ""
    for i, line in enumerate(lines):
        if found := re.match(r"\*\*(\S+) is complete", line):
            lead = found[1]
        if not line.startswith(header):
            continue
        rows = []
        for row in lines[i + 2 :]:
            if not row.startswith("|"):
                break
            rows.append(_cells(row.replace("**", "")))
        tables.append((lead, rows))
    return tables


def _doc_table_rows(header: str) -> list[list[str]]:
    """The one METAWORLD.md table whose header starts so."""
    tables = _doc_tables(header)
    assert len(tables) == 1, f"METAWORLD.md has {len(tables)} tables headed {header!r}"
    return tables[0][1]


def _final_rows_by_seed(profile: str) -> dict[tuple[str, str], dict[int, dict]]:
    """Each (task, entry)'s final evaluation row per seed, from the profile's run files."""
    finals: dict[tuple[str, str], dict[int, dict]] = {}
    for last in final_rows(load_rows(ROOT / "leaderboard" / profile)):
        if last["algo"] == ALGO:
            finals.setdefault((last["task"], last["entry"]), {})[last["seed"]] = last
    return finals


def _per_seed(rows: dict[int, dict], key: str) -> str:
    return " ".join(f"{rows[seed][key]:.1f}" for seed in sorted(rows))


def _readme_name(task: str) -> str:
    """How the tables name a task: its id without namespace, ``MetaWorld-`` or ``-v3``.

    >>> _readme_name("planshape/MetaWorld-drawer-close-v3")
    'drawer-close'
    """
    return task.replace("-v3", "").removeprefix("planshape/MetaWorld-")


def _row_name(row: list[str]) -> str:
    return row[0].split(" (")[0]


def _task_named(profiles: dict[str, ProfileEvidence], name: str) -> str:
    return next(c["task"] for c in profiles["metaworld"].checks if _readme_name(c["task"]) == name)


def _s10_row_key(profiles: dict[str, ProfileEvidence], row: list[str]) -> tuple[str, str]:
    """The (task, entry) an s10 table row names, as in "window-open, `plan-based/stages`"."""
    match = re.fullmatch(r"(\S+), `([^`]+)`(?: \(code \w+\))?", row[0])
    assert match, f"METAWORLD.md: cannot read the s10 table's row {row[0]!r}"
    return _task_named(profiles, match[1]), match[2]


def _cell(profile: ProfileEvidence, task: str) -> str:
    check = next(c for c in profile.checks if c["task"] == task and c["algo"] == ALGO)
    entry = check["outcome_entry"]
    success = profile.success(task, ALGO, entry)
    return f"{LABELS[check['outcome']]}: `{entry}` {_two(success)}"


@pytest.fixture(scope="module")
def profiles() -> dict[str, ProfileEvidence]:
    found = {p.name: p for p in read_profiles(ROOT / "leaderboard")}
    return {name: found[name] for name in PROFILES}


def test_the_table_has_one_row_per_task_of_the_profile(profiles):
    tasks = {c["task"] for c in profiles["metaworld"].checks}
    assert {_readme_name(t) for t in tasks} == {_row_name(row) for row in _readme_table_rows()}


@pytest.mark.parametrize("index", range(6))
def test_each_row_reads_as_the_summaries_do(profiles, index):
    row = _readme_table_rows()[index]
    name, budget = re.fullmatch(r"(\S+) \(([\d,]+)\)", row[0]).groups()
    task = _task_named(profiles, name)
    first = profiles["metaworld"]
    check = next(c for c in first.checks if c["task"] == task)
    assert int(budget.replace(",", "")) == check["budget"], row[0]
    assert row[1] == _two(first.success(task, ALGO, "dense")), f"{name}: dense"
    assert row[2] == _two(first.success(task, ALGO, "sparse")), f"{name}: sparse"
    expected = [_cell(profiles[p], task) for p in PROFILES]
    assert row[3:] == expected, f"{name}: the README's cells differ from the summaries"


def test_the_s10_table_names_each_stored_entry_of_a_deciding_cell_once(profiles):
    """Drawer-close, which separates little, is told in prose, not in the table."""
    named = [_s10_row_key(profiles, row) for row in _doc_table_rows(S10_TABLE_HEADER)]
    s10 = profiles["metaworld-s10"]
    deciding = {c["task"] for c in s10.checks if c["status"] != "separates-little"}
    shaped = {
        (r["task"], r["entry"])
        for r in s10.rows
        if r["algo"] == ALGO and r["task"] in deciding and r["entry"] not in ("sparse", "dense")
    }
    assert len(named) == len(set(named)), "a row is repeated"
    assert set(named) == shaped, "the table's rows and the profile's shaped entries differ"


def test_each_s10_row_reads_as_the_runs_and_summaries_do(profiles):
    finals = _final_rows_by_seed("metaworld-s10")
    for row in _doc_table_rows(S10_TABLE_HEADER):
        task, entry = _s10_row_key(profiles, row)
        at_10 = profiles["metaworld-s10"].row(task, ALGO, entry)
        at_100 = profiles["metaworld"].row(task, ALGO, entry)
        dense = profiles["metaworld"].row(task, ALGO, "dense")
        expected = [
            _per_seed(finals[(task, entry)], "success_any_rate"),
            *(f"{_two(at_10[key])} ({_two(at_100[key])})" for key in FIGURES),
            f"{_two(dense['success_mean'])}, {_two(dense['curve_area_mean'])}",
        ]
        assert row[1:] == expected, f"METAWORLD.md, s10 table, {row[0]}"


def test_metaworld_has_one_table_per_task(profiles):
    named = [name for name, _ in _doc_tables(TASK_TABLE_HEADER)]
    tasks = {_readme_name(c["task"]) for c in profiles["metaworld"].checks}
    assert sorted(named) == sorted(tasks), "each `metaworld` task has one table after its lead"


@pytest.mark.parametrize("index", range(6))
def test_each_metaworld_table_reads_as_the_runs_and_summary_do(profiles, index):
    """A ``metaworld`` task's table: every entry of the cell, per seed and in sum."""
    name, table = _doc_tables(TASK_TABLE_HEADER)[index]
    task = _task_named(profiles, name)
    finals = _final_rows_by_seed("metaworld")
    stored = {entry for stored_task, entry in finals if stored_task == task}
    assert {row[0].strip("`") for row in table} == stored, f"{name}: the table's entries differ"
    for row in table:
        entry = row[0].strip("`")
        seeds = finals[(task, entry)]
        summary = profiles["metaworld"].row(task, ALGO, entry)
        expected = [
            _per_seed(seeds, "success_any_rate") + " \\| " + _per_seed(seeds, "success_rate"),
            f"{_two(summary['success_mean'])} ({_two(summary['success_end_mean'])})",
            f"{_two(summary['success_iqm'])} [{_two(summary['success_iqm_low'])}, "
            f"{_two(summary['success_iqm_high'])}]",
            _two(summary["curve_area_mean"]),
        ]
        assert row[1:] == expected, f"METAWORLD.md, metaworld's {name} table, {entry}"


#: "150 of 155", "150 of its 155", "145 of the profile's 155": a count of a profile's stored runs
STORED_COUNT = re.compile(r"\b(\d+) of (?:its |their |the profile's )?(\d+)\b")
#: a count of runs, not of tasks or cells ("3 of 6"): every MetaWorld profile plans 155 runs
FEWEST_PLANNED = 100
#: the profiles that can be partial, as the documents name them
PARTIAL_NAMES = re.compile(r"`(metaworld-s10|metaworld-progress)`")


def _near(text: str, match: re.Match[str]) -> str:
    """The words around a match, on one line, to say where a failing count stands."""
    return " ".join(text[max(match.start() - 40, 0) : match.end() + 20].split())


def _counts_in_readme() -> list[tuple[str, int, int, str]]:
    """Each (profile, stored, planned, where) the README states: a profile table row's count
    belongs to the row's profile, any other to the partial profile named last before it in its
    paragraph."""
    found = []
    for paragraph in README.read_text(encoding="utf-8").split("\n\n"):
        for line in paragraph.splitlines() if paragraph.startswith("| ") else [paragraph]:
            row = re.match(r"\| `([\w-]+)` \|", line)
            for count in STORED_COUNT.finditer(line):
                before = PARTIAL_NAMES.findall(line[: count.start()])
                name = row[1] if row else (before[-1] if before else None)
                if name in PROFILES and int(count[2]) >= FEWEST_PLANNED:
                    found.append((name, int(count[1]), int(count[2]), _near(line, count)))
    return found


def _counts_in_doc() -> list[tuple[str, int, int, str]]:
    """Each (profile, stored, planned, where) METAWORLD.md states: its section's profile."""
    found = []
    for section in METAWORLD_DOC.read_text(encoding="utf-8").split("\n## ")[1:]:
        heading = re.match(r"`([\w-]+)`", section)
        for count in STORED_COUNT.finditer(section):
            if heading and int(count[2]) >= FEWEST_PLANNED:
                name = heading[1]
                found.append((name, int(count[1]), int(count[2]), _near(section, count)))
    return found


def test_every_count_of_stored_runs_is_the_profiles(profiles):
    """A count such as "145 of its 155 runs", written by hand at each adoption; each partial
    profile's count is stated somewhere."""
    stated = _counts_in_readme() + _counts_in_doc()
    partial = {name for name, p in profiles.items() if p.state.startswith("partial")}
    assert partial <= {name for name, *_ in stated}, "a partial profile's count is not stated"
    for name, stored, planned, where in stated:
        profile = profiles[name]
        of_planned = re.search(r"of the profile's (\d+) runs", profile.state)
        assert planned == (int(of_planned[1]) if of_planned else profile.n_runs), where
        assert stored == profile.n_runs, f"{name} holds {profile.n_runs} runs, not {where!r}"
