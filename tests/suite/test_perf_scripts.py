"""The benchmark scripts that print speed figures run end to end on tiny inputs (their figures
are not asserted: speed goals are read from their output, never timed in tests)."""

from __future__ import annotations

import math

from planshape import perf_shaping, perf_training


def test_training_throughput_script_trains_a_shaped_learner():
    rate = perf_training.steps_per_second("planshape/Reach-v0", "plan-based/grid", "PPO", 1024)
    assert math.isfinite(rate) and rate > 0


def test_shaping_overhead_script_measures_a_planar_task():
    row = perf_shaping.measure("planshape/Reach-v0", "plan-based", "grid", steps=200, repeats=1)
    assert row["task"] == "planshape/Reach-v0"
