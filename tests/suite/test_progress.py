"""The benchmark's progress report: the time left is weighted by cost (stored runs and the
order of cheap and dear runs do not distort it), the session's bar counts runs, and a run's own
bar over its training steps changes none of its numbers."""

from __future__ import annotations

import io

from planshape.harness.bench import pytest_arguments
from planshape.harness.profiles import RunKey
from planshape.harness.runner import RunSpec, execute
from planshape.suite.progress import BenchProgress, TimeLeft


class Terminal(io.StringIO):
    """A stream that says it is a terminal, as tqdm asks before it draws."""

    def isatty(self) -> bool:
        return True


def test_stored_runs_leave_the_estimate_as_it_was():
    cost = {"stored-1": 0.0, "stored-2": 0.0, "ppo": 10.0, "sac": 100.0}
    left = TimeLeft(cost, workers=1)
    assert left.before_any_run() == 110.0
    # two stored runs found at once: a count-based ETA would now say 2 runs in no time
    assert left.finished("stored-1", elapsed=0.0, stored=True) == 110.0
    assert left.finished("stored-2", elapsed=0.0, stored=True) == 110.0
    # the cheap run took twice its estimate: the dear one is expected to, too
    assert left.finished("ppo", elapsed=20.0, stored=False) == 200.0
    assert left.finished("sac", elapsed=240.0, stored=False) == 0.0


def test_the_order_of_cheap_and_dear_runs_does_not_change_the_rate():
    cheap_first = TimeLeft({"a": 10.0, "b": 100.0, "c": 100.0})
    dear_first = TimeLeft({"a": 10.0, "b": 100.0, "c": 100.0})
    # the machine runs at half the estimated speed either way
    assert cheap_first.finished("a", elapsed=20.0, stored=False) == 400.0
    assert dear_first.finished("b", elapsed=200.0, stored=False) == 220.0


def test_the_session_bar_counts_runs_and_shows_the_cost_weighted_time_left():
    screen = Terminal()
    progress = BenchProgress({"a": 0.0, "b": 30.0}, workers=1, file=screen)
    assert not progress.bar.disable  # on a terminal it draws
    first = progress.finished("a", "stored", elapsed=0.5, stored=True)
    second = progress.finished("b", "done", elapsed=60.5, stored=False)
    progress.close()
    assert first == "[1/2] stored  a  elapsed 0m00s, about 0m30s left"
    assert second == "[2/2] done    b  elapsed 1m00s, about 0m00s left"
    drawn = screen.getvalue()
    assert "planshape bench 2/2 runs" in drawn and "about 0m00s left" in drawn


def test_off_a_terminal_there_is_no_bar_only_the_lines():
    log = io.StringIO()
    progress = BenchProgress({"a": 1.0}, file=log)
    line = progress.finished("a", "done", elapsed=1.0, stored=False)
    progress.close()
    assert line.startswith("[1/1] done") and log.getvalue() == ""


def test_a_single_worker_session_lets_the_run_bar_reach_the_terminal(tmp_path):
    import argparse

    args = argparse.Namespace(
        profile="smoke", out=tmp_path, executor="local", potential=[], tasks=None, seeds=None,
        address=None, tensorboard=None, k=None, no_render=True, workers=1,
    )  # fmt: skip
    assert "--capture=no" in pytest_arguments(args)
    args.workers = 2  # a pool: the workers' output is not shown, their capture stays
    assert "--capture=no" not in pytest_arguments(args)


def test_the_run_bar_changes_no_number(monkeypatch):
    key = RunKey("planshape/Reach-v1", "plan-distance/grid", "PPO", 1, 2048)
    spec = RunSpec.create(key, "test", eval_every=1024, eval_episodes=1)
    plain = execute(spec)
    screen = Terminal()
    monkeypatch.setattr("sys.stderr", screen)
    shown = execute(spec, progress=True)
    assert "Reach-v1 plan-distance/grid PPO seed1" in screen.getvalue()  # the bar was drawn
    keep = ("run_id", "step", "success_rate", "final_distance", "sparse_return", "hyperparameters")
    assert [{k: r[k] for k in keep} for r in shown] == [{k: r[k] for k in keep} for r in plain]
