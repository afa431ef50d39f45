"""The metaworld-holdout profile: a held-out test of the MetaWorld question, fixed before any of
its runs trained. These tests pin what was fixed (tasks, budget, the one shaped entry and its
settings), so that a change to any of them fails here instead of silently turning the held-out
test into one chosen after its results were seen."""

from __future__ import annotations

from planshape.harness.profiles import (
    METAWORLD_HOLDOUT_PROFILE,
    METAWORLD_PROFILE,
    METAWORLD_PROGRESS_PROFILE,
    PROFILES,
    RunKey,
)

HOLDOUT = METAWORLD_HOLDOUT_PROFILE
FIXED_TASKS = {
    "planshape/MetaWorld-drawer-open-v3",
    "planshape/MetaWorld-push-v3",
    "planshape/MetaWorld-pick-place-v3",
}
SHAPED = "plan-distance-sum/stages"


def test_the_fixed_design_is_unchanged():
    keys = list(HOLDOUT.runs())
    assert PROFILES["metaworld-holdout"] is HOLDOUT
    assert {k.task for k in keys} == FIXED_TASKS
    assert {k.entry for k in keys} == {"sparse", "dense", SHAPED}
    assert {k.algo for k in keys} == {"SBX-SAC"}
    assert {k.budget for k in keys} == {200_000}
    assert {k.seed for k in keys} == set(range(5))
    assert len(keys) == 3 * 3 * 5
    assert (HOLDOUT.eval_every, HOLDOUT.eval_episodes, HOLDOUT.success_measure) == (
        METAWORLD_PROFILE.eval_every,
        METAWORLD_PROFILE.eval_episodes,
        "any-step",
    )


def test_its_tasks_are_none_that_another_sac_metaworld_profile_trains():
    """Held out: no task of it is in a cell another SAC MetaWorld profile has."""
    others = {
        key.task
        for profile in PROFILES.values()
        if profile is not HOLDOUT and "metaworld" in profile.name
        for key in profile.runs()
        if "SAC" in key.algo
    }
    assert others and not FIXED_TASKS & others


def test_its_shaped_runs_train_with_metaworld_progress_settings():
    """The configuration under test is metaworld-progress's: φ × 10 and the plan progress
    observed, the same hyperparameters a metaworld-progress run of the entry has."""
    assert (HOLDOUT.shaping_scale, HOLDOUT.observe_progress) == (
        METAWORLD_PROGRESS_PROFILE.shaping_scale,
        METAWORLD_PROGRESS_PROFILE.observe_progress,
    )
    for task in FIXED_TASKS:
        key = RunKey(task, SHAPED, "SBX-SAC", 0, 200_000)
        settings = HOLDOUT.spec(key).hyperparameters
        assert settings == METAWORLD_PROGRESS_PROFILE.spec(key).hyperparameters
        assert settings["shaping_scale"] == 10 and settings["observe_progress"] is True
        dense = RunKey(task, "dense", "SBX-SAC", 0, 200_000)
        assert "observe_progress" not in HOLDOUT.spec(dense).hyperparameters
        assert HOLDOUT.spec(dense).run_id == METAWORLD_PROFILE.spec(dense).run_id


def test_its_results_have_a_folder_of_their_own():
    assert HOLDOUT.folder == "leaderboard/metaworld-holdout"
    assert all(p.folder != HOLDOUT.folder for p in PROFILES.values() if p is not HOLDOUT)
