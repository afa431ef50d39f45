"""Scoring: the statistics against hand values and rliable's definitions; loading result rows;
the cells' tables and the provenance."""

from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pytest
import scipy.stats

from planshape.errors import BadInputError, ResultsError
from planshape.results.cells import aggregate, final_rows, summarize
from planshape.results.provenance import describe_runs
from planshape.results.rows import COLUMNS, load_rows, validate_row
from planshape.results.stats import (
    Interval,
    curve_area,
    iqm,
    learning_curve,
    mean,
    normalized_score,
    percentile_interval,
    probability_of_improvement,
    probability_of_improvement_ci,
    stratified_bootstrap,
    stratified_bootstrap_ci,
)
from planshape.results.tables import setup_table
from tests.results.synthetic import make_run, synthetic_rows

# ---------------------------------------------------------------------------- IQM and mean


@pytest.mark.parametrize(
    ("scores", "expected"),
    [
        ([1, 2, 3, 4], 2.5),  # cut one from each end
        (list(range(8)), 3.5),  # cut two: mean of 2, 3, 4, 5
        ([1, 1, 1, 100], 1.0),  # the outlier is trimmed
        ([0.2, 0.4, 0.9], 0.5),  # fewer than four scores: nothing to trim, the mean
        ([7.0], 7.0),
        ([[0, 1], [2, 3]], 1.5),  # runs x tasks matrices are flattened (rliable)
    ],
)
def test_iqm_hand_values(scores, expected):
    assert iqm(scores) == pytest.approx(expected)


def test_iqm_is_scipy_trim_mean_over_pooled_tasks():
    rng = np.random.default_rng(3)
    scores = {"a": rng.random(10), "b": rng.random(7)}
    pooled = np.concatenate([scores["a"], scores["b"]])
    assert iqm(scores) == pytest.approx(scipy.stats.trim_mean(pooled, 0.25))


def test_iqm_and_mean_propagate_nan_and_empty():
    assert math.isnan(iqm([1.0, 2.0, 3.0, math.nan]))
    assert math.isnan(iqm([]))
    assert math.isnan(mean([]))
    assert iqm(np.array([[1, 2, 3, 4], [0, 0, 0, math.nan]]), axis=-1)[0] == 2.5
    assert math.isnan(iqm(np.array([[1, 2, 3, 4], [0, 0, 0, math.nan]]), axis=-1)[1])


def test_mean_pools_runs_over_tasks():
    assert mean({"a": [1.0, 0.0], "b": [0.5]}) == 0.5


# ---------------------------------------------------------------------------- bootstrap


def test_percentile_interval():
    assert percentile_interval(np.arange(101), 0.5) == (25.0, 75.0)
    assert all(math.isnan(v) for v in percentile_interval([]))
    with pytest.raises(BadInputError, match="confidence"):
        percentile_interval([1.0], confidence=1.5)


@pytest.mark.parametrize("statistic", [iqm, mean])
def test_bootstrap_interval_contains_the_estimate(statistic):
    rng = np.random.default_rng(1)
    scores = {"reach": rng.uniform(0.6, 1.0, 5), "push": rng.uniform(0.0, 0.5, 5)}
    ci = stratified_bootstrap_ci(scores, statistic)
    assert isinstance(ci, Interval)
    assert ci.value == pytest.approx(statistic(scores))
    assert ci.low < ci.value < ci.high


def test_bootstrap_is_deterministic_for_a_seed():
    scores = {"reach": [0.1, 0.5, 0.7, 0.9], "push": [0.0, 0.2, 0.3]}
    assert stratified_bootstrap_ci(scores, iqm, seed=7) == stratified_bootstrap_ci(
        scores, iqm, seed=7
    )
    assert stratified_bootstrap_ci(scores, iqm, seed=7) != stratified_bootstrap_ci(
        scores, iqm, seed=8
    )
    # Task order in the mapping does not matter.
    flipped = {"push": scores["push"], "reach": scores["reach"]}
    assert stratified_bootstrap_ci(flipped, iqm, seed=7) == stratified_bootstrap_ci(
        scores, iqm, seed=7
    )


def test_bootstrap_is_stratified_by_task():
    # Every task is constant, so resampling within tasks never changes the pooled mean;
    # resampling across tasks would.
    replicates = stratified_bootstrap({"a": [1.0, 1.0, 1.0], "b": [3.0]}, mean, reps=500)
    assert np.allclose(replicates, 1.5)
    assert replicates.shape == (500,)


def test_bootstrap_degenerate_inputs():
    assert stratified_bootstrap_ci([0.4], mean) == Interval(0.4, 0.4, 0.4)
    assert all(math.isnan(v) for v in stratified_bootstrap_ci([], mean))
    assert all(math.isnan(v) for v in stratified_bootstrap_ci({"a": []}, iqm))


# ---------------------------------------------------------------------------- normalized score


def test_normalized_score_on_success():
    assert normalized_score(0.2, 0.2, 0.8) == 0.0
    assert normalized_score(0.8, 0.2, 0.8) == 1.0
    assert normalized_score(0.5, 0.2, 0.8) == pytest.approx(0.5)
    assert normalized_score(1.0, 0.2, 0.8) == pytest.approx(4 / 3)  # beats dense
    assert normalized_score(0.0, 0.2, 0.8) == pytest.approx(-1 / 3)  # worse than sparse


def test_normalized_score_on_distance_keeps_its_meaning():
    # Lower distance is better: reaching dense's distance is 1, sparse's is 0.
    assert normalized_score(0.05, 0.30, 0.05) == 1.0
    assert normalized_score(0.30, 0.30, 0.05) == 0.0
    assert normalized_score(0.175, 0.30, 0.05) == pytest.approx(0.5)


@pytest.mark.parametrize(
    ("entry", "sparse", "dense"),
    [(0.5, 1.0, 1.0), (0.0, 0.0, 0.0), (0.5, math.nan, 1.0), (0.5, 0.0, math.nan)],
)
def test_normalized_score_is_nan_when_undefined_without_warnings(entry, sparse, dense):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert math.isnan(normalized_score(entry, sparse, dense))


def test_normalized_score_vectorizes():
    out = normalized_score([0.2, 0.5, 0.8], 0.2, 0.8)
    assert isinstance(out, np.ndarray)
    assert out.tolist() == pytest.approx([0.0, 0.5, 1.0])


# ---------------------------------------------------------------------------- P(improvement)


def test_probability_of_improvement_bounds():
    assert probability_of_improvement([0.9, 1.0, 0.8], [0.1, 0.2]) == 1.0
    assert probability_of_improvement([0.1, 0.2], [0.9, 1.0, 0.8]) == 0.0
    assert probability_of_improvement([0.5, 0.5], [0.5, 0.5, 0.5]) == 0.5
    same = {"a": [0.1, 0.4, 0.9], "b": [0.3, 0.3]}
    assert probability_of_improvement(same, same) == 0.5


def test_probability_of_improvement_is_mann_whitney_averaged_over_tasks():
    rng = np.random.default_rng(5)
    x = {"a": rng.random(6).round(1), "b": rng.random(5).round(1)}
    y = {"a": rng.random(4).round(1), "b": rng.random(6).round(1)}
    expected = np.mean(
        [
            scipy.stats.mannwhitneyu(x[t], y[t], alternative="greater").statistic
            / (len(x[t]) * len(y[t]))
            for t in ("a", "b")
        ]
    )
    assert probability_of_improvement(x, y) == pytest.approx(expected)


def test_probability_of_improvement_ci():
    assert probability_of_improvement_ci([1.0, 1.0], [0.0, 0.0, 0.0]) == Interval(1.0, 1.0, 1.0)
    x, y = {"a": [0.2, 0.6, 0.9, 0.4]}, {"a": [0.1, 0.5, 0.3, 0.2]}
    ci = probability_of_improvement_ci(x, y, seed=3)
    assert ci.low <= ci.value <= ci.high
    assert ci == probability_of_improvement_ci(x, y, seed=3)


def test_probability_of_improvement_needs_the_same_tasks():
    with pytest.raises(BadInputError, match="same tasks"):
        probability_of_improvement({"a": [1.0]}, {"b": [0.0]})


# ---------------------------------------------------------------------------- curve area


def test_curve_area_hand_values():
    assert curve_area([0, 50, 100], [0.0, 1.0, 1.0], 100) == 0.75
    assert curve_area([0, 100], [1.0, 1.0], 100) == 1.0
    assert curve_area([100, 0], [1.0, 0.0], 100) == 0.5  # order of points does not matter
    assert curve_area([100], [1.0], 100) == 0.0


def test_curve_area_cuts_an_overshoot_at_the_budget():
    # PPO may train past the budget by part of a rollout; the area stays within [0, 1].
    assert curve_area([0, 50, 150], [0.0, 1.0, 1.0], 100) == 0.75
    assert curve_area([0, 200], [0.0, 1.0], 100) == pytest.approx(0.25)


def test_learning_curve_mean_and_band():
    curves = [([0, 10, 20], [0.0, 0.5, 1.0]), ([0, 20], [0.0, 0.0])]
    grid, avg, low, high = learning_curve(curves)
    assert grid.tolist() == [0, 10, 20]
    assert avg.tolist() == pytest.approx([0.0, 0.25, 0.5])
    assert np.all(low <= avg) and np.all(avg <= high)


# ---------------------------------------------------------------------------- loading rows


def _write(path, rows):
    path.write_text("".join(json.dumps(r) + "\n" for r in rows))


def test_load_rows_reads_runs_in_order_and_ignores_temporary_files(tmp_path):
    runs = tmp_path / "runs"
    runs.mkdir()
    _write(runs / "b.jsonl", make_run(seed=1))
    _write(runs / "a.jsonl", make_run(seed=0))
    (runs / ".c.xyz.tmp").write_text("{half a row")
    (runs / "d.jsonl.tmp").write_text("{half a row")
    with (runs / "a.jsonl").open("a") as handle:
        handle.write("\n")  # a blank line is not a row
    rows = load_rows(tmp_path)
    assert [r["seed"] for r in rows] == [0] * 5 + [1] * 5
    assert set(COLUMNS) <= set(rows[0])


def test_load_rows_names_the_file_and_line_of_a_malformed_row(tmp_path):
    runs = tmp_path / "runs"
    runs.mkdir()
    lines = [json.dumps(r) for r in make_run()]
    lines[2] = lines[2][:40]  # a truncated line
    (runs / "broken.jsonl").write_text("\n".join(lines) + "\n")
    with pytest.raises(ResultsError, match=r"broken\.jsonl:3: not a JSON row") as info:
        load_rows(tmp_path)
    assert info.value.line == 3 and info.value.file.name == "broken.jsonl"


def test_load_rows_names_a_missing_column(tmp_path):
    runs = tmp_path / "runs"
    runs.mkdir()
    rows = make_run()
    del rows[1]["final_distance"]
    _write(runs / "old.jsonl", rows)
    with pytest.raises(ResultsError, match=r"old\.jsonl:2: missing columns final_distance"):
        load_rows(tmp_path)


def test_load_rows_without_results_folder(tmp_path):
    with pytest.raises(ResultsError, match="no results folder"):
        load_rows(tmp_path)


def test_validate_row_rejects_wrong_types():
    row = make_run()[0]
    with pytest.raises(ResultsError, match="'success_rate' must be a number"):
        validate_row({**row, "success_rate": "0.9 ± 0.1"})
    with pytest.raises(ResultsError, match="invariance 'maybe'"):
        validate_row({**row, "invariance": "maybe"})
    assert math.isnan(validate_row({**row, "final_distance": None})["final_distance"])


# ---------------------------------------------------------------------------- summarize


@pytest.fixture(scope="module")
def rows():
    return synthetic_rows()


@pytest.fixture(scope="module")
def summary(rows):
    return summarize(rows)


def _row(summary, task, entry, algo="PPO"):
    (match,) = [r for r in summary if (r["task"], r["entry"], r["algo"]) == (task, entry, algo)]
    return match


def test_summarize_one_row_per_task_entry_algo(summary):
    keys = [(r["task"], r["algo"], r["entry"]) for r in summary]
    assert len(keys) == len(set(keys)) == 2 * 4 * 2
    assert keys == sorted(keys)
    assert all(r["n_seeds"] == 4 for r in summary)


def test_summarize_keeps_numbers_numbers(summary):
    text_columns = {"task", "entry", "potential", "model", "algo", "invariance"}
    for row in summary:
        for column, value in row.items():
            if column in text_columns:
                assert value is None or isinstance(value, str)
            elif column == "seeds":
                assert all(isinstance(s, int) for s in value)
            else:
                assert isinstance(value, int | float), (column, value)


def test_summarize_against_references(summary):
    task = "planshape/Reach-v0"
    sparse, dense = _row(summary, task, "sparse"), _row(summary, task, "dense")
    best = _row(summary, task, "plan-based/multi")
    assert sparse["normalized_success"] == pytest.approx(0.0, abs=1e-12)
    assert dense["normalized_success"] == pytest.approx(1.0)
    assert dense["normalized_distance"] == pytest.approx(1.0)
    assert sparse["p_improve"] == 0.5
    assert best["p_improve"] == 1.0 and best["p_improve_distance"] == 1.0
    for row in (sparse, dense, best):
        for column in ("success_iqm", "success_mean", "distance_iqm", "distance_mean"):
            assert row[f"{column}_low"] <= row[column] <= row[f"{column}_high"]
    assert best["invariance"] == "preserved" and sparse["invariance"] == "not-checked"
    assert 0 < best["curve_area_mean"] < 1


def test_summarize_is_deterministic(rows, summary):
    assert summarize(list(reversed(rows))) == summary


def test_summarize_when_references_tie_or_are_missing():
    rows = []
    for seed in range(3):
        rows += make_run(entry="sparse", seed=seed, final_success=1.0, final_distance=0.3)
        rows += make_run(entry="dense", seed=seed, final_success=1.0, final_distance=0.1)
        rows += make_run(entry="plan-based/grid", seed=seed, final_success=1.0)
        rows += make_run(entry="plan-based/grid", algo="SAC", seed=seed, final_success=1.0)
    summary = summarize(rows)
    shaped = _row(summary, "planshape/Reach-v0", "plan-based/grid")
    assert math.isnan(shaped["normalized_success"])  # sparse and dense both at 100%
    assert not math.isnan(shaped["normalized_distance"])
    sac = _row(summary, "planshape/Reach-v0", "plan-based/grid", "SAC")
    assert math.isnan(sac["p_improve"]) and math.isnan(sac["normalized_distance"])
    caveats = " ".join(describe_runs(rows)["caveats"])
    assert "dense is no better than sparse on mean final success" in caveats
    assert "SAC: no sparse or dense entry" in caveats
    overall = {(r["entry"], r["algo"]): r for r in aggregate(rows)}
    assert overall[("plan-based/grid", "PPO")]["normalized_success_tasks_excluded"] == [
        "planshape/Reach-v0"
    ]
    assert math.isnan(overall[("plan-based/grid", "PPO")]["normalized_success_iqm"])


def test_normalization_is_undefined_where_dense_is_worse_than_sparse():
    """Sparse 1/3 and dense 0/3 (maze-reach, where dense is trapped by the wall): an entry
    that solves it would score (1 − 1/3)/(0 − 1/3) = −2 on an inverted scale; n/a instead."""
    rows = []
    for seed in range(3):
        rows += make_run(entry="sparse", seed=seed, final_success=float(seed == 0))
        rows += make_run(entry="dense", seed=seed, final_success=0.0)
        rows += make_run(entry="plan-based/grid", seed=seed, final_success=1.0)
    shaped = _row(summarize(rows), "planshape/Reach-v0", "plan-based/grid")
    assert math.isnan(shaped["normalized_success"])
    overall = {(r["entry"], r["algo"]): r for r in aggregate(rows)}
    assert overall[("plan-based/grid", "PPO")]["normalized_success_tasks_excluded"] == [
        "planshape/Reach-v0"
    ]


def test_a_single_seed_gets_no_interval():
    rows = make_run(seed=0, final_success=0.6) + make_run(entry="dense", seed=0)
    row = _row(summarize(rows), "planshape/Reach-v0", "sparse")
    assert row["success_iqm"] == pytest.approx(0.6)
    assert math.isnan(row["success_iqm_low"]) and math.isnan(row["success_iqm_high"])
    assert math.isnan(row["p_improve_low"])
    assert "single seed" in " ".join(describe_runs(rows)["caveats"])


def test_runs_without_a_final_row_are_left_out_and_reported():
    finished = make_run(seed=0)
    killed = [{**r, "final": False} for r in make_run(seed=1)]
    assert [r["seed"] for r in final_rows(finished + killed)] == [0]
    info = describe_runs(finished + killed)
    assert info["n_runs"] == 1 and len(info["incomplete_runs"]) == 1
    assert "no final evaluation row" in info["caveats"][0]


def test_a_seed_counted_twice_is_an_error():
    rows = make_run(seed=0) + [{**r, "run_id": "copy"} for r in make_run(seed=0)]
    with pytest.raises(ResultsError, match="seed 0 more than once"):
        summarize(rows)


def test_mixed_budgets_are_an_error():
    rows = make_run(seed=0, budget=1000) + make_run(seed=1, budget=2000)
    with pytest.raises(ResultsError, match="mixes budgets"):
        summarize(rows)


def test_invariance_verdicts_combine():
    rows = make_run(seed=0, invariance="preserved") + make_run(seed=1, invariance="violated")
    assert summarize(rows)[0]["invariance"] == "violated"
    rows = make_run(seed=0, invariance="preserved") + make_run(seed=1)
    assert summarize(rows)[0]["invariance"] == "not-checked"
    rows = make_run(seed=0, invariance="preserved") + make_run(seed=1, invariance="preserved")
    assert summarize(rows)[0]["invariance"] == "preserved"
    rows = make_run(seed=0, invariance="not-applicable")
    assert summarize(rows)[0]["invariance"] == "not-applicable"


def test_aggregate_pools_normalized_scores_over_tasks(rows):
    overall = aggregate(rows)
    assert [(r["algo"], r["entry"]) for r in overall] == sorted(
        (r["algo"], r["entry"]) for r in overall
    )
    best = next(r for r in overall if (r["entry"], r["algo"]) == ("plan-based/multi", "PPO"))
    assert best["n_tasks"] == 2 and best["n_runs"] == 8
    assert best["normalized_success_iqm"] > 1.0  # beats dense on both tasks
    assert best["normalized_success_iqm_low"] <= best["normalized_success_iqm"]
    assert best["p_improve"] == 1.0


def test_describe_runs(rows):
    info = describe_runs(rows, profile="test")
    assert info["budgets"] == {
        "planshape/Push-v0": {"PPO": 1000, "SAC": 1000},
        "planshape/Reach-v0": {"PPO": 1000, "SAC": 1000},
    }
    assert info["seeds"] == [0, 1, 2, 3] and info["eval_episodes"] == [10]
    assert info["caveats"] == []
    mixed = rows + make_run(entry="sparse", seed=9, code_version="v0.2-dirty", profile="other")
    caveats = " ".join(describe_runs(mixed, profile="test")["caveats"])
    assert "several code versions" in caveats and "uncommitted" in caveats
    assert "not only 'test'" in caveats and "unequal numbers of seeds" in caveats


def test_the_set_up_table_names_the_cpus_the_runs_trained_on():
    """An SBX run re-executes only on the CPU type that trained it, so the page names it, with
    how many runs each CPU trained; runs from before rows recorded it count as not recorded."""
    epyc, xeon = "AMD EPYC (avx2)", "Intel(R) Xeon(R) Platinum 8481C (avx512f)"
    old = [r for seed in (0, 1) for r in make_run(entry="sparse", seed=seed)]
    recorded = [
        *make_run(entry="dense", seed=0, cpu=epyc),
        *make_run(entry="dense", seed=1, cpu=epyc),
        *make_run(entry="dense", seed=2, cpu=xeon),
    ]
    info = describe_runs(old + recorded)
    assert info["cpus"] == {epyc: 2, "not recorded": 2, xeon: 1}
    shown = {label.text: text.text for label, text in setup_table({}, info).rows}
    assert shown["CPU"] == f"{epyc}: 2 runs; not recorded: 2 runs; {xeon}: 1 run"
    unrecorded = describe_runs(old)
    assert unrecorded["cpus"] == {"not recorded": 2}
    assert "CPU" not in {label.text for label, _ in setup_table({}, unrecorded).rows}
