"""The benchmark's helper scripts and provenance: the speed scripts run end to end on tiny
inputs (their figures are not asserted: speed goals are read from their output, never timed in
tests), and the code version a run records."""

from __future__ import annotations

import math

import pytest

from planshape.perf import shaping as perf_shaping
from planshape.perf import training as perf_training


def test_training_throughput_script_trains_a_shaped_learner():
    rate = perf_training.steps_per_second("planshape/Reach-v0", "plan-based/grid", "PPO", 1024)
    assert math.isfinite(rate) and rate > 0


def test_shaping_overhead_script_measures_a_planar_task():
    row = perf_shaping.measure("planshape/Reach-v0", "plan-based", "grid", steps=200, repeats=1)
    assert row["task"] == "planshape/Reach-v0"


def test_code_version_ignores_the_benchmarks_own_results(tmp_path, monkeypatch):
    """Results written under leaderboard/ do not mark the code -dirty; a code change does."""
    import subprocess

    from planshape.harness.runner import code_version

    def git(*args):
        subprocess.run(["git", *args], cwd=tmp_path, check=True, capture_output=True)

    git("init", "-q")
    (tmp_path / "leaderboard").mkdir()
    (tmp_path / "leaderboard" / "run.jsonl").write_text("{}\n")
    (tmp_path / "code.py").write_text("x = 1\n")
    git("add", ".")
    git("-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "init")
    monkeypatch.chdir(tmp_path)
    (tmp_path / "leaderboard" / "run.jsonl").write_text("{}\n{}\n")
    code_version.cache_clear()  # cached per process
    assert not code_version().endswith("-dirty")
    (tmp_path / "code.py").write_text("x = 2\n")
    code_version.cache_clear()
    assert code_version().endswith("-dirty")
    code_version.cache_clear()


@pytest.mark.parametrize(("option", "value"), [("--task", "planshape/Nope-v1"), ("--algo", "DQN")])
def test_training_throughput_script_refuses_what_it_does_not_measure(capsys, option, value):
    with pytest.raises(SystemExit) as stop:
        perf_training.main([option, value])
    assert stop.value.code == 2
    assert f"{option} {value}: not measured here" in capsys.readouterr().err


def test_shaping_overhead_on_either_clock_is_a_positive_time():
    for clock in ("thread", "wall"):
        row = perf_shaping.measure("planshape/Reach-v1", "goal-distance", "grid", 100, 1, clock)
        assert row["plain_us"] > 0 and row["shaped_us"] > 0


def test_training_throughput_rows_carry_the_ratio_the_shaping_step_implies(monkeypatch):
    """by_step = 1 / (1 + Δ · sparse rate), Δ the shaping step's cost (fixed here, so that no
    timing is asserted): 1 for sparse, and the render shows it beside the timed ratio."""
    monkeypatch.setattr(
        perf_training, "step_overhead", lambda task, entry: 2e-6 * (entry != "sparse")
    )
    case = ("planshape/Reach-v1", ("PPO",), ("sparse", "plan-based/grid"))
    sparse, shaped = rows = perf_training.measure(1024, 1, [case])
    assert sparse["by_step"] == 1.0
    assert shaped["by_step"] == 1 / (1 + 2e-6 * sparse["steps_per_s"])
    assert "by step" in perf_training.render(rows)


def test_the_shaping_step_overhead_is_read_off_the_shaping_measurement():
    assert perf_training.step_overhead("planshape/Reach-v1", "sparse") == 0.0
    assert math.isfinite(perf_training.step_overhead("planshape/Reach-v1", "plan-based/grid"))


def test_a_run_records_the_code_version_it_started_with(monkeypatch):
    """A run records the checkout as it starts training: an edit or a commit while it trains
    (runs take an hour on MetaWorld) does not relabel the code it ran."""
    from planshape.harness import runner
    from planshape.harness.profiles import RunKey

    evaluated = []
    real_evaluate = runner.evaluate

    def evaluate(*args, **kwargs):
        evaluated.append(True)
        return real_evaluate(*args, **kwargs)

    monkeypatch.setattr(runner, "evaluate", evaluate)
    monkeypatch.setattr(runner, "code_version", lambda: "edited" if evaluated else "started")
    key = RunKey("planshape/Reach-v1", "sparse", "PPO", 0, 1024)
    rows = runner.execute(runner.RunSpec.create(key, "test", eval_every=1024, eval_episodes=1))
    assert {r["code_version"] for r in rows} == {"started"}
