"""`planshape render`: one run trained as its profile trains it, its deterministic policy
rendered as a GIF with the plan's subgoals drawn, named so the leaderboard finds it."""

from __future__ import annotations

import imageio.v3 as iio
import numpy as np

from planshape.cli import main
from planshape.tasks.planar.render import MARK


def test_render_writes_the_policy_of_the_stored_spec(tmp_path, capsys):
    assert (
        main(["render", "reach", "plan-based/multi", "--profile", "smoke", "--out", str(tmp_path)])
        == 0
    )
    path = tmp_path / "videos" / "planshape-Reach-v1__plan-based-multi__PPO__seed0.gif"
    assert f"wrote {path}" in capsys.readouterr().out
    frames = iio.imread(path, index=None)
    assert frames.shape[0] >= 2  # identical consecutive frames are merged by the GIF writer
    assert (np.abs(frames[0].astype(int) - MARK).sum(axis=-1) < 30).any()  # subgoals drawn


def test_render_refuses_a_run_its_profile_does_not_have(tmp_path, capsys):
    assert main(["render", "push", "dense", "--profile", "smoke", "--out", str(tmp_path)]) == 2
    assert "has no budget for planshape/Push-v1 with PPO" in capsys.readouterr().err


def test_render_checks_its_run_as_probe_does(tmp_path, capsys):
    assert main(["render", "reach", "nope", "--profile", "smoke", "--out", str(tmp_path)]) == 2
    assert "entry 'nope': write sparse, dense or POTENTIAL/MODEL" in capsys.readouterr().err
    assert not (tmp_path / "videos").exists()
