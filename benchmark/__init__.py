"""planshape: automatic reward densification with classical planning, as a benchmark suite.

Importing the package registers the reference potentials (``planshape.baselines``) and the
tasks (``planshape.tasks``) under the ``planshape/`` Gymnasium namespace. Registrations are
strings: no task module, simulator or planner is loaded until something is made.

Example:
    >>> import gymnasium, planshape
    >>> env = gymnasium.make("planshape/Reach-v0")  # doctest: +SKIP
"""

from planshape import baselines as _baselines  # noqa: F401  (registers reference potentials)
from planshape import tasks as _tasks  # noqa: F401  (registers tasks with Gymnasium)

__version__ = "0.1.0"
