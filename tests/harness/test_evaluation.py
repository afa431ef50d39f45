"""Evaluation protocol 2: which episodes an evaluation point runs, the step it is recorded at,
and the stored results it must not mix with (ARCHITECTURE correctness rules 5 and 6)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

import planshape
from planshape.cli import main
from planshape.harness.profiles import PROFILES, RunKey
from planshape.harness.runner import (
    EVAL_PROTOCOL,
    EVAL_SEED_OFFSET,
    RunSpec,
    evaluate,
    evaluation_episodes,
    execute,
    make_evaluation_env,
    make_learner,
)

ROOT = Path(__file__).resolve().parents[2]


def test_a_fixed_task_is_evaluated_once_and_a_distribution_on_its_held_out_instances():
    assert evaluation_episodes("planshape/Push-v1", 10) == [{"seed": EVAL_SEED_OFFSET}]
    held_out = evaluation_episodes("planshape/PushRandomized-v1", 10)
    assert [e["options"]["instance"] for e in held_out] == list(range(50))
    seeded = evaluation_episodes("planshape/MetaWorld-reach-v4", 3)
    assert [e["seed"] for e in seeded] == [EVAL_SEED_OFFSET + i for i in range(3)]


def test_the_evaluation_env_of_a_distribution_is_its_held_out_set():
    key = RunKey("planshape/ReachRandomized-v1", "sparse", "PPO", 0, 1024)
    env = make_evaluation_env(key, {})
    _, info = env.reset(options={"instance": 0})
    assert info["instance"] == planshape.tasks.planar.instances.instance_set("reach").eval[0]


def test_a_point_is_recorded_at_the_steps_its_policy_was_trained_on():
    """The point recorded at step 1024 (PPO: 8 environments × 128 steps per rollout) evaluates
    the policy after exactly one update: a learner trained for 1024 steps on its own gives the
    same numbers."""
    key = RunKey("planshape/Reach-v1", "plan-distance/grid", "PPO", 0, 2048)
    spec = RunSpec.create(key, "test", eval_every=1024, eval_episodes=1)
    rows = execute(spec)
    assert [r["step"] for r in rows] == [0, 1024, 2048]
    assert rows[0]["eval_protocol"] == EVAL_PROTOCOL and rows[0]["eval_episodes"] == 1
    alone = make_learner(key, spec.hyperparameters)
    alone.learn(1024)
    scores = evaluate(alone, make_evaluation_env(key, spec.hyperparameters), spec.episodes)
    assert scores["final_distance"] == rows[1]["final_distance"]
    assert scores["success_rate"] == rows[1]["success_rate"]


@pytest.mark.parametrize(
    ("profile", "folder"), [("default-v0", "default-v0"), ("metaworld-v0", "metaworld-v0")]
)
def test_stored_run_ids_are_reproduced_by_their_archived_profile(profile: str, folder: str):
    """Every run stored with protocol 1 is found again under its id: the identity hashing of
    protocol-1 runs did not change with protocol 2 (a code change that does not change a run's
    numbers must not change its id)."""
    runs = ROOT / PROFILES[profile].folder / "runs"
    stored = {path.stem for path in runs.glob("*.jsonl")}
    assert stored, f"no stored runs in {runs}"
    p = PROFILES[profile]
    ids = {
        RunSpec.create(key, p.name, p.eval_every, p.eval_episodes, eval_protocol=1).run_id
        for key in p.runs()
    }
    assert stored == ids
    first = json.loads((runs / f"{min(stored)}.jsonl").read_text().splitlines()[0])
    assert "eval_protocol" not in first  # protocol 1 rows predate the field


def test_protocol_2_changes_the_id_of_what_it_evaluates_differently():
    key = RunKey("planshape/Reach-v0", "sparse", "PPO", 0, 1024)
    old = RunSpec.create(key, "x", 512, 10, eval_protocol=1)
    new = RunSpec.create(key, "x", 512, 10)
    assert old.run_id != new.run_id
    # a fixed task runs one episode whatever the profile's eval_episodes: the same run
    assert RunSpec.create(key, "x", 512, 3).run_id == new.run_id


def test_archived_profiles_and_foreign_results_are_refused_before_training(tmp_path, capsys):
    assert main(["bench", "--profile", "default-v0", "--out", str(tmp_path)]) == 2
    assert "archived" in capsys.readouterr().err
    runs = tmp_path / "runs"
    runs.mkdir()
    stored = next((ROOT / "leaderboard/default-v0/runs").glob("*.jsonl"))  # a whole stored run
    shutil.copy(stored, runs / stored.name)
    before = sorted(p.name for p in tmp_path.rglob("*"))
    assert main(["bench", "--profile", "smoke", "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "holds runs of profile 'default' evaluated with protocol 1" in err
    assert "Traceback" not in err
    assert sorted(p.name for p in tmp_path.rglob("*")) == before  # nothing written


def test_a_distribution_run_trains_on_its_instances_and_scores_the_held_out_ones():
    key = RunKey("planshape/ReachRandomized-v1", "plan-based/grid", "PPO", 0, 1024)
    rows = execute(RunSpec.create(key, "test", eval_every=1024, eval_episodes=3))
    assert {r["eval_episodes"] for r in rows} == {50}
    assert all(r["success_rate"] * 50 == round(r["success_rate"] * 50) for r in rows)
    assert "held-out instances" in rows[0]["evaluation"]


def test_a_short_task_name_means_its_newest_version():
    from planshape.suite.session import resolve_tasks

    assert resolve_tasks("reach,maze-reach,metaworld-reach") == [
        "planshape/Reach-v1",
        "planshape/MazeReach-v1",
        "planshape/MetaWorld-reach-v4",
    ]
    assert resolve_tasks("planshape/Reach-v0") == ["planshape/Reach-v0"]


def test_dry_run_prints_the_selection_and_its_estimate_and_writes_nothing(tmp_path, capsys):
    out = tmp_path / "results"
    assert main(["bench", "--tasks", "reach,push", "--dry-run", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "planshape/Reach-v1" in printed and "planshape/Push-v1" in printed
    assert "40 runs; estimated wall time" in printed  # 25 PPO reach + 15 SBX-SAC push runs
    assert not out.exists()


@pytest.mark.parametrize(
    "expression", ["MazeReach and (sparse or dense) or Push and plan-distance", "not PPO", "seed3"]
)
def test_dry_run_selects_with_k_exactly_what_the_suite_collects(tmp_path, expression):
    """``--dry-run -k`` applies pytest's keyword matching itself; it must pick the very items
    the suite collects with the same ``-k`` (checked against a real collection)."""
    import subprocess
    import sys

    from planshape.harness.bench import SUITE, selected_by
    from planshape.suite.session import BenchSession

    collected = subprocess.run(
        [sys.executable, "-m", "pytest", str(SUITE), "--import-mode=importlib", "-p",
         "no:cacheprovider", "-o", "addopts=", "-q", "--profile", "default", "--out",
         str(tmp_path), "--executor", "local", "-k", expression, "--collect-only"],
        capture_output=True, text=True, check=False,
    ).stdout  # fmt: skip
    ids = {line.split("[", 1)[1].rstrip("]") for line in collected.splitlines() if "[" in line}
    keys = list(PROFILES["default"].runs())
    chosen = {BenchSession.item_id(k) for k in keys if selected_by(expression, k)}
    assert ids and chosen == ids


def test_dry_run_refuses_a_k_that_is_not_an_expression(capsys):
    assert main(["bench", "--dry-run", "-k", "(", "--out", "/nonexistent/x"]) == 2
    assert "-k '(' is not a pytest -k expression" in capsys.readouterr().err


class _ExpertThenAway:
    """MetaWorld's scripted expert for ``leave_at`` steps of each episode, then full speed up and
    away: a policy whose episodes succeed on the way and fail at their end."""

    def __init__(self, env_name: str, leave_at: int) -> None:
        from metaworld.policies import ENV_POLICY_MAP

        self.expert, self.leave_at, self.t = ENV_POLICY_MAP[env_name](), leave_at, 0

    def predict(self, obs, deterministic=True):
        step_of_episode, self.t = self.t % 500, self.t + 1  # MetaWorld's episodes: 500 steps
        if step_of_episode >= self.leave_at:
            return [0.0, -1.0, 1.0, 0.0], None
        return self.expert.get_action(obs.copy()), None


def test_success_at_any_step_is_recorded_beside_success_at_the_end():
    """MetaWorld never terminates on success: an episode can pass through it and end elsewhere.
    The end-of-episode rate misses those, the any-step rate (MetaWorld's protocol) counts them."""
    import gymnasium

    task = "planshape/MetaWorld-reach-v4"
    env = gymnasium.make(task, reward="sparse")
    env_name = env.unwrapped.spec.kwargs["env_name"]
    stays = evaluate(_ExpertThenAway(env_name, leave_at=500), env, 2)
    leaves = evaluate(_ExpertThenAway(env_name, leave_at=150), env, 2)
    assert stays["success_rate"] == stays["success_any_rate"] == 1.0
    assert leaves["success_any_rate"] == 1.0 and leaves["success_rate"] == 0.0
    assert leaves["final_distance"] > 0.05 > stays["final_distance"]
