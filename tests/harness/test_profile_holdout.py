"""The metaworld-holdout profile: a held-out test of the MetaWorld question, fixed before any of
its runs trained. These tests pin what was fixed (tasks, budget, the one shaped entry and its
settings), so that a change to any of them fails here instead of silently turning the held-out
test into one chosen after its results were seen."""

from __future__ import annotations

from planshape.harness.profiles import (
    METAWORLD_HOLDOUT_CANDIDATES,
    METAWORLD_HOLDOUT_PROFILE,
    METAWORLD_HOLDOUT_SCREENED_OUT,
    METAWORLD_HOLDOUT_TASKS,
    METAWORLD_PROFILE,
    METAWORLD_PROGRESS_PROFILE,
    PROFILES,
    RunKey,
)

HOLDOUT = METAWORLD_HOLDOUT_PROFILE
#: the candidates in the order their waves were fixed (wave 1: drawer-open, push, pick-place)
CANDIDATES = tuple(
    f"planshape/MetaWorld-{name}-v3"
    for name in ("drawer-open", "push", "pick-place", "handle-press", "plate-slide", "faucet-open")
)
SHAPED = "plan-distance-sum/stages"
FIXED_TASKS = set(CANDIDATES) - set(METAWORLD_HOLDOUT_SCREENED_OUT)


def test_the_candidates_are_unchanged_and_only_the_screen_removes_one():
    """A candidate leaves only through the dense screen, with its curve stated; a later wave
    adds to the end, it never replaces a candidate."""
    assert METAWORLD_HOLDOUT_CANDIDATES == CANDIDATES
    assert set(METAWORLD_HOLDOUT_SCREENED_OUT) < set(CANDIDATES)
    for task, why in METAWORLD_HOLDOUT_SCREENED_OUT.items():
        assert why.startswith("dense seed 0: "), task
        assert any(task.removeprefix("planshape/") in c for c in HOLDOUT.caveats), task
    assert tuple(t for t in CANDIDATES if t in FIXED_TASKS) == METAWORLD_HOLDOUT_TASKS


def test_the_fixed_design_is_unchanged():
    keys = list(HOLDOUT.runs())
    assert PROFILES["metaworld-holdout"] is HOLDOUT
    assert {k.task for k in keys} == FIXED_TASKS
    assert {k.entry for k in keys} == {"sparse", "dense", SHAPED}
    assert {k.algo for k in keys} == {"SBX-SAC"}
    assert {k.budget for k in keys} == {200_000}
    assert {k.seed for k in keys} == set(range(5))
    assert len(keys) == len(FIXED_TASKS) * 3 * 5
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
