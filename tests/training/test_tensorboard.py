"""TensorBoard logging: the learner's and the shaping's scalars reach the event files, and
logging changes neither a run's identity nor its numbers."""

from __future__ import annotations

import pytest

from planshape.cli import main
from planshape.errors import BadInputError
from planshape.harness.profiles import RunKey
from planshape.harness.runner import RunSpec, execute
from planshape.training import tensorboard_logs

KEY = RunKey("planshape/Reach-v1", "plan-distance/grid", "PPO", 1, 2048)
KEEP = ("run_id", "step", "success_rate", "final_distance", "sparse_return")


def scalar_tags(folder) -> set[str]:
    from tensorboard.backend.event_processing.event_accumulator import EventAccumulator

    events = EventAccumulator(str(folder))
    events.Reload()
    return set(events.Tags()["scalars"])


def test_logging_changes_no_number_and_writes_the_shaping_scalars(tmp_path):
    spec = RunSpec.create(KEY, "test", eval_every=1024, eval_episodes=1)
    plain = execute(spec)
    logged = execute(spec, str(tmp_path))
    assert [{k: r[k] for k in KEEP} for r in logged] == [{k: r[k] for k in KEEP} for r in plain]
    tags = scalar_tags(tensorboard_logs.log_folder(tmp_path, KEY))
    expected = {
        "shaping/shaped_return",
        "shaping/task_return",
        "shaping/final_progress",
        "shaping/phi_start",
        "shaping/phi_end",
        "eval/success_rate",
        "eval/final_distance",
        "rollout/ep_rew_mean",
        "train/explained_variance",
    }
    assert expected <= tags, expected - tags


def test_probe_logs_too(tmp_path, capsys):
    probe = ["probe", "reach", "sparse", "--budget", "1024", "--chunks", "1", "--episodes", "1"]
    status = main([*probe, "--tensorboard", str(tmp_path), "--json"])
    assert status == 0
    key = RunKey("planshape/Reach-v1", "sparse", "PPO", 0, 1024)
    assert {"eval/success_rate", "rollout/ep_rew_mean"} <= scalar_tags(
        tensorboard_logs.log_folder(tmp_path, key)
    )


def test_without_the_package_the_option_is_a_clear_error(monkeypatch, tmp_path, capsys):
    monkeypatch.setattr(tensorboard_logs.importlib.util, "find_spec", lambda name: None)
    with pytest.raises(BadInputError, match=r"pip install 'planshape\[tensorboard\]'"):
        tensorboard_logs.require_tensorboard()
    out = tmp_path / "results"
    assert main(["bench", "--profile", "smoke", "--out", str(out), "--tensorboard", "tb"]) == 2
    assert "planshape[tensorboard]" in capsys.readouterr().err
    assert not out.exists()
