"""planshape.results: the stored rows as one tidy, typed DataFrame, and `planshape export`."""

from __future__ import annotations

import pandas as pd
import pytest

from planshape.cli import main
from planshape.harness.store import ResultStore
from planshape.results import load
from tests.results.synthetic import make_run


@pytest.fixture
def stored(tmp_path):
    store = ResultStore(tmp_path)
    for entry, seed in (("sparse", 0), ("dense", 0), ("plan-based/grid", 1)):
        rows = make_run(entry=entry, seed=seed, points=3)
        store.write(rows[0]["run_id"], rows)
    return tmp_path


def test_one_typed_row_per_evaluation_point_with_nested_fields_flattened(stored):
    frame = load(stored)
    assert len(frame) == 9 and frame["run_id"].nunique() == 3
    assert str(frame["seed"].dtype) == "Int64" and str(frame["step"].dtype) == "Int64"
    assert frame["success_rate"].dtype == "float64" and frame["final"].dtype == bool
    assert frame["hyperparameters.learning_rate"].iloc[0] == pytest.approx(3e-4)
    assert frame["packages.gymnasium"].iloc[0] == "1.4.0"
    assert list(frame.columns[:4]) == ["run_id", "profile", "task", "entry"]
    assert frame.groupby("run_id")["step"].apply(lambda s: s.is_monotonic_increasing).all()
    final = load(stored, final_only=True)
    assert len(final) == 3 and final["final"].all()
    assert set(final["entry"]) == {"sparse", "dense", "plan-based/grid"}


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_export_round_trips(stored, tmp_path, capsys, suffix):
    target = tmp_path / f"out{suffix}"
    assert main(["export", str(stored), "--to", str(target)]) == 0
    assert "wrote 9 rows" in capsys.readouterr().out
    back = pd.read_csv(target) if suffix == ".csv" else pd.read_parquet(target)
    frame = load(stored)
    assert list(back.columns) == list(frame.columns) and len(back) == len(frame)
    assert back["success_rate"].tolist() == pytest.approx(frame["success_rate"].tolist())


def test_export_refuses_other_formats_and_damaged_stores(stored, tmp_path, capsys):
    assert main(["export", str(stored), "--to", str(tmp_path / "out.xlsx")]) == 2
    assert "write a .csv or a .parquet file" in capsys.readouterr().err
    victim = next((stored / "runs").glob("*.jsonl"))
    victim.write_text("")
    assert main(["export", str(stored), "--to", str(tmp_path / "out.csv")]) == 2
    assert "empty: no result rows" in capsys.readouterr().err


def _same(a, b) -> bool:
    """Equal lists of dicts, NaN equal to NaN."""
    import math

    def norm(v):
        return "nan" if isinstance(v, float) and math.isnan(v) else v

    return [{k: norm(v) for k, v in r.items()} for r in a] == [
        {k: norm(v) for k, v in r.items()} for r in b
    ]


def test_the_aggregation_works_on_the_frame_as_on_the_rows():
    """summarize and aggregate give the same numbers from load()'s frame as from the stored
    rows (the committed default leaderboard), and a selection of the frame is scored alone."""
    from pathlib import Path

    from planshape.harness.profiles import PROFILES
    from planshape.results.cells import aggregate, summarize
    from planshape.results.frame import records
    from planshape.results.rows import load_rows

    folder = Path(__file__).resolve().parents[2] / "leaderboard"
    rows = PROFILES["default"].shown(load_rows(folder))  # not the runs at an old budget
    frame = load(folder)
    frame = frame[frame["run_id"].isin({r["run_id"] for r in rows})]
    assert records(frame.iloc[:1])[0]["hyperparameters"]["n_envs"] in (1, 8)
    assert _same(summarize(frame, reps=200), summarize(rows, reps=200))
    assert _same(aggregate(frame, reps=200), aggregate(rows, reps=200))
    maze = summarize(frame[frame["task"] == "planshape/MazeReach-v1"], reps=200)
    assert maze and {r["task"] for r in maze} == {"planshape/MazeReach-v1"}
