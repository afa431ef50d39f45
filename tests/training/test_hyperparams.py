"""The hyperparameter tables: typed, documented dataclasses whose serialisation is exactly what
the stored runs recorded, so that their run ids do not change."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import pytest

from planshape.harness.profiles import PROFILES, RunKey
from planshape.harness.runner import RunSpec
from planshape.training import hyperparams
from planshape.training.hyperparams import (
    PPOSettings,
    SACSettings,
    Settings,
    hyperparameters,
)

ROOT = Path(__file__).resolve().parents[2]
#: the committed folders of protocol-2 runs (the archived v0 profiles are checked by
#: tests/harness/test_evaluation.py with protocol 1)
FOLDERS = ("leaderboard/runs", "leaderboard/planar/runs")


@pytest.mark.parametrize("table", [Settings, PPOSettings, SACSettings])
def test_every_setting_is_documented(table):
    for setting in dataclasses.fields(table):
        assert setting.metadata.get("doc"), f"{table.__name__}.{setting.name} has no doc"


def test_every_table_is_a_typed_settings_object():
    assert hyperparams.TABLE and hyperparams.TASK_TABLE
    for settings in (*hyperparams.TABLE.values(), *hyperparams.TASK_TABLE.values()):
        assert isinstance(settings, Settings)
    ppo = hyperparams.PPO_PLANAR.as_dict()
    ppo["n_steps"] = 1  # a fresh copy: the table itself is never changed
    assert hyperparams.PPO_PLANAR.n_steps == 128
    assert hyperparams.SAC_DEFAULT.as_dict() == {"n_envs": 1, "gamma": 0.99, "shaping_scale": 10.0}


def _first_rows() -> list[tuple[Path, dict]]:
    rows = []
    for folder in FOLDERS:
        for path in sorted((ROOT / folder).glob("*.jsonl")):
            rows.append((path, json.loads(path.read_text().split("\n", 1)[0])))
    return rows


def test_the_tables_give_every_stored_run_its_settings_and_its_id():
    """Every stored run's id is the hash of its spec, and its settings are the tables' — but
    for the shaped SAC runs trained before SAC's tables got a shaping scale of their own
    (SAC_SHAPING_SCALE), which differ in that one setting, the rule's scale, and are kept
    (out of the leaderboards' cells: tests/harness/test_bench.py)."""
    rows = _first_rows()
    assert len(rows) >= 300
    before_sac_scale = 0
    for path, row in rows:
        profile = PROFILES[row["profile"]]
        key = RunKey(row["task"], row["entry"], row["algo"], row["seed"], row["budget"])
        now, recorded = hyperparameters(key.task, key.algo, key.entry), row["hyperparameters"]
        if recorded != now:
            assert key.reward == "shaped" and "SAC" in key.algo, path.name
            assert now["shaping_scale"] == hyperparams.SAC_SHAPING_SCALE, path.name
            assert recorded == {**now, "shaping_scale": hyperparams.SHAPING_SCALE}, path.name
            before_sac_scale += 1
        spec = RunSpec(key, profile.name, profile.eval_every, profile.eval_episodes, recorded)
        assert spec.run_id == row["run_id"] == path.stem, path.name
        if recorded == now:
            created = RunSpec.create(key, profile.name, profile.eval_every, profile.eval_episodes)
            assert created.run_id == spec.run_id, path.name
    assert before_sac_scale < len(rows) / 2


def test_a_tables_shaping_scale_changes_the_shaped_runs_ids_only(monkeypatch):
    """Sparse and dense runs ignore the scale: giving a table a scale of its own must leave
    their ids (and so their stored runs) as they are, and give every shaped run a new one."""

    def ids() -> dict[str, str]:
        return {
            entry: RunSpec.create(
                RunKey("planshape/Reach-v1", entry, "SBX-SAC", 0, 100_000), "planar", 10_000, 10
            ).run_id
            for entry in ("sparse", "dense", "plan-distance/grid")
        }

    before = ids()
    table = hyperparams.TABLE[("Reach", "SAC")]
    monkeypatch.setitem(hyperparams.TABLE, ("Reach", "SAC"), table.replace(shaping_scale=3.0))
    after = ids()
    assert after["sparse"] == before["sparse"] and after["dense"] == before["dense"]
    assert after["plan-distance/grid"] != before["plan-distance/grid"]
    shaped = hyperparameters("planshape/Reach-v1", "SBX-SAC", "plan-distance/grid")
    assert shaped["shaping_scale"] == 3.0
    assert hyperparameters("planshape/Reach-v1", "SBX-SAC", "sparse")["shaping_scale"] == 100.0


def test_sac_on_the_planar_tasks_scales_phi_by_its_own_scale_and_ppo_by_the_rule():
    scale = lambda task, algo: hyperparameters(task, algo, "plan-distance/grid")["shaping_scale"]  # noqa: E731
    for task in ("planshape/Reach-v1", "planshape/Push-v1", "planshape/MazeReachRandomized-v1"):
        assert scale(task, "SBX-SAC") == scale(task, "SAC") == scale(task, "SAC-default") == 10.0
        assert scale(task, "PPO") == 100.0
    assert scale("planshape/Push-v0", "SAC") == 100.0  # the v0 tasks' stored runs
    for task in ("planshape/MetaWorld-reach-v4", "planshape/PointMaze_UMaze-v3"):
        assert scale(task, "SBX-SAC") == scale(task, "PPO") == 100.0  # the rule's, see the docs
