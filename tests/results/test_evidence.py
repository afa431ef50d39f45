"""`planshape evidence`: every profile's verdicts on one page, read from the rendered summaries;
the committed page is the one the committed summaries give."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from planshape.cli import main
from planshape.results.evidence import evidence_markdown, read_profiles
from planshape.results.leaderboard import render_leaderboard
from planshape.results.verdict import SOLVED
from tests.results.synthetic import make_run

LEADERBOARD = Path(__file__).resolve().parents[2] / "leaderboard"
COMMITTED = LEADERBOARD / "EVIDENCE.md"


def _render(
    out: Path, profile: str, caveats: list[str], plan_success: float, budget: int = 1000
) -> None:
    """A rendered profile of one 5-seed reach cell: dense 1.0, sparse 0.0, one potential."""
    rows = []
    for seed in range(5):
        rows += make_run(entry="dense", seed=seed, final_success=1.0, budget=budget)
        rows += make_run(entry="sparse", seed=seed, final_success=0.0, budget=budget)
        rows += make_run(
            entry="plan-based/grid", seed=seed, final_success=plan_success, budget=budget
        )
    header = {"profile": profile, "description": f"{profile} runs", "caveats": caveats}
    render_leaderboard(rows, out, header, reps=50)


@pytest.fixture
def rendered(tmp_path: Path) -> Path:
    _render(tmp_path, "default", [], plan_success=1.0)
    partial = "partial: 15 of the profile's 30 runs are stored; the others have not been trained"
    _render(tmp_path / "planar", "planar", [partial], plan_success=0.0)
    _render(tmp_path / "default-v0", "default-v0", [], plan_success=1.0)
    return tmp_path


def test_it_gathers_each_rendered_profile_in_the_registry_order_with_its_state(rendered):
    profiles = read_profiles(rendered)
    assert [(p.name, p.folder) for p in profiles] == [
        ("default", "."),
        ("planar", "planar"),
        ("default-v0", "default-v0"),
    ]
    assert [p.state.split(":")[0] for p in profiles] == ["complete", "partial", "archived"]
    assert profiles[0].counts() == {
        "cells": 1,
        "decides": 1,
        "at-least-dense": 1,
        "faster": 0,
        "below-dense": 0,
    }
    assert profiles[1].counts()["below-dense"] == 1
    assert profiles[1].success("planshape/Reach-v0", "PPO", "dense") == pytest.approx(1.0)


def test_the_page_puts_each_cells_verdict_beside_the_numbers_of_its_leaderboard(rendered):
    page = evidence_markdown(rendered)
    assert "| `default` | complete | 15 | 1 | 1 | 1 | 0 | 0 |" in page
    partial = "partial: 15 of the profile's 30 runs are stored"
    assert f"| `planar` | {partial} | 15 | 1 | 1 | 0 | 0 | 1 |" in page
    assert "no rendered results here: `smoke`, `paper`, `full`, `metaworld`," in page
    planar = page.split("## planar")[1].split("## default-v0")[0]
    assert "Planar runs. State: partial" in planar
    assert "[planar/LEADERBOARD.md](planar/LEADERBOARD.md)" in planar
    row = next(line for line in planar.splitlines() if line.startswith("| Reach-v0 | PPO"))
    # entry, dense and sparse success as the planar profile's summary states them
    assert "| decides | below dense | `plan-based/grid` | 0.00 | 1.00 | 0.00 |" in row
    summary = json.loads((rendered / "planar" / "summary.json").read_text())
    assert summary["budget_checks"][0]["outcome"] == "below-dense"


def test_profiles_that_run_the_same_cells_show_each_entry_side_by_side(rendered):
    """default and planar share the reach cell and differ in plan-based's runs; the archived
    default-v0 is left out."""
    section = evidence_markdown(rendered).split("## Profiles that run the same cells")[1]
    assert "| Task | Algorithm | Entry | default | planar |" in section
    assert "| Reach-v0 | PPO | `plan-based/grid` | 1.00 | 0.00 |" in section
    assert "| Reach-v0 | PPO | `dense` | 1.00 | 1.00 |" in section  # for reference
    assert "default-v0" not in section


def test_entries_whose_runs_are_the_same_everywhere_have_no_row(tmp_path):
    _render(tmp_path, "default", [], plan_success=1.0)
    _render(tmp_path / "planar", "planar", [], plan_success=1.0)  # the same runs' numbers
    _render(tmp_path / "paper", "paper", [], plan_success=0.0, budget=2000)  # another cell
    page = evidence_markdown(tmp_path)
    assert "## Profiles that run the same cells" not in page
    _render(tmp_path / "planar", "planar", [], plan_success=0.0, budget=2000)
    # planar now shares paper's cell, not default's, and their plan-based runs are the same
    assert "## Profiles that run the same cells" not in evidence_markdown(tmp_path)
    _render(tmp_path / "planar", "planar", [], plan_success=1.0, budget=2000)
    section = evidence_markdown(tmp_path).split("## Profiles that run the same cells")[1]
    assert "| Task | Algorithm | Entry | planar | paper |" in section
    assert "| Reach-v0 | PPO | `plan-based/grid` | 1.00 | 0.00 |" in section


def test_the_command_prints_or_writes_the_page(rendered, tmp_path, capsys):
    assert main(["evidence", str(rendered)]) == 0
    assert capsys.readouterr().out == evidence_markdown(rendered)
    target = tmp_path / "out" / "EVIDENCE.md"
    assert main(["evidence", str(rendered), "--to", str(target)]) == 0
    assert target.read_text() == evidence_markdown(rendered)


def test_bad_input_is_a_clear_error_and_writes_nothing(rendered, tmp_path, capsys):
    empty = tmp_path / "empty"
    empty.mkdir()
    target = tmp_path / "EVIDENCE.md"
    assert main(["evidence", str(empty), "--to", str(target)]) == 2
    assert f"{empty}: no summary.json" in capsys.readouterr().err
    assert main(["evidence", str(rendered), "--to", str(tmp_path / "page.html")]) == 2
    assert "name a Markdown file" in capsys.readouterr().err
    (rendered / "planar" / "summary.json").write_text('{"header": {}}')
    assert main(["evidence", str(rendered), "--to", str(target)]) == 2
    err = capsys.readouterr().err
    assert f"{rendered / 'planar' / 'summary.json'}: not a leaderboard summary" in err
    assert "Traceback" not in err and not target.exists()


def test_the_committed_page_is_the_one_the_committed_summaries_give():
    assert COMMITTED.read_text(encoding="utf-8") == evidence_markdown(LEADERBOARD), (
        "leaderboard/EVIDENCE.md is stale: run "
        "planshape evidence leaderboard --to leaderboard/EVIDENCE.md"
    )


def test_every_committed_verdict_agrees_with_the_numbers_beside_it():
    """The budget check's and the outcome's rules, read back from each committed cell's means:
    a wrong verdict anywhere in the committed summaries fails here."""
    for profile in read_profiles(LEADERBOARD):
        for check in profile.checks:
            cell = f"{profile.name}: {check['task']} {check['algo']}"
            mean = {
                who: profile.success(check["task"], check["algo"], entry)
                for who, entry in (
                    ("entry", check["outcome_entry"]),
                    ("dense", "dense"),
                    ("sparse", "sparse"),
                )
            }
            if check["outcome"] == "at-least-dense":
                assert mean["entry"] >= mean["dense"] - 1e-9, cell
            elif check["outcome"] in ("faster", "below-dense"):
                assert mean["entry"] < mean["dense"], cell
            if check["status"] == "decides":
                solved = max(mean["dense"], mean["entry"] or 0.0)
                assert mean["sparse"] < SOLVED <= solved, cell
            elif check["status"] == "separates-little":
                assert mean["sparse"] >= SOLVED, cell
