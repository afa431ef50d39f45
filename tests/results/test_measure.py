"""Success measures: a profile that counts success at any step scores, ranks and checks every
cell that way, never mixes the two counts in one comparison, and says which cells it could not
count so."""

from __future__ import annotations

import pytest

from planshape.harness.profiles import METAWORLD_PROFILE, PROFILES, current_settings
from planshape.results.cells import summarize
from planshape.results.leaderboard import render_leaderboard
from planshape.results.measure import measured
from planshape.results.tables import by_task_and_algo
from planshape.results.verdict import budget_check
from tests.results.synthetic import make_run

TASK = "planshape/MetaWorld-reach-v4"
ALGO = "SBX-SAC"
BUDGET = METAWORLD_PROFILE.budgets()[(TASK, ALGO)]


def _cell(end_any: dict[str, tuple[float, float]], seeds: int = 5) -> list[dict]:
    """Runs of one cell: entry -> (success at the end, success at any step) on every seed."""
    rows = []
    for entry, (end, any_step) in end_any.items():
        for seed in range(seeds):
            rows += make_run(TASK, entry, ALGO, seed, BUDGET, end, success_any_rate=any_step)
    return rows


#: dense drifts off the goal before the episode ends; plan-distance stays on it less often
LEVELS = {
    "sparse": (0.0, 0.2),
    "dense": (0.3, 1.0),
    "plan-distance/stages": (0.6, 0.6),
}


def _ranked(rows) -> list[str]:
    [[ranked]] = [by_algo.values() for by_algo in by_task_and_algo(summarize(rows)).values()]
    return [r["entry"] for r in ranked]


def test_any_step_counts_every_point_of_every_run_and_keeps_the_end_rate_beside_it():
    rows = _cell(LEVELS)
    out, at_end = measured(rows, "any-step")
    assert at_end == {}
    assert len(out) == len(rows)
    for before, after in zip(rows, out, strict=True):
        assert after["success_rate"] == before["success_any_rate"]
        assert after["success_end_rate"] == before["success_rate"]
        assert "success_any_rate" not in after
    assert measured(rows, "end") == (rows, {})


def test_the_measure_decides_the_ranking_and_the_budget_check():
    rows = _cell(LEVELS)
    assert _ranked(rows)[0] == "plan-distance/stages"
    assert budget_check(summarize(rows)).status == "no-verdict"
    counted = measured(rows, "any-step")[0]
    assert _ranked(counted)[0] == "dense"
    check = budget_check(summarize(counted))
    assert check.status == "decides"
    assert "dense 1.00" in check.text


def test_a_cell_with_one_older_run_is_counted_at_the_end_for_all_its_runs():
    rows = _cell(LEVELS)
    older = rows[0]["run_id"]
    rows = [
        {k: v for k, v in r.items() if not (r["run_id"] == older and k == "success_any_rate")}
        for r in rows
    ]
    other = make_run("planshape/MetaWorld-drawer-close-v3", "dense", ALGO, 0, 100_000, 0.1,
                     success_any_rate=0.9)  # fmt: skip
    out, at_end = measured(rows + other, "any-step")
    assert at_end == {(TASK, ALGO): [older]}
    cell = [r for r in out if r["task"] == TASK]
    assert [r["success_rate"] for r in cell] == [r["success_rate"] for r in rows]
    assert all("success_end_rate" not in r for r in cell)
    assert [r["success_rate"] for r in out if r["task"] != TASK] == [
        r["success_any_rate"] for r in other
    ]


def test_an_unknown_measure_is_refused():
    with pytest.raises(ValueError, match="unknown success measure 'last'"):
        measured([], "last")


def test_metaworld_counts_success_at_any_step_and_the_planar_profiles_at_the_end():
    assert METAWORLD_PROFILE.success_measure == "any-step"
    planar = [p for name, p in PROFILES.items() if "metaworld" not in name and name != "full"]
    assert planar and all(p.success_measure == "end" for p in planar)


def test_the_profile_shows_rows_by_its_measure_and_its_header_names_cells_it_could_not(tmp_path):
    profile = METAWORLD_PROFILE
    rows = [
        r | {"hyperparameters": current_settings(TASK, ALGO, r["entry"])} for r in _cell(LEVELS)
    ]
    shown = profile.shown(rows)
    assert [r["success_rate"] for r in shown] == [r["success_any_rate"] for r in rows]
    header = profile.header(rows)
    assert any("at any step (MetaWorld's own protocol)" in c for c in header["caveats"])
    assert not any("counted at the episode's end" in c for c in header["caveats"])

    older = [{k: v for k, v in r.items() if k != "success_any_rate"} for r in rows]
    assert profile.shown(older) == older
    [caveat] = [c for c in profile.header(older)["caveats"] if c.startswith(f"{TASK} / {ALGO}:")]
    assert caveat.startswith(f"{TASK} / {ALGO}: success counted at the episode's end")
    assert "15 of its stored runs" in caveat

    render_leaderboard(shown, tmp_path, profile.header(rows), reps=200)
    text = (tmp_path / "LEADERBOARD.md").read_text()
    assert "| Mean success | Mean success, episode end |" in text
    assert "Success here counts an episode whose success flag is set at any step" in text
    render_leaderboard(profile.shown(older), tmp_path, profile.header(older), reps=200)
    text = (tmp_path / "LEADERBOARD.md").read_text()
    assert "episode end |" not in text and "Success here counts" not in text
