"""Shaping overhead: time per step of a shaped environment over the same environment unshaped.

Both are made with ``gymnasium.make`` in the same process and driven by the same actions;
timings are the fastest of many short interleaved repeats (as ``timeit`` reports), and interleaving
makes drift hit both alike. Each repeat times the stretches of steps between resets on the
thread's CPU clock (``--clock thread``, the default), which other processes on a busy machine do
not advance; ``--clock wall`` uses ``time.perf_counter``.
Goal: a ratio ≤ 1.25 on the planar tasks for every reference potential (≤ 1.10 on the slower
MuJoCo environments). The ratio depends on how long the environment's own step takes: the
planar tasks step in about 20 µs, so a few µs of classification and progress tracking is a
large fraction there, while on MetaWorld or Fetch it is not.
Run ``python -m planshape.perf.shaping``.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable

import gymnasium
import numpy as np

import planshape  # noqa: F401  (registers the tasks)

#: every reference potential on the planar tasks the benchmark runs (their grid models), and
#: two robotics tasks, whose own step is slower
PLANAR_POTENTIALS = (
    "plan-based",
    "time-varying",
    "distance-varying",
    "plan-distance",
    "plan-path",
    "goal-distance",
    "h-add",
    "h-ff",
    "h-star",
    "h-star-geodesic",
)
CASES = [
    *(("planshape/Push-v1", p, "grid") for p in PLANAR_POTENTIALS),
    ("planshape/Push-v1", "plan-distance", "grid-diagonal"),
    ("planshape/Push-v1", "distance-varying", "multi"),
    *(("planshape/Reach-v1", p, "grid") for p in ("plan-based", "plan-distance", "plan-path")),
    ("planshape/MazeReach-v1", "h-star-geodesic", "grid"),
    ("planshape/MetaWorld-pick-place-v3", "plan-based", "stages"),
    ("planshape/FetchPush-v4", "distance-varying", "stages"),
]
GOAL = 1.25


#: the clocks a measurement can read
CLOCKS: dict[str, Callable[[], float]] = {"thread": time.thread_time, "wall": time.perf_counter}


def seconds_per_step(
    env: gymnasium.Env, actions: np.ndarray, clock: Callable[[], float] = time.thread_time
) -> float:
    """Time per step over ``actions`` on ``clock``, resetting on episode ends: each stretch of
    steps between resets is timed as a whole (resets not counted, nor a clock read per step)."""
    env.reset(seed=0)
    elapsed = 0.0
    start = clock()
    for action in actions:
        _, _, terminated, truncated, _ = env.step(action)
        if terminated or truncated:
            elapsed += clock() - start
            env.reset()
            start = clock()
    elapsed += clock() - start
    return elapsed / len(actions)


def measure(
    task: str, potential: str, model: str, steps: int, repeats: int, clock: str = "thread"
) -> dict:
    plain = gymnasium.make(task)
    shaped = gymnasium.make(task, reward="shaped", potential=potential, model=model, gamma=0.99)
    shape = plain.action_space.shape
    actions = np.random.default_rng(0).uniform(-1, 1, (steps, *shape)).astype(np.float32)
    read = CLOCKS[clock]
    seconds_per_step(plain, actions[:500], read)  # warm up both
    seconds_per_step(shaped, actions[:500], read)
    plain_times, shaped_times = [], []
    for _ in range(repeats):
        plain_times.append(seconds_per_step(plain, actions, read))
        shaped_times.append(seconds_per_step(shaped, actions, read))
    plain_s, shaped_s = min(plain_times), min(shaped_times)
    return {
        "task": task,
        "potential": potential,
        "model": model,
        "plain_us": plain_s * 1e6,
        "shaped_us": shaped_s * 1e6,
        "ratio": shaped_s / plain_s,
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=1000, help="steps per repeat")
    parser.add_argument("--repeats", type=int, default=25, help="interleaved repeats")
    parser.add_argument(
        "--clock", choices=sorted(CLOCKS), default="thread", help="what a step's time is read on"
    )
    args = parser.parse_args(argv)
    print(f"shaping overhead (fastest of interleaved repeats, same actions, {args.clock} clock)")
    print(f"{'task':34s} {'potential':17s} {'model':13s} {'plain µs':>9s} {'shaped µs':>10s} ratio")
    rows = [measure(*case, args.steps, args.repeats, args.clock) for case in CASES]
    for r in rows:
        print(
            f"{r['task']:34s} {r['potential']:17s} {r['model']:13s} {r['plain_us']:9.1f} "
            f"{r['shaped_us']:10.1f} {r['ratio']:5.2f}"
        )
    for r in rows:
        overhead = r["shaped_us"] - r["plain_us"]
        verdict = "met" if r["ratio"] <= GOAL else "not met"
        print(
            f"{r['task']} {r['potential']}/{r['model']}: +{overhead:.1f} µs per step, "
            f"ratio {r['ratio']:.2f} ({verdict})"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
