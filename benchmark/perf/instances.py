"""Planning cost of the task-instance distributions: every instance has its own PDDL problem.

Run ``python -m planshape.perf.instances [--tasks ...] [--limit N]`` (``--limit`` instances per
model, 20 by default; ``--limit 150`` binds every training and held-out instance, about 15 minutes
on 2 cores). For each randomized task
and model it binds every instance's plan (generate the problem, parse it, plan it with Fast
Downward, build the classifiers' progress tracker) and prints:

* cold: with an empty plan cache (a fresh ``$PLANSHAPE_CACHE_DIR``), the total over the
  instances, the mean and the largest per instance;
* cached: the same in a fresh process state but with the plans on disk (what every later
  benchmark run pays once per instance and process), mean per instance;
* reset: the shaping wrapper's lookup of an instance already bound in the process (what every
  ``reset`` pays), mean.

The single and multi models of reach and maze-reach share one problem file across instances
(only the classifiers' places change), so they plan once. This is a measurement script, not a
test: numbers depend on the machine.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from collections.abc import Sequence

from planshape.planning import parse_task
from planshape.shaping.registration import (
    _instance_plan,
    _planned,
    instance_plan,
    instance_set,
    task_spec,
)

TASKS = (
    "planshape/ReachRandomized-v1",
    "planshape/PushRandomized-v1",
    "planshape/MazeReachRandomized-v1",
)


def _clear_process_caches() -> None:
    _instance_plan.cache_clear()
    _planned.cache_clear()
    parse_task.cache_clear()


def _bind_all(task: str, model: str, instances: Sequence[object]) -> list[float]:
    """Seconds to bind each instance's plan."""
    seconds = []
    for instance in instances:
        started = time.perf_counter()
        instance_plan(task, model, instance)
        seconds.append(time.perf_counter() - started)
    return seconds


def measure(task: str, model: str, limit: int | None) -> dict[str, float | int | str]:
    """One row: cold, cached and per-reset binding costs of ``model``'s instance plans."""
    sets = instance_set(task_spec(task))
    instances = list(sets.train + sets.eval)[:limit]
    previous = os.environ.get("PLANSHAPE_CACHE_DIR")
    with tempfile.TemporaryDirectory(prefix="planshape-perf-instances-") as cache:
        os.environ["PLANSHAPE_CACHE_DIR"] = cache
        try:
            _clear_process_caches()
            cold = _bind_all(task, model, instances)
            _clear_process_caches()
            cached = _bind_all(task, model, instances)
            started = time.perf_counter()
            for instance in instances:
                instance_plan(task, model, instance)
            reset_s = (time.perf_counter() - started) / len(instances)
        finally:
            if previous is None:
                os.environ.pop("PLANSHAPE_CACHE_DIR", None)
            else:
                os.environ["PLANSHAPE_CACHE_DIR"] = previous
            _clear_process_caches()
    return {
        "task": task,
        "model": model,
        "instances": len(instances),
        "cold_total_s": sum(cold),
        "cold_mean_s": statistics.mean(cold),
        "cold_max_s": max(cold),
        "cached_mean_ms": statistics.mean(cached) * 1e3,
        "reset_us": reset_s * 1e6,
    }


def render(rows: Sequence[dict[str, float | int | str]]) -> str:
    header = (
        f"{'task':<34} {'model':<14} {'n':>4} {'cold total s':>12} {'cold/inst s':>11} "
        f"{'cold max s':>10} {'cached/inst ms':>14} {'reset µs':>9}"
    )
    lines = ["planning cost per instance (bind = generate, parse, plan, track)", header]
    lines.append("-" * len(header))
    for r in rows:
        lines.append(
            f"{r['task']:<34} {r['model']:<14} {r['instances']:>4} {r['cold_total_s']:>12.2f} "
            f"{r['cold_mean_s']:>11.3f} {r['cold_max_s']:>10.3f} {r['cached_mean_ms']:>14.2f} "
            f"{r['reset_us']:>9.2f}"
        )
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m planshape.perf.instances", description=__doc__)
    parser.add_argument("--tasks", nargs="+", default=list(TASKS), metavar="ID")
    parser.add_argument("--limit", type=int, default=20, help="instances per model (%(default)s)")
    args = parser.parse_args(argv)
    rows = [
        measure(task, model, args.limit) for task in args.tasks for model in task_spec(task).models
    ]
    print(render(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
