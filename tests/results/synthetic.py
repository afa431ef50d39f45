"""Synthetic result rows, shaped like the benchmark runner's, for the scoring tests."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from planshape.harness.profiles import Profile, RunKey

#: entry -> (final success rate, final distance) around which the seeds scatter.
LEVELS = {
    "sparse": (0.2, 0.30),
    "dense": (0.8, 0.05),
    "plan-based/multi": (0.9, 0.04),
    "distance-varying/grid": (0.5, 0.15),
}


def make_run(
    task: str = "planshape/Reach-v0",
    entry: str = "sparse",
    algo: str = "PPO",
    seed: int = 0,
    budget: int = 1000,
    final_success: float = 0.5,
    final_distance: float = 0.1,
    points: int = 5,
    invariance: str = "not-checked",
    **extra: Any,
) -> list[dict[str, Any]]:
    """The rows of one run: evaluations at steps 0 .. budget, success rising linearly."""
    potential, model = (None, None) if entry in ("sparse", "dense") else entry.rsplit("/", 1)
    run_id = f"{task.replace('/', '-')}__{entry.replace('/', '-')}__{algo}__s{seed}"
    rows = []
    for i, step in enumerate(np.linspace(0, budget, points).astype(int)):
        fraction = i / (points - 1)
        row = {
            "run_id": run_id,
            "task": task,
            "entry": entry,
            "potential": potential,
            "model": model,
            "algo": algo,
            "seed": seed,
            "step": int(step),
            "budget": budget,
            "final": i == points - 1,
            "success_rate": float(final_success * fraction),
            "final_distance": float(0.5 + (final_distance - 0.5) * fraction),
            "sparse_return": float(final_success * fraction),
            "eval_episodes": 10,
            "profile": "test",
            "invariance": invariance,
            "wall_time_s": 12.5,
            "steps_per_s": 800.0,
            "code_version": "v0.1.0-5-gabcdef0",
            "packages": {"gymnasium": "1.4.0", "stable-baselines3": "2.9.2"},
            "hyperparameters": {"learning_rate": 0.0003, "n_steps": 128},
            "gamma": 0.99,
        }
        row.update(extra)
        rows.append(row)
    return rows


def synthetic_rows(
    tasks: tuple[str, ...] = ("planshape/Reach-v0", "planshape/Push-v0"),
    algos: tuple[str, ...] = ("PPO", "SAC"),
    seeds: int = 4,
) -> list[dict[str, Any]]:
    """A small benchmark: every task x entry of :data:`LEVELS` x algo x seed."""
    rng = np.random.default_rng(0)
    rows = []
    for task in tasks:
        for entry, (success, distance) in LEVELS.items():
            for algo in algos:
                for seed in range(seeds):
                    s = float(np.clip(success + rng.normal(0, 0.1), 0, 1).round(1))
                    d = float(max(distance + rng.normal(0, 0.02), 0.0))
                    invariance = "preserved" if entry == "plan-based/multi" else "not-checked"
                    rows += make_run(task, entry, algo, seed, 1000, s, d, invariance=invariance)
    return rows


def store_run(folder: Path, key: RunKey, profile: Profile) -> str:
    """Write a synthetic finished run of ``key`` into ``folder``'s store as ``profile`` stores
    it: the settings, id and evaluation protocol of :meth:`Profile.spec`; return the id."""
    from planshape.harness.store import ResultStore

    spec = profile.spec(key)
    rows = make_run(
        task=key.task,
        entry=key.entry,
        algo=key.algo,
        seed=key.seed,
        budget=key.budget,
        profile=profile.name,
        eval_protocol=spec.eval_protocol,
        hyperparameters=spec.hyperparameters,
    )
    ResultStore(folder).write(spec.run_id, [{**r, "run_id": spec.run_id} for r in rows])
    return spec.run_id
