"""What a benchmark selection costs before it trains: ``planshape bench --dry-run``.

The estimate of one run is ``budget / training rate + evaluation points × episodes × seconds
per evaluated episode``, from measured rates (:data:`TRAINING_RATE`,
:data:`EVALUATION_SECONDS`); the selection's wall time is the sum over its runs divided by the
workers. Rates are per run while another run trains beside it on the 2-core machine, so the
estimate is for ``--workers 2`` there.

Example:
    >>> from planshape.harness.profiles import PROFILES
    >>> rows, total = estimate(list(PROFILES["smoke"].runs()), PROFILES["smoke"], workers=1)
    >>> rows[0]["runs"], rows[0]["algo"], round(total) > 0
    (3, 'PPO', True)
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Sequence
from typing import Any

from planshape.harness.profiles import Profile, RunKey
from planshape.harness.runner import evaluation_episodes

#: training steps per second of one run beside another on 2 cores, by (family, algorithm):
#: the medians of the stored runs' ``steps_per_s`` — planar PPO and SBX-SAC from the v1 default
#: leaderboard (leaderboard/: PPO 5,589 on Reach-v1 and 5,949 on MazeReach-v1, SBX-SAC 579 on
#: Push-v1 with 4 × 4 updates; its 95 runs took 45 min 26 s against 47 estimated with the
#: rates before), SAC and MetaWorld PPO from leaderboard/default-v0 and metaworld-v0 (SAC
#: 132-171, MetaWorld PPO 1,051);
#: SBX-PPO is PPO's times the side-by-side ratio of ``python -m planshape.perf.training``
#: (1.15); SB3's SAC rate was measured with one gradient step every step (the v0 table);
#: SAC-default (SB3's SAC with the library's [256, 256] networks and one gradient step per
#: step) from its first stored run, reach dense seed 2 at 100,000 steps: 35.9 steps/s while it
#: had 0.68 of a core (31.5 CPU minutes in 46.4 minutes of wall time, the machine shared with
#: other jobs), so about 53 beside one other run; MetaWorld SBX-SAC ([256, 256], one gradient
#: step per step) from ``planshape probe planshape/MetaWorld-reach-v4 dense --algo SBX-SAC
#: --budget 200000 --chunks 10`` beside one other run: 25.5 minutes, 44 s of it evaluation, but
#: the metaworld-holdout screens on a 2-core machine of the same kind (2026-12) ran at 40-55
#: (median 47; 62-88 minutes a 200,000-step run beside another, and about 85 alone, so a
#: second worker adds nothing there): the estimate takes the slower, recent rate
TRAINING_RATE: dict[tuple[str, str], float] = {
    ("planar", "PPO"): 5700.0,
    ("planar", "SAC"): 150.0,
    ("planar", "SAC-default"): 53.0,
    ("planar", "SBX-SAC"): 580.0,
    ("planar", "SBX-PPO"): 5200.0,
    ("MetaWorld", "PPO"): 1050.0,
    ("MetaWorld", "SBX-SAC"): 47.0,
}
#: seconds per evaluated episode of the deterministic policy (stored runs: wall time not spent
#: training, per evaluated episode; planar 0.011-0.016 s, MetaWorld 0.40 s)
EVALUATION_SECONDS: dict[str, float] = {"planar": 0.014, "MetaWorld": 0.40}

_PLANAR = ("Reach", "Push", "MazeReach")


def family(task: str) -> str:
    """``"planar"`` for reach, push and maze-reach (every version and distribution), else the
    family the task is registered with (``"MetaWorld"``)."""
    from planshape.training.hyperparams import family as registered_family

    name = registered_family(task)
    return "planar" if name.removesuffix("Randomized") in _PLANAR else name


def run_seconds(key: RunKey, profile: Profile) -> float | None:
    """The estimated wall time of one run, or None without a measured training rate."""
    rate = TRAINING_RATE.get((family(key.task), key.algo))
    per_episode = EVALUATION_SECONDS.get(family(key.task))
    if rate is None or per_episode is None:
        return None
    points = key.budget // profile.eval_every + 2
    episodes = len(evaluation_episodes(key.task, profile.eval_episodes))
    return key.budget / rate + points * episodes * per_episode


def estimate(
    keys: Sequence[RunKey], profile: Profile, workers: int
) -> tuple[list[dict[str, Any]], float]:
    """One row per (task, algorithm) of ``keys`` — runs, environment steps, estimated minutes
    (None without a measured rate) — and the estimated wall time of them all in seconds."""
    groups: dict[tuple[str, str], list[RunKey]] = defaultdict(list)
    for key in keys:
        groups[(key.task, key.algo)].append(key)
    rows, total = [], 0.0
    for (task, algo), group in sorted(groups.items()):
        seconds = [run_seconds(k, profile) for k in group]
        known = None if any(s is None for s in seconds) else sum(s or 0.0 for s in seconds)
        total += known or 0.0
        rows.append(
            {
                "task": task,
                "algo": algo,
                "runs": len(group),
                "steps": sum(k.budget for k in group),
                "minutes": None if known is None else known / 60,
            }
        )
    return rows, total / max(workers, 1)


def render(rows: Sequence[dict[str, Any]], total: float, workers: int) -> str:
    lines = [f"{'task':36s} {'algo':11s} {'runs':>5s} {'env steps':>12s} {'est. min':>9s}"]
    for r in rows:
        minutes = "no rate" if r["minutes"] is None else f"{r['minutes']:.1f}"
        lines.append(
            f"{r['task']:36s} {r['algo']:11s} {r['runs']:5d} {r['steps']:12,d} {minutes:>9s}"
        )
    unknown = [f"{r['task']} {r['algo']}" for r in rows if r["minutes"] is None]
    lines.append(
        f"{sum(r['runs'] for r in rows)} runs; estimated wall time {total / 60:.0f} minutes with "
        f"{workers} workers (rates measured on 2 cores: planshape.harness.estimate)"
    )
    if unknown:
        lines.append("not in the estimate (no measured rate): " + ", ".join(unknown))
    return "\n".join(lines)
