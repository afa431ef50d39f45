"""planshape: automatic reward densification with classical planning, as a benchmark suite.

Importing the package registers the reference potentials (``planshape.baselines``) and the
tasks (``planshape.tasks``) under the ``planshape/`` Gymnasium namespace. Registrations are
strings: no task module, simulator or planner is loaded until something is made.

The map: each top-level folder of the repository is one import, and inside the engine
(``benchmark/``, imported as ``planshape``) the subpackages follow the data path of a shaped
step, from the PDDL model to the leaderboard::

    folder                  import                  job
    benchmark/planning/     planshape.planning      PDDL parsing, Fast Downward, plan cache,
                                                    plan -> subgoal states
    benchmark/shaping/      planshape.shaping       classifiers -> abstract state -> progress
                                                    -> potential φ -> F = γ·φ(s') − φ(s);
                                                    task registration and shape()
    benchmark/invariance/   planshape.invariance    toy MDPs solved exactly: is the optimal
                                                    policy kept?
    benchmark/training/     planshape.training      learners (SB3, SBX), hyperparameters
    benchmark/harness/      planshape.harness       runs, profiles, the store, bench, probe
    benchmark/results/      planshape.results       stored rows as data, scoring, leaderboard
    benchmark/perf/         planshape.perf          performance scripts
    benchmark/suite/        planshape.suite         the pytest-style benchmark suite
    benchmark/cli.py        planshape.cli           the ``planshape`` command (its
                                                    subcommands: planshape.commands)
    tasks/                  planshape.tasks         one module per task family
    baselines/              planshape.baselines     the reference potentials
    pddl/                   planshape.pddl_files    domain and problem files

The engine never imports a task or a baseline: they register themselves (``module:attr``
strings) and the engine reaches them through the registries.

Example:
    >>> import gymnasium, planshape
    >>> env = gymnasium.make("planshape/Reach-v0")  # doctest: +SKIP
"""

from planshape import baselines as _baselines  # noqa: F401  (registers reference potentials)
from planshape import tasks as _tasks  # noqa: F401  (registers tasks with Gymnasium)

__version__ = "0.1.0"
