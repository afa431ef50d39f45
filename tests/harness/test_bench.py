"""The benchmark end to end: the smoke profile with a submitted potential, resuming, the
leaderboard, determinism and the Ray executor."""

from __future__ import annotations

import json

import pytest

from planshape.cli import main
from planshape.harness.profiles import RunKey
from planshape.harness.runner import RunSpec, execute
from planshape.harness.store import ResultStore
from planshape.results.rows import load_rows

SUBMISSION = "tests.submission.example:ProgressAndDistance"


@pytest.fixture(scope="module")
def smoke_out(tmp_path_factory):
    """One real smoke-profile benchmark with the README's example submission."""
    out = tmp_path_factory.mktemp("bench")
    status = main(
        [
            "bench",
            "--profile",
            "smoke",
            "--out",
            str(out),
            "--workers",
            "1",
            "--potential",
            SUBMISSION,
        ]
    )
    assert status == 0
    return out


def test_smoke_profile_with_a_submission_writes_the_leaderboard(smoke_out):
    rows = load_rows(smoke_out)
    entries = {r["entry"] for r in rows}
    # the profile's three entries, and the submission on every model of the task
    assert {"sparse", "dense", "plan-based/multi"} <= entries
    assert {f"{SUBMISSION}/{m}" for m in ("single", "multi", "grid")} <= entries
    for name in ("LEADERBOARD.md", "index.html", "summary.json"):
        assert (smoke_out / name).is_file()
    board = (smoke_out / "LEADERBOARD.md").read_text()
    assert SUBMISSION in board and "smoke" in board
    verdicts = {r["entry"]: r["invariance"] for r in rows if r["potential"]}
    assert set(verdicts.values()) == {"preserved"}
    # scores come from the task's own metrics at every evaluation point (rule 5): the sparse
    # reward pays 0 or 1 per step, so a return that included shaping terms would not be whole
    assert all(0.0 <= r["success_rate"] <= 1.0 and r["final_distance"] >= 0 for r in rows)
    shaped = [r for r in rows if r["potential"]]
    totals = [r["sparse_return"] * r["eval_episodes"] for r in shaped]
    assert shaped and all(abs(total - round(total)) < 1e-9 for total in totals)


def test_resume_reruns_nothing_that_finished(smoke_out, capfd):
    capfd.readouterr()  # what the fixture's first benchmark printed
    before = sorted(p.name for p in (smoke_out / "runs").glob("*.jsonl"))
    stamp = {p.name: p.stat().st_mtime_ns for p in (smoke_out / "runs").glob("*.jsonl")}
    (smoke_out / "runs" / ".deadbeef.killed.tmp").write_text('{"half": ')  # a killed write
    assert (
        main(
            [
                "bench",
                "--profile",
                "smoke",
                "--out",
                str(smoke_out),
                "--workers",
                "1",
                "--potential",
                SUBMISSION,
            ]
        )
        == 0
    )
    after = sorted(p.name for p in (smoke_out / "runs").glob("*.jsonl"))
    assert after == before
    lines = [line for line in capfd.readouterr().out.splitlines() if line.startswith("[")]
    # stored runs take no time and say nothing about the rest: nothing is left to estimate
    assert len(lines) == len(before) and all(" stored " in line for line in lines), lines
    assert all(line.endswith("about 0m00s left") for line in lines), lines
    assert all(p.stat().st_mtime_ns == stamp[p.name] for p in (smoke_out / "runs").glob("*.jsonl"))
    assert not list((smoke_out / "runs").glob("*.tmp"))


def test_leaderboard_command_renders_again(smoke_out, capsys):
    assert main(["leaderboard", "--out", str(smoke_out), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert any(row["entry"] == "dense" for row in summary)


def test_bad_input_exits_2(tmp_path, capsys):
    assert main(["bench", "--profile", "nope", "--out", str(tmp_path)]) == 2
    assert "unknown profile 'nope'" in capsys.readouterr().err
    assert main(["bench", "--profile", "smoke", "--tasks", "reech", "--out", str(tmp_path)]) == 2
    assert main(["bench", "--potential", "no_such_module:X", "--out", str(tmp_path)]) == 2
    assert main(["leaderboard", "--out", str(tmp_path / "empty")]) == 2


TINY = RunKey("planshape/Reach-v0", "plan-based/grid", "PPO", 3, 1024)


def test_same_spec_same_numbers():
    spec = RunSpec.create(TINY, "test", eval_every=512, eval_episodes=2)
    first, second = execute(spec), execute(spec)
    keep = ("step", "success_rate", "final_distance", "sparse_return")
    assert [{k: r[k] for k in keep} for r in first] == [{k: r[k] for k in keep} for r in second]


def test_ray_executor_gives_the_local_numbers(tmp_path):
    import ray

    from planshape.suite.session import _execute_on_ray

    spec = RunSpec.create(TINY, "test", eval_every=512, eval_episodes=2)
    ray.init(num_cpus=1, include_dashboard=False, log_to_driver=False)
    try:
        remote_rows = _execute_on_ray(spec, None)
    finally:
        ray.shutdown()
    local_rows = execute(spec)
    keep = ("step", "success_rate", "final_distance", "sparse_return", "run_id")
    assert [{k: r[k] for k in keep} for r in remote_rows] == [
        {k: r[k] for k in keep} for r in local_rows
    ]
    ResultStore(tmp_path).write(spec.run_id, remote_rows)
    assert ResultStore(tmp_path).has(spec.run_id)


def test_a_run_keeps_its_identity_through_training():
    """stable-baselines3 writes into policy_kwargs; the spec (and so the run id under which a
    finished run is stored and found again) must not change."""
    spec = RunSpec.create(RunKey("planshape/Reach-v0", "sparse", "SAC", 0, 64), "test", 64, 1)
    before = spec.run_id
    rows = execute(spec)
    assert spec.run_id == before == rows[0]["run_id"]


def _older_budget(row: dict) -> None:
    row["budget"] = 2048


def _older_scale(row: dict) -> None:
    row["hyperparameters"]["shaping_scale"] = 10.0


@pytest.mark.parametrize(
    ("entry", "change", "named"),
    [("sparse", _older_budget, "2,048 steps"), ("plan-based/multi", _older_scale, "4,096 steps")],
)
def test_runs_at_a_budget_or_settings_the_profile_no_longer_uses_are_kept_but_not_shown(
    smoke_out, tmp_path, entry, change, named
):
    """After a budget or a hyperparameter table changes (here: a shaped entry's shaping
    scale), the runs stored with the old one stay in the store and out of the cells: the
    leaderboard names them in its caveats instead of mixing two budgets or two settings."""
    import shutil

    out = tmp_path / "board"
    shutil.copytree(smoke_out / "runs", out / "runs")
    stored = [
        [json.loads(line) for line in p.read_text().splitlines()]
        for p in sorted((out / "runs").glob("*.jsonl"))
    ]
    rows = next(rows for rows in stored if rows[0]["entry"] == entry)
    for row in rows:
        change(row)
        row["run_id"], row["seed"] = "0000older0run000", 7
    (out / "runs" / "0000older0run000.jsonl").write_text(
        "".join(json.dumps(row) + "\n" for row in rows)
    )
    assert main(["leaderboard", "--out", str(out), "--json"]) == 0
    board = (out / "LEADERBOARD.md").read_text()
    assert "1 stored runs at budgets or settings this profile no longer uses" in board
    assert f"runs/0000older0run000.jsonl, {named}" in board
    summary = json.loads((out / "summary.json").read_text())
    cells = [c for c in summary["per_task"] if c["entry"] == entry]
    assert [(c["n_seeds"], c["budget"]) for c in cells] == [(1, 4096)]


def test_a_profile_with_runs_missing_says_it_is_partial(smoke_out, tmp_path):
    import shutil

    out = tmp_path / "board"
    shutil.copytree(smoke_out / "runs", out / "runs")
    next(p for p in (out / "runs").glob("*.jsonl") if '"dense"' in p.read_text()).unlink()
    assert main(["leaderboard", "--out", str(out), "--json"]) == 0
    board = (out / "LEADERBOARD.md").read_text()
    assert "partial: 2 of the profile's 3 runs are stored" in board
    assert "(missing: planshape/Reach-v1 dense PPO seed 0)" in board
    assert main(["leaderboard", "--out", str(smoke_out), "--json"]) == 0
    assert "partial" not in (smoke_out / "LEADERBOARD.md").read_text()


def test_a_k_selection_counts_and_estimates_only_its_own_runs(tmp_path, capfd):
    out = tmp_path / "one"
    assert (
        main(["bench", "--profile", "smoke", "--out", str(out), "--workers", "1", "-k", "sparse"])
        == 0
    )
    lines = [line for line in capfd.readouterr().out.splitlines() if line.startswith("[")]
    assert len(lines) == 1 and lines[0].startswith("[1/1] done")
    assert lines[0].endswith("about 0m00s left")


def test_a_run_another_benchmark_is_training_is_left_to_it(tmp_path, capfd):
    """Two benchmarks on one folder: a run the other one holds the claim on is skipped
    ("busy"), not trained twice, and trained once the claim is released."""
    from planshape.harness.profiles import PROFILES
    from planshape.suite.session import BenchSession

    out = tmp_path / "shared"
    session = BenchSession(profile=PROFILES["smoke"], out=out)
    runs = session.keys()
    (key,) = [k for k in runs if k.entry == "sparse"]
    run_id = session.spec(key, with_verdict=False).run_id
    store = ResultStore(out)
    command = ["bench", "--profile", "smoke", "--out", str(out), "--workers", "1", "-k", "sparse"]
    with store.claim(run_id) as mine:  # the other benchmark, training this run
        assert mine
        assert main([*command, "--no-render"]) == 0
        lines = [line for line in capfd.readouterr().out.splitlines() if line.startswith("[")]
        assert len(lines) == 1 and lines[0].startswith("[1/1] busy"), lines
        assert not store.has(run_id)
    assert main(command) == 0  # released (that benchmark ended without storing it): trained
    lines = [line for line in capfd.readouterr().out.splitlines() if line.startswith("[")]
    assert lines[0].startswith("[1/1] done") and store.has(run_id)
    assert list((out / ".claims").iterdir()) == []  # no claim is left behind


@pytest.mark.parametrize(
    ("task", "algo", "reason"),
    [
        ("planshape/Push-v1", "PPO", "PPO on push trains {budget:,} steps"),
        ("planshape/MazeReach-v1", "SBX-SAC", "SAC on maze-reach trains {budget:,} steps"),
    ],
)
def test_every_profile_at_a_replaced_planar_budget_says_why(task, algo, reason):
    """A planar budget that replaced an earlier one leaves the earlier runs stored; every
    profile that trains at it (planar, and paper, which reuses its runs) states the learning
    curves that chose it, so a reader of either leaderboard sees why the cell has that budget."""
    from planshape.harness.profiles import PROFILES

    budget = PROFILES["planar"].budgets()[(task, algo)]
    at_it = [p for p in PROFILES.values() if p.budgets().get((task, algo)) == budget]
    assert {"planar", "paper"} <= {p.name for p in at_it}
    stated = reason.format(budget=budget)
    for profile in at_it:
        assert any(c.startswith(stated) for c in profile.caveats), profile.name


def test_every_profile_that_publishes_cells_trains_five_seeds_per_cell():
    """A committed leaderboard cell has at least 5 seeds: every profile that can still train
    (all but the archived ones) does, except smoke, which only checks the pipeline."""
    from planshape.harness.profiles import PROFILES

    publishing = [p for p in PROFILES.values() if not p.archived and p.name != "smoke"]
    assert {"default", "planar", "instances", "paper", "metaworld"} <= {p.name for p in publishing}
    for profile in publishing:
        for block in profile.blocks:
            assert len(set(block.seeds)) >= 5, (profile.name, block.tasks)


def test_the_metaworld_profile_evaluates_where_its_budget_probes_did():
    """The metaworld profile's budgets come from ``planshape probe ... --chunks 10`` curves
    evaluated every 20,000 steps; evaluating its runs at the same points makes a seed-0 run
    repeat the curve that chose its budget, which a reader can check."""
    from planshape.harness.profiles import METAWORLD_SAC_BUDGETS, PROFILES

    profile = PROFILES["metaworld"]
    assert METAWORLD_SAC_BUDGETS and all(
        budget % profile.eval_every == 0 for budget in METAWORLD_SAC_BUDGETS.values()
    )
    keys = list(profile.runs())
    assert {k.algo for k in keys} == {"SBX-SAC"}
    entries = {k.entry for k in keys}
    assert entries == {
        "sparse",
        "dense",
        "plan-based/stages",
        "plan-distance/stages",
        "plan-distance-sum/stages",
        "plan-distance/stages-above",
        "plan-distance-sum/stages-above",
    }
    # plan-distance-sum only where the plan places an object: on reach-v4 it is plan-distance
    summed = {k.task for k in keys if k.entry == "plan-distance-sum/stages"}
    assert summed == set(METAWORLD_SAC_BUDGETS) - {"planshape/MetaWorld-reach-v4"}
    # the second geometry only on button-press-topdown, and only for the distance potentials
    # (plan-based reads no geometry: on it plan-based would repeat plan-based/stages)
    above = {(k.task, k.entry) for k in keys if k.entry.endswith("/stages-above")}
    topdown = "planshape/MetaWorld-button-press-topdown-v3"
    assert above == {
        (topdown, "plan-distance/stages-above"),
        (topdown, "plan-distance-sum/stages-above"),
    }


def test_the_metaworld_profile_holds_at_least_four_distinct_tasks():
    """The MetaWorld block needs at least four tasks on which dense reaches 0.8 within the
    budget; each is a different MetaWorld environment, registered with the `stages` PDDL model
    that the profile's planning entries plan with."""
    from planshape.harness.catalog import describe_tasks
    from planshape.harness.profiles import METAWORLD_SAC_BUDGETS

    assert len(METAWORLD_SAC_BUDGETS) >= 4
    environments = {task.rsplit("-v", 1)[0] for task in METAWORLD_SAC_BUDGETS}
    assert len(environments) == len(METAWORLD_SAC_BUDGETS)
    for row in describe_tasks(METAWORLD_SAC_BUDGETS):
        assert "stages" in row["models"], row["id"]
