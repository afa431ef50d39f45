"""Every performance figure of the engine and the tasks, in one run (``python -m planshape.perf``).

* planner: cold plan time and cache-hit time on generated 10x10 and 30x30 grids;
* instances: the planning cost of the task-instance distributions, cold and cached, per
  instance;
* shaping: time per step shaped over unshaped, same environment and actions;
* environments: steps per second of reach, push and maze-reach next to PointMaze;
* invariance: value iteration on an augmented MDP of about 10^6 state-action pairs;
* training: training throughput with shaping over without.

Each section is a script of its own (``python -m planshape.perf.planner`` and so on); they
print figures and never fail on a missed goal, so that the figures are always reported.
"""

from __future__ import annotations

import sys

from planshape.perf import envs, instances, invariance, planner, shaping, training

SECTIONS = [
    ("planner", planner),
    ("instances", instances),
    ("shaping", shaping),
    ("environments", envs),
    ("invariance", invariance),
    ("training", training),
]


def main(argv: list[str] | None = None) -> int:
    del argv  # each section uses its defaults
    for title, module in SECTIONS:
        print(f"\n=== {title} ===", flush=True)
        module.main([])
    return 0


if __name__ == "__main__":
    sys.exit(main())
