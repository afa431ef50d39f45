"""Training throughput: environment steps per second of every learner backend on the same
task and entries, measured side by side (interleaved) in one process, so that each ratio is
read from one run.

For each (task, algorithm, entry) the learner first trains a warm-up (so JAX has compiled and
the replay buffer is past its random steps), then is timed on ``--steps`` more; the fastest of
``--repeats`` interleaved timings (each repeat does the same work from the same seed, so the
slower ones measure other processes) is reported with two ratios: shaped over sparse (the cost of
shaping; goal ≥ 0.95) and this backend over stable-baselines3's same algorithm (the gain of
SBX). Timings are read on the process's CPU clock (``--clock process``, the default: every
thread's time, XLA's included, and none of other processes' on a busy machine) or on the wall
clock (``--clock wall``). Run ``python -m planshape.perf.training [--json]``.

Timed directly, the shaped/sparse ratio is a small difference of two noisy rates: a PPO step on
a planar task costs about 130 µs, shaping adds 2-4 µs to it, and separately built learners
differ by more than that (on a quiet machine the fastest of 5 timings ranged 0.85-1.17 for
shaped/sparse). So each row also gives ``by_step``: the ratio that the shaping step's own cost
implies, 1 / (1 + Δ · sparse rate), with Δ the shaped step's time over the plain step's
(:func:`planshape.perf.shaping.measure`, the fastest of many interleaved repeats). It is the
whole difference: the learner's work (network sizes, batches, gradient steps) does not depend
on the reward's values, and the two runs step the same environments otherwise.
"""

from __future__ import annotations

import argparse
import json
import time
from collections.abc import Callable, Sequence
from typing import Any

import planshape  # noqa: F401  (registers the tasks)
from planshape.harness.profiles import RunKey
from planshape.harness.runner import make_learner
from planshape.perf import shaping as perf_shaping
from planshape.training.hyperparams import hyperparameters
from planshape.training.learners import learner, release_compiled

GOAL = 0.95
ENTRIES = ("sparse", "plan-based/grid", "plan-distance/grid", "plan-path/grid")
#: (task, algorithms side by side, entries)
CASES: tuple[tuple[str, tuple[str, ...], tuple[str, ...]], ...] = (
    ("planshape/Push-v1", ("PPO", "SBX-PPO"), ENTRIES),
    ("planshape/Push-v1", ("SAC", "SBX-SAC", "SBX-TQC", "SBX-CrossQ"), ENTRIES),
    ("planshape/Reach-v1", ("SAC", "SBX-SAC"), ("sparse", "plan-path/grid")),
)
#: the stable-baselines3 algorithm each learner is compared with
_REFERENCE = {"PPO": "PPO", "SAC": "SAC", "TQC": "SAC", "CrossQ": "SAC"}


#: the clocks a timing can read
CLOCKS: dict[str, Callable[[], float]] = {"process": time.process_time, "wall": time.perf_counter}


def steps_per_second(
    task: str,
    entry: str,
    algo: str,
    steps: int,
    warmup: int = 0,
    clock: Callable[[], float] = time.process_time,
) -> float:
    """Train ``algo`` on one entry for ``warmup`` steps, then time ``steps`` more on ``clock``
    (no evaluation)."""
    import torch

    torch.set_num_threads(1)
    settings = hyperparameters(task, algo, entry)
    if "learning_starts" in settings:  # time gradient steps, not the random warm-up
        settings["learning_starts"] = 0
    model = make_learner(RunKey(task, entry, algo, 0, steps), settings)
    if warmup:
        model.learn(warmup)
    start = clock()
    model.learn(steps, reset_num_timesteps=not warmup)
    elapsed = clock() - start
    del model
    release_compiled()  # dozens of models in one process: free each one's compiled functions
    return steps / elapsed


def step_overhead(task: str, entry: str) -> float:
    """Seconds that shaping with ``entry`` adds to one environment step of ``task`` (0 for
    sparse): the shaped step's time minus the plain step's, fastest of interleaved repeats on
    the thread's clock."""
    key = RunKey(task, entry, "PPO", 0, 0)
    if key.potential is None:
        return 0.0
    row = perf_shaping.measure(task, key.potential, key.model, steps=250, repeats=20)
    return (row["shaped_us"] - row["plain_us"]) * 1e-6


def measure(steps: int, repeats: int, cases=CASES, clock: str = "process") -> list[dict[str, Any]]:
    """One row per (task, algorithm, backend, entry)."""
    rows = []
    overheads: dict[tuple[str, str], float] = {}
    for task, algos, entries in cases:
        timings: dict[tuple[str, str], list[float]] = {(a, e): [] for a in algos for e in entries}
        for _ in range(repeats):
            for algo, entry in timings:
                n = steps if "PPO" in algo else max(steps // 16, 64)
                timings[algo, entry].append(
                    steps_per_second(task, entry, algo, n, n // 4, CLOCKS[clock])
                )
        rate = {k: max(v) for k, v in timings.items()}
        for algo, entry in timings:
            reference = _REFERENCE[learner(algo).cls]
            if (task, entry) not in overheads:
                overheads[task, entry] = step_overhead(task, entry)
            rows.append(
                {
                    "task": task,
                    "algo": algo,
                    "backend": learner(algo).backend,
                    "entry": entry,
                    "steps_per_s": rate[algo, entry],
                    "shaped_over_sparse": rate[algo, entry] / rate[algo, "sparse"],
                    "by_step": 1.0 / (1.0 + overheads[task, entry] * rate[algo, "sparse"]),
                    "over_sb3": (
                        rate[algo, entry] / rate[reference, entry]
                        if (reference, entry) in rate
                        else None
                    ),
                }
            )
    return rows


def render(rows: Sequence[dict[str, Any]]) -> str:
    header = (
        f"{'task':12s} {'algo':11s} {'backend':17s} {'entry':20s} {'steps/s':>8s} "
        f"{'shaped/sparse':>13s} {'by step':>9s} {'/ sb3':>6s}"
    )
    lines = [f"training throughput (goal shaped/sparse ≥ {GOAL})", header, "-" * len(header)]
    for r in rows:
        ratio = by_step = ""
        if r["entry"] != "sparse":
            ratio, by_step = (
                f"{v:.2f}" + (" ok" if v >= GOAL else " LOW")
                for v in (r["shaped_over_sparse"], r["by_step"])
            )
        over = "" if r["over_sb3"] is None else f"{r['over_sb3']:.2f}"
        lines.append(
            f"{r['task'].split('/')[1]:12s} {r['algo']:11s} {r['backend']:17s} {r['entry']:20s} "
            f"{r['steps_per_s']:8.0f} {ratio:>13s} {by_step:>9s} {over:>6s}"
        )
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=8192, help="PPO steps per timing (SAC: /16)")
    parser.add_argument("--repeats", type=int, default=5, help="interleaved repeats")
    parser.add_argument("--json", action="store_true", help="print the rows as JSON")
    parser.add_argument(
        "--clock", choices=sorted(CLOCKS), default="process", help="what a timing is read on"
    )
    parser.add_argument(
        "--task", action="append", help="only these tasks (e.g. planshape/Push-v1; repeatable)"
    )
    parser.add_argument(
        "--algo", action="append", help="only these learners (e.g. PPO, SBX-PPO; repeatable)"
    )
    args = parser.parse_args(argv)
    for option, chosen, known in (
        ("--task", args.task, [task for task, _, _ in CASES]),
        ("--algo", args.algo, [a for _, algos, _ in CASES for a in algos]),
    ):
        unknown = sorted(set(chosen or ()) - set(known))
        if unknown:
            choices = ", ".join(dict.fromkeys(known))
            parser.error(f"{option} {unknown[0]}: not measured here; choose from {choices}")
    cases = [
        (task, tuple(a for a in algos if not args.algo or a in args.algo), entries)
        for task, algos, entries in CASES
        if not args.task or task in args.task
    ]
    cases = [case for case in cases if case[1]]
    rows = measure(args.steps, args.repeats, cases, args.clock)
    print(json.dumps(rows, indent=2) if args.json else render(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
