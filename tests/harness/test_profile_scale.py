"""A profile's own shaping scale (``Profile.shaping_scale``): the metaworld-s10 profile runs the
metaworld profile's cells with φ scaled by 10. Its shaped runs are new runs with ids of their
own; its sparse and dense runs are the metaworld profile's, so they are adopted, not trained,
and neither profile's stored runs mix into the other's cells."""

from __future__ import annotations

import pytest

from planshape.errors import BadInputError
from planshape.harness.adopt import adopt
from planshape.harness.bench import check_store
from planshape.harness.profiles import (
    METAWORLD_PROFILE,
    METAWORLD_PROGRESS_PROFILE,
    METAWORLD_S10_PROFILE,
    PROFILES,
    RunKey,
)
from planshape.harness.runner import RunSpec
from planshape.harness.store import ResultStore
from planshape.training.hyperparams import SAC_SHAPING_SCALE, SHAPING_SCALE
from tests.results.synthetic import store_run

TASK = "planshape/MetaWorld-button-press-v3"
ALGO = "SBX-SAC"
BUDGET = METAWORLD_PROFILE.budgets()[(TASK, ALGO)]
SHAPED = "plan-distance-sum/stages"


def _key(entry: str, seed: int = 0) -> RunKey:
    return RunKey(TASK, entry, ALGO, seed, BUDGET)


def test_the_s10_profile_has_the_metaworld_profiles_runs_and_scores_them_alike():
    s10, metaworld = METAWORLD_S10_PROFILE, METAWORLD_PROFILE
    assert PROFILES["metaworld-s10"] is s10
    assert list(s10.runs()) == list(metaworld.runs())
    assert (s10.eval_every, s10.eval_episodes, s10.success_measure) == (
        metaworld.eval_every,
        metaworld.eval_episodes,
        metaworld.success_measure,
    )
    assert s10.folder == "leaderboard/metaworld-s10" != metaworld.folder
    assert (s10.shaping_scale, metaworld.shaping_scale) == (SAC_SHAPING_SCALE, None)


@pytest.mark.parametrize("entry", ["sparse", "dense"])
def test_unshaped_runs_are_the_same_runs_in_both_profiles(entry):
    ours, theirs = METAWORLD_S10_PROFILE.spec(_key(entry)), METAWORLD_PROFILE.spec(_key(entry))
    assert ours.run_id == theirs.run_id
    assert ours.hyperparameters == theirs.hyperparameters
    assert ours.hyperparameters["shaping_scale"] == SHAPING_SCALE


def test_a_shaped_run_trains_at_the_profiles_scale_under_an_id_of_its_own():
    ours, theirs = METAWORLD_S10_PROFILE.spec(_key(SHAPED)), METAWORLD_PROFILE.spec(_key(SHAPED))
    assert ours.hyperparameters["shaping_scale"] == SAC_SHAPING_SCALE
    assert theirs.hyperparameters["shaping_scale"] == SHAPING_SCALE
    assert ours.run_id != theirs.run_id
    assert {k: v for k, v in ours.hyperparameters.items() if k != "shaping_scale"} == {
        k: v for k, v in theirs.hyperparameters.items() if k != "shaping_scale"
    }
    # the profile's spec is the one a run created by hand with the same scale has
    created = RunSpec.create(
        _key(SHAPED), "metaworld-s10", 20_000, 10, shaping_scale=SAC_SHAPING_SCALE
    )
    assert created.run_id == ours.run_id


def test_each_profile_shows_the_others_unshaped_rows_and_not_its_shaped_ones():
    s10, metaworld = METAWORLD_S10_PROFILE, METAWORLD_PROFILE
    for profile in (s10, metaworld):
        spec = profile.spec(_key(SHAPED))
        shaped = {
            "task": TASK,
            "entry": SHAPED,
            "algo": ALGO,
            "budget": BUDGET,
            "hyperparameters": spec.hyperparameters,
        }
        dense = shaped | {
            "entry": "dense",
            "hyperparameters": profile.spec(_key("dense")).hyperparameters,
        }
        other = metaworld if profile is s10 else s10
        assert profile.shows(shaped) and not other.shows(shaped)
        assert profile.shows(dense) and other.shows(dense)


def test_a_s10_folder_starts_from_metaworlds_unshaped_runs_and_refuses_its_shaped_ones(tmp_path):
    """check_store, which every bench runs before training: the metaworld profile's dense run
    is one of metaworld-s10's runs (the same id); its shaped run, trained at 100, is not, and
    metaworld still shows it, so new runs at 10 would mix into a folder of runs at 100."""
    dense_id = store_run(tmp_path, _key("dense"), METAWORLD_PROFILE)
    check_store(tmp_path, METAWORLD_S10_PROFILE)
    assert ResultStore(tmp_path).has(METAWORLD_S10_PROFILE.spec(_key("dense")).run_id)
    assert dense_id == METAWORLD_S10_PROFILE.spec(_key("dense")).run_id
    store_run(tmp_path, _key(SHAPED), METAWORLD_PROFILE)
    with pytest.raises(BadInputError, match="holds runs of profile 'metaworld'"):
        check_store(tmp_path, METAWORLD_S10_PROFILE)


def test_adopt_takes_metaworlds_dense_runs_into_the_s10_store_and_refuses_its_shaped_ones(
    tmp_path,
):
    stored, scratch = tmp_path / "stored", tmp_path / "scratch"
    dense_id = store_run(scratch, _key("dense"), METAWORLD_PROFILE)
    plan = adopt(scratch, stored, METAWORLD_S10_PROFILE)
    assert [p.stem for p in plan.added] == [dense_id]
    before = sorted(p.name for p in (stored / "runs").glob("*"))
    store_run(scratch, _key(SHAPED), METAWORLD_PROFILE)
    with pytest.raises(BadInputError, match="is not a run of the 'metaworld-s10' profile"):
        adopt(scratch, stored, METAWORLD_S10_PROFILE)
    assert sorted(p.name for p in (stored / "runs").glob("*")) == before


@pytest.mark.parametrize("profile", [METAWORLD_S10_PROFILE, METAWORLD_PROGRESS_PROFILE], ids=str)
def test_every_committed_run_is_one_of_its_runs_and_its_unshaped_runs_are_metaworlds(profile):
    """The committed folders of the profiles derived from metaworld: each run's id is the one
    its profile gives it now (a code change that leaves the numbers must leave the ids), with
    the profile's settings (so metaworld-progress's shaped runs observed their progress),
    shaped runs trained at 10, and every sparse and dense file is the metaworld profile's file
    byte for byte (adopted, not retrained)."""
    import json
    from pathlib import Path

    root = Path(__file__).resolve().parents[2] / "leaderboard"
    ours = root / profile.name / "runs"
    paths = sorted(ours.glob("*.jsonl"))
    assert paths, f"no committed runs in {ours}"
    planned = set(profile.runs())
    for path in paths:
        first = json.loads(path.read_text().split("\n", 1)[0])
        key = RunKey(first["task"], first["entry"], first["algo"], first["seed"], first["budget"])
        assert key in planned, path.name
        spec = profile.spec(key)
        assert spec.run_id == path.stem and spec.hyperparameters == first["hyperparameters"]
        if key.reward == "shaped":
            assert first["hyperparameters"]["shaping_scale"] == SAC_SHAPING_SCALE, path.name
            observed = first["hyperparameters"].get("observe_progress", False)
            assert observed == profile.observe_progress, path.name
        else:
            theirs = root / "metaworld" / "runs" / path.name
            assert theirs.read_bytes() == path.read_bytes(), path.name
