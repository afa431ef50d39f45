"""The planar MuJoCo tasks of the source paper (section 5.1): reach, push and maze-reach.

Plain Gymnasium environments with the paper's sparse reward (or a hand-crafted dense one),
their geometry as one importable object, and a scripted oracle per task. Shaping and the PDDL
models are wired in by the task registration, not here.

=================  ==========================================  =======================
entry point        observation                                 task distance
=================  ==========================================  =======================
``reach``          ``(x_e, y_e)``                              end effector → goal
``push``           ``(x_e, y_e, x_o, y_o)``                    box → goal
``maze_reach``     ``(x_e, y_e)``                              end effector → goal
=================  ==========================================  =======================

Entry points: ``"planshape.tasks.planar.reach:ReachEnv"``,
``"planshape.tasks.planar.push:PushEnv"``, ``"planshape.tasks.planar.maze_reach:MazeReachEnv"``.
The environments never end an episode themselves; register them with ``max_episode_steps``
(see :data:`RECOMMENDED_HORIZONS`).

Horizons. The paper ran every task for 25 steps. At 0.02 m per axis per step that is too short
for two of them: reach needs at least 27 steps (the goal is 0.58 m above the start, success
needs 0.53 m of it at 0.02 m per step), and maze-reach at least 31 (up 0.49 m to clear the
walls, down 0.12 m into the goal); push fits (the oracle needs 23). The oracles' first
successes from the paper's start are in :data:`ORACLE_STEPS`; :data:`RECOMMENDED_HORIZONS`
gives each task about 1.5 times that, so that a learner can succeed and then has to *stay*.

Example:
    >>> import gymnasium
    >>> gymnasium.register("doc/PlanarReach-v0", "planshape.tasks.planar.reach:ReachEnv",
    ...                    max_episode_steps=25)
    >>> env = gymnasium.make("doc/PlanarReach-v0", reward="dense")
    >>> obs, info = env.reset(seed=0)
    >>> sorted(info)
    ['distance', 'ee_position', 'goal_position', 'move_rejected', 'success']
"""

from planshape.tasks.planar.base import REWARD_VARIANTS, PlanarEnv
from planshape.tasks.planar.geometry import GEOMETRY, PlanarGeometry, Rect
from planshape.tasks.planar.maze_reach import MazeReachEnv
from planshape.tasks.planar.model import PHYSICS, PlanarPhysics, planar_mjcf
from planshape.tasks.planar.oracle import (
    ORACLES,
    OracleRun,
    maze_reach_oracle,
    push_oracle,
    reach_oracle,
    run_oracle,
)
from planshape.tasks.planar.push import PushEnv
from planshape.tasks.planar.reach import ReachEnv

PAPER_HORIZON = 25
"""The episode length of the paper (25 steps for all three tasks)."""

ORACLE_STEPS: dict[str, int] = {"reach": 27, "push": 23, "maze-reach": 35}
"""Step at which each v0 task's oracle first succeeds from the paper's start (checked by the
tests). Lower bounds: reach 27, maze-reach 31. In v1 (the paper's wall and cylinder) the
oracles first succeed at 33 (reach), 27 (push) and 35 (maze-reach) steps, and the tasks are
registered with 50, 40 and 50 steps."""

RECOMMENDED_HORIZONS: dict[str, int] = {"reach": 40, "push": 40, "maze-reach": 50}
"""``max_episode_steps`` recommended per task: about 1.5 × :data:`ORACLE_STEPS`. Push alone
is also solvable within the paper's 25 steps, with 2 steps to spare."""

__all__ = [
    "GEOMETRY",
    "ORACLES",
    "ORACLE_STEPS",
    "PAPER_HORIZON",
    "PHYSICS",
    "RECOMMENDED_HORIZONS",
    "REWARD_VARIANTS",
    "MazeReachEnv",
    "OracleRun",
    "PlanarEnv",
    "PlanarGeometry",
    "PlanarPhysics",
    "PushEnv",
    "ReachEnv",
    "Rect",
    "maze_reach_oracle",
    "planar_mjcf",
    "push_oracle",
    "reach_oracle",
    "run_oracle",
]
