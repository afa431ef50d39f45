"""Environment steps per second of the planar tasks against gymnasium-robotics' PointMaze.

Every environment is created through ``gymnasium.make`` (so the standard wrappers are
included: TimeLimit, OrderEnforcing, PassiveEnvChecker) and stepped with the same pre-drawn
uniform random actions, resetting when an episode ends; the runs are interleaved round-robin
and each environment's median over the repeats is reported, with its ratio to
``PointMaze_UMaze-v3`` measured in the same process (goal: ratio ≥ 1.0).

Usage::

    python -m planshape.perf.envs [--steps 20000] [--repeats 3] [--json]

The planar environments are registered here under temporary ``planshape-perf/`` ids (the
suite's own ids come from the task registration).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from collections.abc import Sequence
from dataclasses import asdict, dataclass

import gymnasium
import numpy as np

BASELINE = "PointMaze_UMaze-v3"

PLANAR = {
    "planshape-perf/Reach-v0": "planshape.tasks.planar.reach:ReachEnv",
    "planshape-perf/Push-v0": "planshape.tasks.planar.push:PushEnv",
    "planshape-perf/MazeReach-v0": "planshape.tasks.planar.maze_reach:MazeReachEnv",
}


@dataclass(frozen=True)
class Row:
    """One environment's throughput (median over repeats)."""

    env_id: str
    steps: int
    steps_per_s: float
    ratio_to_baseline: float


def _register() -> None:
    import gymnasium_robotics

    gymnasium.register_envs(gymnasium_robotics)
    for env_id, entry_point in PLANAR.items():
        if env_id not in gymnasium.registry:
            gymnasium.register(env_id, entry_point=entry_point, max_episode_steps=50)


def _time_steps(env: gymnasium.Env, actions: np.ndarray, seed: int) -> float:
    """Seconds to take ``len(actions)`` steps (resets included)."""
    env.reset(seed=seed)
    step, reset = env.step, env.reset
    start = time.perf_counter()
    for action in actions:
        _, _, terminated, truncated, _ = step(action)
        if terminated or truncated:
            reset()
    return time.perf_counter() - start


def measure(steps: int = 20000, repeats: int = 3, seed: int = 0) -> list[Row]:
    """Steps per second of each planar environment and of the baseline, same process."""
    _register()
    ids = [*PLANAR, BASELINE]
    envs = {env_id: gymnasium.make(env_id) for env_id in ids}
    rng = np.random.default_rng(seed)
    actions = rng.uniform(-1.0, 1.0, size=(steps, 2)).astype(np.float32)
    for env in envs.values():  # warm up: first-call checks, caches
        _time_steps(env, actions[:500], seed)
    seconds: dict[str, list[float]] = {env_id: [] for env_id in ids}
    for _ in range(repeats):
        for env_id in ids:
            seconds[env_id].append(_time_steps(envs[env_id], actions, seed))
    for env in envs.values():
        env.close()
    rate = {env_id: steps / statistics.median(seconds[env_id]) for env_id in ids}
    return [Row(env_id, steps, rate[env_id], rate[env_id] / rate[BASELINE]) for env_id in ids]


def render(rows: Sequence[Row]) -> str:
    """A Markdown table of the rows."""
    lines = [
        f"| environment | steps/s | ratio to {BASELINE} |",
        "|---|---:|---:|",
    ]
    lines += [f"| {r.env_id} | {r.steps_per_s:,.0f} | {r.ratio_to_baseline:.2f} |" for r in rows]
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m planshape.perf.envs", description=__doc__)
    parser.add_argument("--steps", type=int, default=20000, help="steps per timed run")
    parser.add_argument("--repeats", type=int, default=3, help="timed runs per environment")
    parser.add_argument("--seed", type=int, default=0, help="seed of the random actions")
    parser.add_argument("--json", action="store_true", help="print JSON rows instead")
    args = parser.parse_args(argv)
    if args.steps < 1 or args.repeats < 1:
        parser.error("--steps and --repeats must be positive")
    rows = measure(args.steps, args.repeats, args.seed)
    if args.json:
        print(json.dumps([asdict(r) for r in rows], indent=2))
    else:
        print(
            f"{args.steps} random-action steps x {args.repeats} interleaved repeats, median; "
            "through gymnasium.make (TimeLimit, OrderEnforcing, PassiveEnvChecker)"
        )
        print(render(rows))
    slowest = min(r.ratio_to_baseline for r in rows if r.env_id != BASELINE)
    return 0 if slowest >= 1.0 else 1


if __name__ == "__main__":
    sys.exit(main())
