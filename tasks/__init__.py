"""Every planshape task, registered with Gymnasium under the ``planshape/`` namespace.

A flat list of registrations under one banner per family: the whole suite on one page.
Entry points are strings, so nothing below imports a simulator until an environment is made.
``planshape tasks`` lists the ids with their models, predicates and reward variants.
"""

from planshape.registration import TaskSpec, register_task

# ---- planar MuJoCo tasks of the source paper: reach, push, maze-reach --------------------------
# Horizons: the paper's 25 steps cannot reach the goal at 0.02 m per step (reach needs 27,
# maze-reach 31); these give a learner room to reach the goal and then stay there. Pass
# max_episode_steps=25 to gymnasium.make for the paper's setting.

register_task(TaskSpec(
    id="planshape/Reach-v0",
    env_entry_point="planshape.tasks.planar.reach:ReachEnv",
    models={
        "single": "planshape.tasks.planar.abstract:reach_single",
        "multi": "planshape.tasks.planar.abstract:reach_multi",
        "grid": "planshape.tasks.planar.abstract:reach_grid",
    },
    default_model="grid",
    max_episode_steps=40,
    description="move the end effector to a goal in the plane and stay there",
))
register_task(TaskSpec(
    id="planshape/Push-v0",
    env_entry_point="planshape.tasks.planar.push:PushEnv",
    models={
        "single": "planshape.tasks.planar.abstract:push_single",
        "multi": "planshape.tasks.planar.abstract:push_multi",
        "grid": "planshape.tasks.planar.abstract:push_grid",
    },
    default_model="grid",
    max_episode_steps=40,
    description="push a box to a goal with the end effector",
))
register_task(TaskSpec(
    id="planshape/MazeReach-v0",
    env_entry_point="planshape.tasks.planar.maze_reach:MazeReachEnv",
    models={
        "single": "planshape.tasks.planar.abstract:maze_reach_single",
        "multi": "planshape.tasks.planar.abstract:maze_reach_multi",
        "grid": "planshape.tasks.planar.abstract:maze_reach_grid",
    },
    default_model="grid",
    max_episode_steps=50,
    description="reach a goal inside three walls, entering from above",
))

# ---- MetaWorld v3 ------------------------------------------------------------------------------

# ---- gymnasium-robotics ----------------------------------------------------------------------

__all__ = ["TaskSpec", "register_task"]
