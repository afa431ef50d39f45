"""Timings of the planning stage on generated grids: parse, cold plan, cache hit.

Run ``python -m planshape.perf.planner [--repeats N] [--sizes 10 30]``. For each n x n grid
(start in one corner, goal in the opposite one) it prints:

* parse: :func:`parse_task` on the PDDL text (median of a few runs, the grammar already built);
* cold: :func:`solve` with an empty cache (parse + Fast Downward + validation + cache write), and
  the planner's share of it;
* hit: :func:`solve` answered by the cache (median of ``--repeats`` runs), the target being
  under 1 ms; and hit + states, the same followed by building every full subgoal state (which
  :class:`SubgoalStates` otherwise defers until a state is used).

This is a measurement script, not a test: numbers depend on the machine.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from collections.abc import Callable, Sequence
from pathlib import Path

from planshape.planning import grid_pddl, parse_task, solve

HIT_TARGET_MS = 1.0


def _median_seconds(function: Callable[[], object], repeats: int) -> float:
    samples = []
    for _ in range(repeats):
        started = time.perf_counter()
        function()
        samples.append(time.perf_counter() - started)
    return statistics.median(samples)


def measure(size: int, repeats: int, search: str) -> dict[str, float | int | str]:
    """One row of the table for an ``size`` x ``size`` grid."""
    grid = grid_pddl(size, size, start=(0, 0), goal=(size - 1, size - 1))
    parse = parse_task.__wrapped__  # the memoized function's body: parse for real every time
    parse_s = _median_seconds(lambda: parse(grid.domain, grid.problem), repeats=3)
    with tempfile.TemporaryDirectory(prefix="planshape-perf-") as tmp:
        domain, problem = grid.write(tmp, stem=f"grid-{size}x{size}")
        cache = Path(tmp) / "plans"
        parse_task.cache_clear()
        started = time.perf_counter()
        plan = solve(domain, problem, search=search, cache_dir=cache)
        cold_s = time.perf_counter() - started
        assert not plan.from_cache
        hit_s = _median_seconds(
            lambda: solve(domain, problem, search=search, cache_dir=cache), repeats
        )
        assert solve(domain, problem, search=search, cache_dir=cache).from_cache
        states_s = _median_seconds(
            lambda: list(solve(domain, problem, search=search, cache_dir=cache).subgoals),
            max(10, repeats // 10),
        )
    return {
        "problem": f"grid {size}x{size}",
        "atoms": len(plan.subgoals[0]),
        "steps": plan.length,
        "parse_s": parse_s,
        "cold_s": cold_s,
        "planner_s": plan.planner_seconds,
        "hit_ms": hit_s * 1e3,
        "states_ms": states_s * 1e3,
    }


def render(rows: Sequence[dict[str, float | int | str]], search: str, repeats: int) -> str:
    """The table printed by :func:`main`."""
    header = (
        f"{'problem':<12} {'atoms':>6} {'steps':>5} {'parse s':>8} {'cold s':>7} "
        f"{'FD s':>6} {'hit ms':>7} {'hit+states ms':>13}"
    )
    lines = [
        f"planning stage, search {search}; hit = median of {repeats} cache hits "
        f"(target < {HIT_TARGET_MS:g} ms)",
        header,
        "-" * len(header),
    ]
    for r in rows:
        lines.append(
            f"{r['problem']:<12} {r['atoms']:>6} {r['steps']:>5} {r['parse_s']:>8.3f} "
            f"{r['cold_s']:>7.3f} {r['planner_s']:>6.3f} {r['hit_ms']:>7.3f} "
            f"{r['states_ms']:>13.2f}"
        )
    slow = [str(r["problem"]) for r in rows if float(r["hit_ms"]) >= HIT_TARGET_MS]
    lines.append("cache hits under target: " + ("yes" if not slow else f"NO ({', '.join(slow)})"))
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m planshape.perf.planner", description=__doc__)
    parser.add_argument("--sizes", type=int, nargs="+", default=[10, 30], metavar="N")
    parser.add_argument("--repeats", type=int, default=500, help="cache hits to time")
    parser.add_argument("--search", default="astar-lmcut")
    args = parser.parse_args(argv)
    parse_task.__wrapped__(*grid_pddl(1, 2, start=(0, 0), goal=(0, 1)).texts)  # build grammar
    rows = [measure(size, args.repeats, args.search) for size in args.sizes]
    print(render(rows, args.search, args.repeats))
    return 0


if __name__ == "__main__":
    sys.exit(main())
