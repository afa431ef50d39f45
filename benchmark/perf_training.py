"""Training throughput with shaping over without: environment steps per second of the same
learner on the same task, the sparse entry against shaped entries, interleaved in one process.

Goal: ≥ 0.90 (shaping costs at most a tenth of the training throughput).
Run ``python -m planshape.perf_training``.
"""

from __future__ import annotations

import argparse
import statistics
import time

import planshape  # noqa: F401  (registers the tasks)
from planshape.hyperparams import hyperparameters
from planshape.profiles import RunKey
from planshape.runner import make_learner

GOAL = 0.90
CASES = [
    ("planshape/Reach-v0", "PPO", ("plan-based/grid", "distance-varying/grid", "h-star/grid")),
    ("planshape/Push-v0", "PPO", ("plan-based/grid", "plan-distance/grid")),
    ("planshape/Reach-v0", "SAC", ("plan-based/grid",)),
]


def steps_per_second(task: str, entry: str, algo: str, steps: int) -> float:
    """Train ``algo`` on one entry for ``steps`` steps (no evaluation) and time it."""
    import torch

    torch.set_num_threads(1)
    settings = hyperparameters(task, algo)
    if "learning_starts" in settings:  # time gradient steps, not the random warm-up
        settings["learning_starts"] = 0
    model = make_learner(RunKey(task, entry, algo, 0, steps), settings)
    start = time.perf_counter()
    model.learn(steps)
    return steps / (time.perf_counter() - start)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=8192, help="PPO steps per timing")
    parser.add_argument("--repeats", type=int, default=3, help="interleaved repeats")
    args = parser.parse_args(argv)
    print("training throughput, shaped over sparse (median of interleaved repeats)")
    print(f"{'task':20s} {'algo':4s} {'entry':22s} {'steps/s':>8s} {'sparse':>8s} ratio")
    for task, algo, entries in CASES:
        steps = args.steps if algo == "PPO" else args.steps // 8
        timings: dict[str, list[float]] = {e: [] for e in ("sparse", *entries)}
        for _ in range(args.repeats):
            for entry in timings:
                timings[entry].append(steps_per_second(task, entry, algo, steps))
        sparse = statistics.median(timings["sparse"])
        for entry in entries:
            rate = statistics.median(timings[entry])
            ratio = rate / sparse
            verdict = "met" if ratio >= GOAL else "not met"
            print(
                f"{task.split('/')[1]:20s} {algo:4s} {entry:22s} {rate:8.0f} {sparse:8.0f} "
                f"{ratio:5.2f} ({verdict})"
            )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
