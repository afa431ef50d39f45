"""Timings of the invariance checker on an augmented MDP of about 10^6 state-action pairs.

Run ``python -m planshape.perf.invariance [--cell 0.055] [--gammas 0.9 0.99] [--horizon 30]``.
It builds the push toy on a grid of ``--cell`` metre cells (0.055: 14 280 (ee, box) states,
16 progress values, 5 actions: 1 142 400 augmented state-action pairs; 0.05 is the real
``push_grid()`` resolution, 2.0 million) and prints, each timed on its own:

* build: the tabular MDP (states, transitions, observations) and its plan (Fast Downward,
  cached on disk after the first run);
* augment: the (s, max_idx) MDP: one batched ``PlanProgress.advance`` over every
  (progress, observation) pair and the relabelled sparse transitions;
* potential: φ of every augmented state through ``ShapingContext`` (plan-based and
  distance-varying), one Python call per state;
* value iteration on the augmented MDP with the shaped reward, from zero, for each γ
  (iterations, seconds; the goal is 5 s on one core), with the Jacobi backup the checker uses
  and, for comparison, the ordinary one; and backward induction over ``--horizon`` layers.

The process pins itself to one CPU (``os.sched_setaffinity``) and asks for one BLAS/OpenMP
thread; sparse products and NumPy reductions are single-threaded anyway. This is a measurement
script, not a test: numbers depend on the machine.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from collections.abc import Sequence  # noqa: E402

import numpy as np  # noqa: E402

GOAL_SECONDS = 5.0


def _pin_one_cpu() -> str:
    try:
        cpu = min(os.sched_getaffinity(0))
        os.sched_setaffinity(0, {cpu})
        return f"pinned to CPU {cpu}"
    except (AttributeError, OSError):  # not Linux
        return "not pinned (no sched_setaffinity here)"


def _timed(function):
    started = time.perf_counter()
    result = function()
    return result, time.perf_counter() - started


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m planshape.perf.invariance")
    parser.add_argument("--cell", type=float, default=0.055, help="push grid cell side (m)")
    parser.add_argument("--gammas", type=float, nargs="+", default=[0.9, 0.99])
    parser.add_argument("--horizon", type=int, default=30)
    args = parser.parse_args(argv)
    pinned = _pin_one_cpu()

    from planshape.invariance.registry import TOYS
    from planshape.invariance.shaped import PotentialBased, Step
    from planshape.invariance.solve import backward_induction, value_iteration
    from planshape.shaping.potentials import load_reference

    push = load_reference(TOYS["push"][0])  # the push toy's builder, at a finer cell side
    toy, build_s = _timed(lambda: push(cell=args.cell))
    aug, augment_s = _timed(lambda: toy.augmented)
    mdp = aug.mdp
    print(f"invariance checker timings, {pinned}; goal: value iteration ≤ {GOAL_SECONDS:g} s")
    print(
        f"push toy, {args.cell:g} m cells: {toy.mdp.n_states} states x {aug.n_progress} progress "
        f"= {aug.n_states} augmented states, {mdp.n_pairs} state-action pairs, "
        f"{mdp.transitions.nnz} transitions"
    )
    print(f"  build (tabular MDP + plan)      {build_s:8.3f} s")
    print(f"  augment (advance batch + CSR)   {augment_s:8.3f} s")
    shapings = {name: PotentialBased(name) for name in ("plan-based", "distance-varying")}
    for name, shaping in shapings.items():
        _, potential_s = _timed(lambda s=shaping: s.values(aug, 0, time_dependent=False))
        rate = aug.n_states / potential_s
        print(f"  potential {name:<21} {potential_s:8.3f} s ({rate:,.0f} states/s)")
    r = aug.lift(toy.mdp.expected_reward())
    dynamics, dynamics_s = _timed(lambda: mdp.dynamics)
    print(f"  continuation, action-major      {dynamics_s:8.3f} s")
    worst = 0.0
    for gamma in args.gammas:
        bonus, bonus_s = _timed(
            lambda g=gamma: shapings["distance-varying"].expected(aug, Step(0, 0, g, 1))
        )
        print(f"  γ={gamma:g}: shaping term (distance-varying)  {bonus_s:.3f} s")
        for jacobi in (True, False):
            result, vi_s = _timed(
                lambda g=gamma, b=bonus, j=jacobi: value_iteration(dynamics, r + b, g, jacobi=j)
            )
            if jacobi:
                worst = max(worst, vi_s)
            print(
                f"    value iteration, {'Jacobi' if jacobi else 'ordinary'} backup"
                f"{'' if jacobi else ' (for comparison)'}: {vi_s:.3f} s, {result.iterations} "
                f"backups ({1e3 * vi_s / result.iterations:.2f} ms each), bound "
                f"{result.error_bound:.1e}"
            )
    layers, bi_s = _timed(
        lambda: sum(1 for _ in backward_induction(dynamics, lambda t: r, 1.0, args.horizon))
    )
    print(f"  backward induction H={layers:<3d}        {bi_s:8.3f} s")
    verdict = "met" if worst <= GOAL_SECONDS else "NOT met"
    print(f"goal {verdict}: slowest value iteration {worst:.3f} s (≤ {GOAL_SECONDS:g} s)")
    return 0 if np.isfinite(worst) else 1


if __name__ == "__main__":
    sys.exit(main())
