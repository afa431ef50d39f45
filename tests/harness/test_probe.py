"""``planshape probe``: one benchmark run, trained in chunks, with the learner's statistics."""

from __future__ import annotations

import json

import pytest

from planshape.cli import main
from planshape.errors import BadInputError
from planshape.harness.probe import format_rows, probe
from planshape.harness.profiles import RunKey


def test_rows_per_chunk_with_plan_progress_and_critic_fit():
    rows = probe(RunKey("planshape/Reach-v0", "plan-distance/grid", "PPO", 0, 2048), 2, 1)
    assert [row["step"] for row in rows] == [1024, 2048]
    for row in rows:
        # 1024 steps = 128 in each of 8 environments: three 40-step episodes end in each
        assert row["train_episodes"] == 8 * 3
        assert row["plan_length"] == 13  # the reach grid plan: 13 cells to the goal
        assert 0 <= row["progress"] <= 13
        assert 0 < row["train_distance"] < 1 and row["train_success"] == 0.0
        assert row["explained_variance"] is not None and 0 < row["action_std"] <= 1.01
        assert row["eval_success"] in (0.0, 1.0)
    assert format_rows(rows).splitlines()[0].split()[:3] == ["step", "train", "dist"]


def test_unshaped_entries_have_no_progress(capsys):
    assert (
        main(
            [
                "probe",
                "planshape/Reach-v0",
                "dense",
                "--budget",
                "1024",
                "--chunks",
                "1",
                "--episodes",
                "1",
                "--json",
            ]
        )
        == 0
    )
    (row,) = json.loads(capsys.readouterr().out)
    assert row["progress"] is None and row["plan_length"] is None


def test_shaping_scale_replaces_the_tables_and_is_recorded(monkeypatch):
    """The scale reaches the shaping wrappers the learner trains on (not just the row)."""
    from planshape.harness import runner

    seen: list[float] = []
    make = runner.make_training_env

    def spy(key, n_envs, gamma, seed, shaping_scale=1.0, **kwargs):
        seen.append(shaping_scale)
        return make(key, n_envs, gamma, seed, shaping_scale, **kwargs)

    monkeypatch.setattr(runner, "make_training_env", spy)
    key = RunKey("planshape/Reach-v0", "plan-distance/grid", "PPO", 0, 1024)
    (row,) = probe(key, 1, 1, shaping_scale=7.5)
    (default,) = probe(key, 1, 1)
    assert seen == [7.5, 100.0]
    assert row["shaping_scale"] == 7.5 and default["shaping_scale"] == 100.0


def test_chunks_must_fit_the_budget():
    with pytest.raises(BadInputError, match="--chunks must be between 1 and the budget"):
        probe(RunKey("planshape/Reach-v0", "dense", "PPO", 0, 10), chunks=20)


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (
            ["push", "nope"],
            "write sparse, dense or POTENTIAL/MODEL with a model of planshape/Push-v1",
        ),
        (["reach", "foo/grid"], "unknown potential 'foo'"),
        (["rech", "dense"], "unknown task 'rech'"),
        (["reach", "dense", "--algo", "XYZ"], "unknown algorithm 'XYZ'"),
        (["reach", "dense", "--budget", "0"], "--budget and --episodes ≥ 1"),
        (["reach", "dense", "--shaping-scale", "10"], "entry 'dense' has none"),
        (["reach", "plan-distance/grid", "--shaping-scale", "0"], "finite number > 0; got 0.0"),
        (["reach", "plan-distance/grid", "--shaping-scale", "nan"], "finite number > 0"),
    ],
)
def test_bad_probe_input_exits_2_before_training(capsys, argv, message):
    from planshape.cli import main

    assert main(["probe", *argv]) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err


@pytest.mark.parametrize(
    ("key", "eval_every"),
    [
        (RunKey("planshape/Reach-v1", "plan-distance/grid", "PPO", 1, 2048), 1024),
        (RunKey("planshape/Reach-v1", "plan-distance/grid", "SBX-SAC", 1, 1600), 800),
    ],
)
def test_the_probe_trains_the_benchmarks_run(key, eval_every):
    """A curve the probe prints is the curve the benchmark stores for the same run: its chunks
    end where the benchmark evaluates, and the numbers there are the same floats (budgets and
    shaping scales are chosen from probe curves, so they must describe the stored runs)."""
    from planshape.harness.runner import RunSpec, execute

    rows = execute(RunSpec.create(key, "test", eval_every, 1))
    stored = {row["step"]: (row["success_rate"], row["final_distance"]) for row in rows}
    probed = probe(key, chunks=key.budget // eval_every, eval_episodes=1)
    assert [row["step"] for row in probed] == [eval_every * (i + 1) for i in range(len(probed))]
    for row in probed:
        assert stored[row["step"]] == (row["eval_success"], row["eval_distance"]), row["step"]
