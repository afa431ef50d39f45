"""A profile whose shaped runs' learners observe their plan progress
(``Profile.observe_progress``): metaworld-progress is metaworld-s10 with that setting. Its
shaped runs have ids of their own; its sparse and dense runs are the metaworld profile's; no
stored run of one profile enters another's cells."""

from __future__ import annotations

import pytest

from planshape.errors import BadInputError
from planshape.harness.bench import check_store
from planshape.harness.profiles import (
    METAWORLD_PROFILE,
    METAWORLD_PROGRESS_PROFILE,
    METAWORLD_S10_PROFILE,
    PROFILES,
    RunKey,
)
from planshape.training.hyperparams import SAC_SHAPING_SCALE
from tests.results.synthetic import store_run

TASK = "planshape/MetaWorld-button-press-v3"
ALGO = "SBX-SAC"
BUDGET = METAWORLD_PROFILE.budgets()[(TASK, ALGO)]
SHAPED = "plan-distance-sum/stages"
PROGRESS, S10 = METAWORLD_PROGRESS_PROFILE, METAWORLD_S10_PROFILE


def _key(entry: str, seed: int = 0) -> RunKey:
    return RunKey(TASK, entry, ALGO, seed, BUDGET)


def test_the_profile_is_s10s_cells_with_the_progress_observed():
    assert PROFILES["metaworld-progress"] is PROGRESS
    assert list(PROGRESS.runs()) == list(S10.runs())
    assert (PROGRESS.shaping_scale, PROGRESS.observe_progress) == (SAC_SHAPING_SCALE, True)
    assert not S10.observe_progress and not METAWORLD_PROFILE.observe_progress
    assert PROGRESS.folder == "leaderboard/metaworld-progress"


@pytest.mark.parametrize("entry", ["sparse", "dense"])
def test_unshaped_runs_are_the_metaworld_profiles_runs(entry):
    assert PROGRESS.spec(_key(entry)).run_id == METAWORLD_PROFILE.spec(_key(entry)).run_id


def test_a_shaped_run_differs_from_s10s_by_the_setting_only():
    ours, theirs = PROGRESS.spec(_key(SHAPED)), S10.spec(_key(SHAPED))
    assert ours.hyperparameters == {**theirs.hyperparameters, "observe_progress": True}
    assert ours.run_id != theirs.run_id


def test_neither_profile_shows_the_others_shaped_rows():
    def row(profile, entry):
        return {
            "task": TASK,
            "entry": entry,
            "algo": ALGO,
            "budget": BUDGET,
            "hyperparameters": profile.spec(_key(entry)).hyperparameters,
        }

    for profile, other in ((PROGRESS, S10), (S10, PROGRESS)):
        assert profile.shows(row(profile, SHAPED)) and not other.shows(row(profile, SHAPED))
        assert other.shows(row(profile, "dense"))


def test_a_progress_folder_refuses_s10s_shaped_runs(tmp_path):
    store_run(tmp_path, _key("dense"), METAWORLD_PROFILE)
    check_store(tmp_path, PROGRESS)
    store_run(tmp_path, _key(SHAPED), S10)
    with pytest.raises(BadInputError, match="holds runs of profile 'metaworld-s10'"):
        check_store(tmp_path, PROGRESS)
