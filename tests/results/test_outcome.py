"""The shaping outcome: whether a planning-derived potential reaches dense in a cell, and that the
leaderboard says it for every cell and counts it over the cells that decide."""

from __future__ import annotations

import json

import numpy as np
import pytest

from planshape.harness import profiles
from planshape.results import outcome
from planshape.results.leaderboard import render_leaderboard, summary_table
from planshape.results.outcome import shaping_outcome, tally
from tests.results.synthetic import make_run


def _row(entry: str, success: float, area: float) -> dict[str, object]:
    potential = None if entry in ("sparse", "dense") else entry.split("/", 1)[0]
    return {
        "entry": entry,
        "potential": potential,
        "success_mean": success,
        "curve_area_mean": area,
    }


@pytest.mark.parametrize(
    ("cell", "status", "entry"),
    [
        # drawer-close counted at the episode's end: level with dense at the budget
        ([_row("dense", 0.94, 0.85), _row("plan-distance/stages", 0.94, 0.63)],
         "at-least-dense", "plan-distance/stages"),
        # the best final success is the one compared, not the first or the fastest
        ([_row("dense", 0.5, 0.4), _row("plan-based/grid", 0.2, 0.9),
          _row("plan-path/grid", 0.6, 0.1)], "at-least-dense", "plan-path/grid"),
        # window-close: ends lower, larger curve area
        ([_row("dense", 0.90, 0.36), _row("plan-distance/stages", 0.64, 0.47),
          _row("sparse", 0.28, 0.17)], "faster", "plan-distance/stages"),
        # button-press: below on both
        ([_row("dense", 0.62, 0.30), _row("plan-based/stages", 0.36, 0.13),
          _row("sparse", 0.40, 0.11)], "below-dense", "plan-based/stages"),
        # an equal curve area is not faster
        ([_row("dense", 0.9, 0.4), _row("plan-based/grid", 0.8, 0.4)], "below-dense",
         "plan-based/grid"),
        # the control is shaped but not planning-derived: it never answers
        ([_row("dense", 0.8, 0.5), _row("goal-distance/grid", 1.0, 0.9),
          _row("plan-based/grid", 0.1, 0.1)], "below-dense", "plan-based/grid"),
        ([_row("dense", 0.8, 0.5), _row("goal-distance/grid", 1.0, 0.9)], "none", None),
        ([_row("sparse", 0.0, 0.0), _row("plan-based/grid", 1.0, 0.9)], "none", None),
    ],
)  # fmt: skip
def test_status(cell, status, entry):
    result = shaping_outcome(cell)
    assert (result.status, result.entry) == (status, entry)


def test_means_that_differ_only_by_rounding_tie():
    """0.94 as a mean of the same rates in another order is not below 0.94."""
    dense = float(np.mean([1.0, 1.0, 0.9, 0.9, 0.9]))
    shaped = float(np.mean([0.9, 0.9, 1.0, 0.9, 1.0]))
    assert shaped < dense  # the sums round differently
    cell = [_row("dense", dense, 0.9), _row("plan-distance/stages", shaped, 0.1)]
    assert shaping_outcome(cell).status == "at-least-dense"


def test_a_clear_gap_is_not_a_tie():
    cell = [_row("dense", 0.94, 0.9), _row("plan-distance/stages", 0.92, 0.1)]
    assert shaping_outcome(cell).status == "below-dense"


def test_the_sentences_name_the_entries_and_levels():
    faster = shaping_outcome([_row("dense", 0.9, 0.36), _row("plan-distance/stages", 0.64, 0.47)])
    assert "best plan-distance/stages 0.64, dense 0.90" in faster.text
    assert "0.47 against dense's 0.36" in faster.text
    below = shaping_outcome(
        [_row("dense", 0.62, 0.3), _row("plan-based/g", 0.36, 0.1), _row("plan-path/g", 0.2, 0.13)]
    )
    assert "best plan-based/g 0.36, dense 0.62" in below.text
    assert "(best plan-path/g 0.13, dense 0.30)" in below.text


def test_the_tally_counts_only_cells_that_decide():
    checks = [
        {"task": "planshape/Push-v1", "algo": "PPO", "status": "decides", "outcome": "faster"},
        {"task": "planshape/Reach-v1", "algo": "PPO", "status": "decides", "outcome": "none"},
        {"task": "planshape/Maze-v1", "algo": "PPO", "status": "separates-little",
         "outcome": "at-least-dense"},
    ]  # fmt: skip
    text = tally(checks)
    assert "Of the 2 cells whose budget check decides" in text
    assert "reaches dense's mean success at equal budget in 0," in text
    assert "learns faster but ends lower in 1 (Push-v1 PPO)" in text
    assert "1 (Reach-v1 PPO) have nothing to compare" in text
    assert "The 1 other cell cannot show whether shaping helps" in text
    assert tally(checks[2:]).startswith("No cell's budget check decides")


def test_profiles_and_outcomes_share_one_list_of_controls():
    assert profiles.CONTROL_POTENTIALS is outcome.CONTROL_POTENTIALS


def _deciding_rows() -> list[dict[str, object]]:
    """A PPO cell that decides (plan-distance reaches dense) and a SAC cell without sparse."""
    rows = []
    for seed in range(5):
        rows += make_run(seed=seed, final_success=0.0)
        rows += make_run(entry="dense", seed=seed, final_success=0.9)
        rows += make_run(entry="plan-distance/grid", seed=seed, final_success=1.0)
        rows += make_run(entry="goal-distance/grid", seed=seed, final_success=1.0)
        rows += make_run(entry="dense", seed=seed, algo="SAC", final_success=0.9)
        rows += make_run(entry="plan-distance/grid", seed=seed, algo="SAC", final_success=0.3)
    return rows


def test_the_leaderboard_gives_every_cells_outcome(tmp_path):
    header = {"profile": "test", "command": "planshape bench --profile test", "caveats": []}
    render_leaderboard(_deciding_rows(), tmp_path, header, reps=50)
    text = (tmp_path / "LEADERBOARD.md").read_text()
    verdicts = text.split("## Verdicts")[1].split("## ")[0]
    assert (
        "Of the 1 cell whose budget check decides, a planning-derived potential reaches dense's "
        "mean success at equal budget in 1 (Reach-v0 PPO)"
    ) in verdicts
    assert (
        "| Reach-v0 | PPO | 1,000 | decides | at least dense | `plan-distance/grid` |" in verdicts
    )
    assert (
        "| Reach-v0 | SAC | 1,000 | no verdict | below dense | `plan-distance/grid` |" in verdicts
    )
    ppo = text.split("### PPO — budget")[1].split("###")[0]
    assert "**Shaping outcome**: reaches dense: plan-distance/grid's mean success 1.00" in ppo
    assert "Shaping outcome</strong>: reaches dense" in (tmp_path / "index.html").read_text()
    checks = json.loads((tmp_path / "summary.json").read_text())["budget_checks"]
    assert [(c["algo"], c["outcome"], c["outcome_entry"]) for c in checks] == [
        ("PPO", "at-least-dense", "plan-distance/grid"),
        ("SAC", "below-dense", "plan-distance/grid"),
    ]


def test_the_printed_summary_gives_each_cells_outcome():
    printed = summary_table(_deciding_rows(), reps=50)
    assert "shaping outcome: reaches dense: plan-distance/grid's" in printed
    assert "shaping outcome: below dense" in printed


def test_each_cell_gives_its_probability_of_beating_dense():
    """P(entry > dense) over runs (ties count half), counted independently here."""
    from planshape.results.cells import summarize

    plan, dense = [1.0, 0.0, 0.5, 1.0, 0.5], [0.5, 0.5, 1.0, 0.0, 0.5]
    rows = []
    for seed in range(5):
        rows += make_run(seed=seed, final_success=0.0)
        rows += make_run(entry="dense", seed=seed, final_success=dense[seed])
        rows += make_run(entry="plan-path/grid", seed=seed, final_success=plan[seed])
    pairs = [(x > y) + 0.5 * (x == y) for x in plan for y in dense]
    summary = summarize(rows, reps=200)
    shaped = next(r for r in summary if r["entry"] == "plan-path/grid")
    assert shaped["p_improve_dense"] == pytest.approx(sum(pairs) / len(pairs))
    assert shaped["p_improve_dense_low"] <= shaped["p_improve_dense"]
    assert shaped["p_improve_dense"] <= shaped["p_improve_dense_high"]
    result = shaping_outcome(summary)
    assert result.status == "at-least-dense"  # equal means: 0.6 each
    assert result.p_improve_dense[0] == shaped["p_improve_dense"]
    assert f"; P(plan-path/grid > dense) {shaped['p_improve_dense']:.2f} [" in result.text
    # dense against itself: every pair of runs is as likely to go either way
    assert next(r for r in summary if r["entry"] == "dense")["p_improve_dense"] == 0.5
