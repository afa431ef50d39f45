"""Rendering the leaderboard: every file written, offline HTML, header fields, determinism."""

from __future__ import annotations

import json
import re

import pytest

from planshape.errors import ResultsError
from planshape.results.leaderboard import render_leaderboard, summary_table
from planshape.results.tables import slug
from tests.results.synthetic import make_run, synthetic_rows

HEADER = {
    "profile": "test",
    "command": "planshape bench --profile test --out leaderboard",
    "caveats": ["synthetic rows for a unit test"],
}
REPS = 200  # keeps rendering fast; the default (2000) is tested in test_scoring


@pytest.fixture(scope="module")
def rows():
    rows = synthetic_rows(seeds=3)
    # An entry named by a submitter, with characters that must be escaped.
    for seed in range(3):
        rows += make_run(entry="my_mod:<Pot>|x/grid", seed=seed, final_success=0.4)
    return rows


@pytest.fixture(scope="module")
def rendered(rows, tmp_path_factory):
    out = tmp_path_factory.mktemp("leaderboard")
    return out, render_leaderboard(rows, out, HEADER, reps=REPS)


def test_writes_every_file(rendered):
    out, paths = rendered
    names = {p.relative_to(out).as_posix() for p in paths}
    assert {"LEADERBOARD.md", "index.html", "summary.json"} <= names
    for task in ("planshape/Reach-v0", "planshape/Push-v0"):
        assert f"plots/curves_{slug(task)}.png" in names
        assert f"plots/final_distance_{slug(task)}.png" in names
    for figure in ("intervals", "profiles", "improvement"):  # rliable's, across tasks
        assert f"plots/aggregate_{figure}.png" in names
    for path in paths:
        assert path.is_file() and path.stat().st_size > 0
    for path in (p for p in paths if p.suffix == ".png"):
        data = path.read_bytes()
        assert data.startswith(b"\x89PNG")
        assert b"matplotlib" not in data  # no version string, no timestamp


def test_html_works_offline(rendered):
    out, _ = rendered
    page = (out / "index.html").read_text()
    assert not re.search(r"https?://", page)
    assert not re.search(r"<link\b|<script[^>]*\bsrc=|@import", page)
    assert page.count("data:image/png;base64,") == 4 + 3  # per task 2, across tasks 3
    assert '<table class="sortable">' in page and "addEventListener" in page
    assert "my_mod:&lt;Pot&gt;|x/grid" in page and "<Pot>" not in page
    assert f"({REPS} resamples" in page and "{reps}" not in page


def test_markdown_header_fields(rendered):
    out, _ = rendered
    text = (out / "LEADERBOARD.md").read_text()
    for expected in (
        "| Profile | test |",
        "`planshape bench --profile test --out leaderboard`",
        "- synthetic rows for a unit test",
        "v0.1.0-5-gabcdef0",  # code version
        "gymnasium 1.4.0",  # package versions
        "stable-baselines3 2.9.2",
        "| planshape/Reach-v0 | 1,000 | 1,000 |",  # budgets per task and algorithm
        "0, 1, 2",  # seeds
        "10 deterministic episodes",
        "## Hyperparameters",
        "![planshape/Reach-v0: learning curves](plots/curves_planshape-Reach-v0.png)",
    ):
        assert expected in text, expected
    assert "my_mod:<Pot>\\|x/grid" in text  # a pipe would break the table
    assert f"({REPS} resamples" in text


def test_markdown_tables_are_ranked_by_iqm_success(rendered):
    out, _ = rendered
    text = (out / "LEADERBOARD.md").read_text()
    section = text.split("## planshape/Reach-v0")[1].split("### SAC")[0]
    entries = re.findall(r"^\| `([^`]+)` \|", section, flags=re.MULTILINE)
    assert entries[0] == "plan-based/multi" and entries[-1] == "sparse"


def test_summary_json_is_strict_json_with_numbers(rendered):
    out, _ = rendered

    def reject(constant):
        raise AssertionError(f"non-standard JSON constant {constant}")

    data = json.loads((out / "summary.json").read_text(), parse_constant=reject)
    assert set(data) == {
        "aggregate", "budget_checks", "header", "per_task", "provenance", "statistics"
    }  # fmt: skip
    row = data["per_task"][0]
    assert isinstance(row["success_iqm"], float) and isinstance(row["success_iqm_low"], float)
    assert data["header"]["caveats"][0] == "synthetic rows for a unit test"
    assert data["statistics"]["bootstrap_reps"] == REPS


def test_rendering_is_byte_for_byte_deterministic(rows, rendered, tmp_path):
    out, paths = rendered
    again = render_leaderboard(list(reversed(rows)), tmp_path, HEADER, reps=REPS)
    assert [p.relative_to(tmp_path) for p in again] == [p.relative_to(out) for p in paths]
    for first, second in zip(paths, again, strict=True):
        assert first.read_bytes() == second.read_bytes(), first.name


def test_stale_plots_are_removed(tmp_path):
    rows = make_run(seed=0) + make_run(entry="dense", seed=0)
    render_leaderboard(rows, tmp_path, HEADER, reps=REPS)
    other = [{**r, "task": "planshape/Push-v0", "run_id": r["run_id"] + "-push"} for r in rows]
    render_leaderboard(other, tmp_path, HEADER, reps=REPS)
    names = sorted(p.name for p in (tmp_path / "plots").iterdir())
    assert names == ["curves_planshape-Push-v0.png", "final_distance_planshape-Push-v0.png"]


def test_a_single_seed_shows_no_interval(tmp_path):
    rows = make_run(seed=0, final_success=0.6) + make_run(entry="dense", seed=0)
    render_leaderboard(rows, tmp_path, HEADER, reps=REPS)
    text = (tmp_path / "LEADERBOARD.md").read_text()
    assert "| `sparse` | 1 | 0.600 (n=1: no CI) | 0.600 |" in text


@pytest.mark.parametrize(("seeds", "shown"), [(2, False), (4, False), (5, True)])
def test_intervals_are_shown_from_five_seeds_on(tmp_path, seeds, shown):
    """A percentile bootstrap of 2 seeds gives [min, max]: not shown as an interval."""
    rows = []
    for seed in range(seeds):
        rows += make_run(seed=seed, final_success=0.2 * seed)
        rows += make_run(entry="dense", seed=seed, final_success=1.0)
    render_leaderboard(rows, tmp_path, HEADER, reps=REPS)
    text = (tmp_path / "LEADERBOARD.md").read_text()
    line = next(li for li in text.splitlines() if li.startswith("| `sparse` |"))
    assert (f"(n={seeds}: no CI)" not in line) is shown
    assert ("[" in line.split("|")[3]) is shown


def test_the_across_task_table_names_the_tasks_left_out_of_normalization(tmp_path):
    rows = make_run(seed=0, final_success=1.0) + make_run(entry="dense", seed=0, final_success=1.0)
    rows += make_run(entry="plan-based/grid", seed=0, final_success=1.0)
    push = [{**r, "task": "planshape/Push-v0", "run_id": r["run_id"] + "-push"} for r in rows]
    render_leaderboard(rows + push, tmp_path, HEADER, reps=REPS)
    text = (tmp_path / "LEADERBOARD.md").read_text()
    across = text.split("## Across tasks")[1].split("## planshape/")[0]
    assert "Not normalized on (dense no better than sparse)" in across
    assert "Push-v0, Reach-v0" in across  # sparse and dense tie on both


def test_nothing_to_render(tmp_path):
    with pytest.raises(ResultsError, match="no finished runs"):
        render_leaderboard([], tmp_path, HEADER)


def test_summary_table(rows):
    text = summary_table(rows, reps=REPS)
    lines = text.splitlines()
    assert lines[0].split()[:3] == ["task", "algo", "entry"]
    assert "planshape/Push-v0" in text and "plan-based/multi" in text
    reach_ppo = [line for line in lines if line.startswith("planshape/Reach-v0  PPO")]
    assert "plan-based/multi" in reach_ppo[0] and "sparse" in reach_ppo[-1]
    assert summary_table([]) == "no finished runs"


def test_summary_table_and_json_give_each_cells_budget_check(rows, rendered):
    """3 seeds per entry: no cell of the fixture can carry a verdict, and both outputs say so."""
    lines = summary_table(rows, reps=REPS).splitlines()
    checks = [i for i, line in enumerate(lines) if line.startswith("budget check: ")]
    assert len(checks) == 4  # 2 tasks x 2 algorithms, each after its cell's rows
    assert all(lines[i + 1].startswith("shaping outcome: ") for i in checks)
    assert checks[-1] == len(lines) - 2
    assert all("no verdict: some entries have 3 seeds, fewer than 5" in lines[i] for i in checks)
    out, _ = rendered
    data = json.loads((out / "summary.json").read_text())
    assert [(c["task"], c["algo"], c["status"]) for c in data["budget_checks"]] == [
        (task, algo, "no-verdict")
        for task in ("planshape/Push-v0", "planshape/Reach-v0")
        for algo in ("PPO", "SAC")
    ]


def test_policy_videos_in_the_results_folder_appear_beside_their_task(tmp_path):
    import imageio.v3 as iio
    import numpy as np

    rows = make_run(seed=0) + make_run(entry="dense", seed=0)
    videos = tmp_path / "videos"
    videos.mkdir()
    frames = np.zeros((2, 8, 8, 3), np.uint8)
    iio.imwrite(videos / "planshape-Reach-v0__dense__PPO__seed0.gif", frames, duration=80)
    render_leaderboard(rows, tmp_path, HEADER, reps=REPS)
    board = (tmp_path / "LEADERBOARD.md").read_text()
    assert "![planshape/Reach-v0: final policy of dense (PPO, seed0)]" in board
    assert "videos/planshape-Reach-v0__dense__PPO__seed0.gif" in board
    assert "data:image/gif;base64," in (tmp_path / "index.html").read_text()


def test_success_at_any_step_shows_only_where_every_run_recorded_it(tmp_path):
    """Rows that record success at any step (MetaWorld's protocol) get their own column; a cell
    with one run stored before that field existed shows n/a, not a mean of the others."""
    rows = []
    for seed in range(5):
        rows += make_run(seed=seed, final_success=0.0, success_any_rate=0.6)
        rows += make_run(entry="dense", seed=seed, final_success=1.0, success_any_rate=1.0)
    rows += make_run(entry="plan-based/grid", seed=0, final_success=0.2, success_any_rate=0.9)
    rows += make_run(entry="plan-based/grid", seed=1, final_success=0.2)
    render_leaderboard(rows, tmp_path, HEADER, reps=REPS)
    text = (tmp_path / "LEADERBOARD.md").read_text()
    assert "| Mean success | Mean success, any step |" in text
    assert "| `sparse` | 5 | 0.000 [0.000, 0.000] | 0.000 | 0.600 |" in text
    assert "| `plan-based/grid` | 2 | 0.200 (n=2: no CI) | 0.200 | n/a |" in text
    cells = json.loads((tmp_path / "summary.json").read_text())["per_task"]
    assert {c["entry"]: c["success_any_mean"] for c in cells} == {
        "dense": 1.0, "plan-based/grid": None, "sparse": 0.6
    }  # fmt: skip

    older = [{k: v for k, v in r.items() if k != "success_any_rate"} for r in rows]
    render_leaderboard(older, tmp_path, HEADER, reps=REPS)
    assert "any step |" not in (tmp_path / "LEADERBOARD.md").read_text()
