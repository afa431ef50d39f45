"""``planshape adopt``: runs move from a scratch folder into stored results only where that
cannot change or mix stored evidence."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from planshape.cli import main
from planshape.harness.adopt import adopt
from planshape.harness.profiles import METAWORLD_PROFILE, current_settings
from planshape.harness.store import ResultStore
from tests.results.synthetic import make_run

TASK = "planshape/MetaWorld-window-close-v3"
ALGO = "SBX-SAC"
BUDGET = METAWORLD_PROFILE.budgets()[(TASK, ALGO)]


def _run(seed: int, entry: str = "dense", budget: int = BUDGET) -> list[dict]:
    """A run of the metaworld profile (its settings), named by entry and seed."""
    rows = make_run(TASK, entry, ALGO, seed, budget, 0.6)
    settings = current_settings(TASK, ALGO, entry)
    run_id = f"{entry.replace('/', '-')}{seed}"
    return [
        r | {"profile": "metaworld", "run_id": run_id, "hyperparameters": settings} for r in rows
    ]


def _main(scratch: Path, stored: Path) -> int:
    return main(["adopt", str(scratch), "--out", str(stored), "--profile", "metaworld"])


def _write(folder: Path, rows: list[dict]) -> Path:
    return ResultStore(folder).write(rows[0]["run_id"], rows)


def _snapshot(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted((folder / "runs").glob("*"))}


def test_a_re_execution_that_repeats_a_stored_run_replaces_it_and_adds_its_fields(tmp_path):
    stored, scratch = tmp_path / "stored", tmp_path / "scratch"
    _write(stored, _run(0))
    again = [r | {"wall_time_s": 99.0, "success_any_rate": 0.9} for r in _run(0)]
    _write(scratch, again)
    _write(scratch, _run(1))
    plan = adopt(scratch, stored, METAWORLD_PROFILE)
    assert [p.name for p in plan.replaced] == ["dense0.jsonl"]
    assert [p.name for p in plan.added] == ["dense1.jsonl"]
    assert _snapshot(stored) == _snapshot(scratch)
    assert adopt(scratch, stored, METAWORLD_PROFILE).unchanged  # adopting again changes nothing


def test_a_re_execution_with_other_numbers_is_refused_and_nothing_changes(tmp_path, capsys):
    stored, scratch = tmp_path / "stored", tmp_path / "scratch"
    _write(stored, _run(0))
    _write(scratch, _run(1))  # fine, but a refusal writes nothing at all
    changed = _run(0)
    changed[2]["success_rate"] += 0.1
    _write(scratch, changed)
    before = _snapshot(stored)
    assert _main(scratch, stored) == 2
    err = capsys.readouterr().err
    assert "dense0.jsonl: does not repeat the stored run" in err
    assert "row 3 (step 100000): success_rate" in err
    assert "Traceback" not in err
    assert _snapshot(stored) == before


def test_a_run_the_profile_does_not_plan_is_never_mixed_in(tmp_path, capsys):
    stored, scratch = tmp_path / "stored", tmp_path / "scratch"
    _write(stored, _run(0))
    _write(scratch, _run(1, budget=100_000))
    assert _main(scratch, stored) == 2
    err = capsys.readouterr().err
    assert "seed 1, 100,000 steps, is not a run of the 'metaworld' profile" in err
    assert list(_snapshot(stored)) == ["dense0.jsonl"]


def test_the_profile_is_the_one_whose_folder_out_is_unless_named(tmp_path, capsys):
    _write(tmp_path / "scratch", _run(0))
    assert main(["adopt", str(tmp_path / "scratch"), "--out", str(tmp_path / "stored")]) == 2
    assert "not a profile's own folder; name the profile" in capsys.readouterr().err


def test_whole_entries_holds_back_runs_of_entries_with_seeds_missing(tmp_path):
    stored, scratch = tmp_path / "stored", tmp_path / "scratch"
    for seed in range(5):
        _write(scratch, _run(seed))
    for seed in range(3):
        _write(scratch, _run(seed, entry="plan-distance/stages"))
    plan = adopt(scratch, stored, METAWORLD_PROFILE, whole_entries=True, dry_run=True)
    assert not (stored / "runs").exists()  # a dry run writes nothing
    assert sorted(p.name for p in plan.added) == [f"dense{s}.jsonl" for s in range(5)]
    assert len(plan.held_back) == 3
    adopt(scratch, stored, METAWORLD_PROFILE, whole_entries=True)
    assert sorted(_snapshot(stored)) == [f"dense{s}.jsonl" for s in range(5)]


def test_an_unfinished_scratch_run_is_refused_by_name(tmp_path, capsys):
    stored, scratch = tmp_path / "stored", tmp_path / "scratch"
    path = _write(scratch, _run(0))
    lines = path.read_text().splitlines()
    path.write_text("\n".join(lines[:-1]) + "\n")  # the final row is missing
    assert _main(scratch, stored) == 2
    assert "dense0.jsonl" in capsys.readouterr().err
    assert not (stored / "runs").exists()


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("wall_time_s", 1.0),
        ("steps_per_s", 1.0),
        ("code_version", "v9"),
        ("cpu", "Intel(R) Xeon(R) Platinum 8481C (avx512f)"),
    ],
)
def test_only_the_execution_s_own_fields_may_differ(tmp_path, field, value):
    stored, scratch = tmp_path / "stored", tmp_path / "scratch"
    _write(stored, [r | {"cpu": "AMD EPYC (avx2)"} for r in _run(0)])
    _write(scratch, [r | {"cpu": "AMD EPYC (avx2)", field: value} for r in _run(0)])
    assert [p.name for p in adopt(scratch, stored, METAWORLD_PROFILE).replaced] == ["dense0.jsonl"]
    assert (
        json.loads((stored / "runs" / "dense0.jsonl").read_text().splitlines()[0])[field] == value
    )
