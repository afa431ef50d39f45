"""Every planshape task, registered with Gymnasium under the ``planshape/`` namespace.

A flat list of registrations under one banner per family: the whole suite on one page.
Entry points are strings, so nothing below imports a simulator until an environment is made.
``planshape tasks`` lists the ids with their models, predicates and reward variants.
"""

from planshape.invariance.registry import register_toy
from planshape.shaping.registration import TaskSpec, register_task

# ---- planar MuJoCo tasks of the source paper: reach, push, maze-reach --------------------------
# v1 is the paper's code as its main.py ran it (reach behind a wall, push with a cylinder, the
# paper's subgoals and dense rewards); v0 (reach without the wall, push with a square box) stays
# registered for the runs stored with it. Horizons: the paper's 25 steps cannot reach the goal at
# 0.02 m per step (reach-v1's oracle needs 33, maze-reach 35); these give a learner room to reach
# the goal and then stay there. Pass max_episode_steps=25 to gymnasium.make for the paper's
# setting.

register_task(
    TaskSpec(
        id="planshape/Reach-v1",
        family="Reach",
        env_entry_point="planshape.tasks.planar.reach:ReachEnv",
        models={
            "single": "planshape.tasks.planar.paper_models:reach_single",
            "multi": "planshape.tasks.planar.paper_models:reach_multi",
            "grid": "planshape.tasks.planar.paper_models:reach_grid",
        },
        default_model="grid",
        max_episode_steps=50,
        description="move the end effector around a wall to a goal in the plane and stay there",
        kwargs={"version": "v1"},
        fixed=True,
    )
)
register_task(
    TaskSpec(
        id="planshape/Push-v1",
        family="Push",
        env_entry_point="planshape.tasks.planar.push:PushEnv",
        models={
            "single": "planshape.tasks.planar.paper_models:push_single",
            "multi": "planshape.tasks.planar.paper_models:push_multi",
            "grid": "planshape.tasks.planar.paper_models:push_grid_model",
            "grid-diagonal": "planshape.tasks.planar.paper_models:push_grid_diagonal",
        },
        default_model="grid",
        max_episode_steps=40,
        description="push a cylinder to a goal with the end effector",
        kwargs={"version": "v1"},
        fixed=True,
    )
)
register_task(
    TaskSpec(
        id="planshape/MazeReach-v1",
        family="MazeReach",
        env_entry_point="planshape.tasks.planar.maze_reach:MazeReachEnv",
        models={
            "single": "planshape.tasks.planar.paper_models:maze_reach_single",
            "multi": "planshape.tasks.planar.paper_models:maze_reach_multi",
            "grid": "planshape.tasks.planar.paper_models:maze_reach_grid",
        },
        default_model="grid",
        max_episode_steps=50,
        description="reach a goal inside three walls, entering from above",
        kwargs={"version": "v1"},
        fixed=True,
    )
)
# ---- task-instance distributions of the v1 planar tasks -----------------------------------------
# Every episode is one instance (start, goal and, in push, the object's start) from a fixed,
# seeded training set; the benchmark evaluates on the disjoint held-out set. The goal is part of
# the observation, and each instance's PDDL problem is planned by Fast Downward (cached).

register_task(
    TaskSpec(
        id="planshape/ReachRandomized-v1",
        family="ReachRandomized",
        env_entry_point="planshape.tasks.planar.reach:ReachEnv",
        models={
            "single": "planshape.tasks.planar.instances:reach_single",
            "multi": "planshape.tasks.planar.instances:reach_multi",
            "grid": "planshape.tasks.planar.instances:reach_grid",
        },
        default_model="grid",
        max_episode_steps=50,
        description="reach around the wall to a goal drawn behind it, from a start drawn below it",
        kwargs={"version": "v1"},
        instances="planshape.tasks.planar.instances:reach_instances",
    )
)
register_task(
    TaskSpec(
        id="planshape/PushRandomized-v1",
        family="PushRandomized",
        env_entry_point="planshape.tasks.planar.push:PushEnv",
        models={
            "single": "planshape.tasks.planar.instances:push_single",
            "multi": "planshape.tasks.planar.instances:push_multi",
            "grid": "planshape.tasks.planar.instances:push_grid",
            "grid-diagonal": "planshape.tasks.planar.instances:push_grid_diagonal",
        },
        default_model="grid",
        max_episode_steps=60,
        description="push the cylinder to a drawn goal from a drawn start, two or more cells away",
        kwargs={"version": "v1"},
        instances="planshape.tasks.planar.instances:push_instances",
    )
)
register_task(
    TaskSpec(
        id="planshape/MazeReachRandomized-v1",
        family="MazeReachRandomized",
        env_entry_point="planshape.tasks.planar.maze_reach:MazeReachEnv",
        models={
            "single": "planshape.tasks.planar.instances:maze_reach_single",
            "multi": "planshape.tasks.planar.instances:maze_reach_multi",
            "grid": "planshape.tasks.planar.instances:maze_reach_grid",
        },
        default_model="grid",
        max_episode_steps=60,
        description="reach a goal drawn inside the walls from a start drawn outside them",
        kwargs={"version": "v1"},
        instances="planshape.tasks.planar.instances:maze_reach_instances",
    )
)

# ---- v0 of the planar tasks (stored runs) --------------------------------------------------------
# Reach without the paper's wall, push with a square box, straight-distance dense rewards.

register_task(
    TaskSpec(
        id="planshape/Reach-v0",
        family="Reach",
        env_entry_point="planshape.tasks.planar.reach:ReachEnv",
        models={
            "single": "planshape.tasks.planar.abstract:reach_single",
            "multi": "planshape.tasks.planar.abstract:reach_multi",
            "grid": "planshape.tasks.planar.abstract:reach_grid",
        },
        default_model="grid",
        max_episode_steps=40,
        description="v0, without the paper's wall: move the end effector to a goal and stay there",
        fixed=True,
    )
)
register_task(
    TaskSpec(
        id="planshape/Push-v0",
        family="Push",
        env_entry_point="planshape.tasks.planar.push:PushEnv",
        models={
            "single": "planshape.tasks.planar.abstract:push_single",
            "multi": "planshape.tasks.planar.abstract:push_multi",
            "grid": "planshape.tasks.planar.abstract:push_grid",
            "grid-diagonal": "planshape.tasks.planar.abstract:push_grid_diagonal",
        },
        default_model="grid",
        max_episode_steps=40,
        description="v0, with a square box for the paper's cylinder: push it to a goal",
        fixed=True,
    )
)
register_task(
    TaskSpec(
        id="planshape/MazeReach-v0",
        family="MazeReach",
        env_entry_point="planshape.tasks.planar.maze_reach:MazeReachEnv",
        models={
            "single": "planshape.tasks.planar.abstract:maze_reach_single",
            "multi": "planshape.tasks.planar.abstract:maze_reach_multi",
            "grid": "planshape.tasks.planar.abstract:maze_reach_grid",
        },
        default_model="grid",
        max_episode_steps=50,
        description="v0, with the straight-distance dense reward: reach a goal inside three walls",
        fixed=True,
    )
)

# ---- MetaWorld v3 ------------------------------------------------------------------------------

# reach-v4 observes MetaWorld's tcp_center (in the unused second object's slot), so that its
# plan's last subgoal holds on the step of MetaWorld's success; -v3 (estimated from the hand,
# 2-5 steps late) stays for the runs stored with it.
register_task(
    TaskSpec(
        id="planshape/MetaWorld-reach-v4",
        family="MetaWorld",
        env_entry_point="planshape.tasks.metaworld.env:MetaWorldTask",
        models={"stages": "planshape.tasks.metaworld.reach:stages"},
        max_episode_steps=500,
        description="MetaWorld reach-v3 with the fingertip centre observed: move it to a goal",
        kwargs={"env_name": "reach-v3", "observe_tcp": True},
    )
)
register_task(
    TaskSpec(
        id="planshape/MetaWorld-reach-v3",
        family="MetaWorld",
        env_entry_point="planshape.tasks.metaworld.env:MetaWorldTask",
        models={"stages": "planshape.tasks.metaworld.reach:stages_v3"},
        max_episode_steps=500,
        description="MetaWorld reach-v3: move the fingertips to a goal position",
        kwargs={"env_name": "reach-v3"},
    )
)
register_task(
    TaskSpec(
        id="planshape/MetaWorld-push-v3",
        family="MetaWorld",
        env_entry_point="planshape.tasks.metaworld.env:MetaWorldTask",
        models={"stages": "planshape.tasks.metaworld.push:stages"},
        max_episode_steps=500,
        description="MetaWorld push-v3: push a puck to a goal on the table",
        kwargs={"env_name": "push-v3"},
    )
)
register_task(
    TaskSpec(
        id="planshape/MetaWorld-pick-place-v3",
        family="MetaWorld",
        env_entry_point="planshape.tasks.metaworld.env:MetaWorldTask",
        models={"stages": "planshape.tasks.metaworld.pick_place:stages"},
        max_episode_steps=500,
        description="MetaWorld pick-place-v3: grasp a puck, lift it and carry it to a goal",
        kwargs={"env_name": "pick-place-v3"},
    )
)
register_task(
    TaskSpec(
        id="planshape/MetaWorld-door-open-v3",
        family="MetaWorld",
        env_entry_point="planshape.tasks.metaworld.env:MetaWorldTask",
        models={"stages": "planshape.tasks.metaworld.door:stages"},
        max_episode_steps=500,
        description="MetaWorld door-open-v3: hook a door's handle and swing the door open",
        kwargs={"env_name": "door-open-v3"},
    )
)
register_task(
    TaskSpec(
        id="planshape/MetaWorld-drawer-open-v3",
        family="MetaWorld",
        env_entry_point="planshape.tasks.metaworld.env:MetaWorldTask",
        models={"stages": "planshape.tasks.metaworld.drawer:open_stages"},
        max_episode_steps=500,
        description="MetaWorld drawer-open-v3: pull a drawer open by its handle",
        kwargs={"env_name": "drawer-open-v3"},
    )
)
register_task(
    TaskSpec(
        id="planshape/MetaWorld-drawer-close-v3",
        family="MetaWorld",
        env_entry_point="planshape.tasks.metaworld.env:MetaWorldTask",
        models={"stages": "planshape.tasks.metaworld.drawer:close_stages"},
        max_episode_steps=500,
        description="MetaWorld drawer-close-v3: push an open drawer shut",
        kwargs={"env_name": "drawer-close-v3"},
    )
)
register_task(
    TaskSpec(
        id="planshape/MetaWorld-button-press-topdown-v3",
        family="MetaWorld",
        env_entry_point="planshape.tasks.metaworld.env:MetaWorldTask",
        models={
            "stages": "planshape.tasks.metaworld.button:topdown_stages",
            "stages-above": "planshape.tasks.metaworld.button:topdown_stages_above",
        },
        max_episode_steps=500,
        description="MetaWorld button-press-topdown-v3: press a button down from above",
        kwargs={"env_name": "button-press-topdown-v3"},
    )
)
register_task(
    TaskSpec(
        id="planshape/MetaWorld-window-open-v3",
        family="MetaWorld",
        env_entry_point="planshape.tasks.metaworld.env:MetaWorldTask",
        models={"stages": "planshape.tasks.metaworld.window:open_stages"},
        max_episode_steps=500,
        description="MetaWorld window-open-v3: slide a window open by its handle",
        kwargs={"env_name": "window-open-v3"},
    )
)
register_task(
    TaskSpec(
        id="planshape/MetaWorld-window-close-v3",
        family="MetaWorld",
        env_entry_point="planshape.tasks.metaworld.env:MetaWorldTask",
        models={"stages": "planshape.tasks.metaworld.window:close_stages"},
        max_episode_steps=500,
        description="MetaWorld window-close-v3: slide an open window shut by its handle",
        kwargs={"env_name": "window-close-v3"},
    )
)
register_task(
    TaskSpec(
        id="planshape/MetaWorld-button-press-v3",
        family="MetaWorld",
        env_entry_point="planshape.tasks.metaworld.env:MetaWorldTask",
        models={"stages": "planshape.tasks.metaworld.button:front_stages"},
        max_episode_steps=500,
        description="MetaWorld button-press-v3: push a wall-mounted button in from the front",
        kwargs={"env_name": "button-press-v3"},
    )
)
register_task(
    TaskSpec(
        id="planshape/MetaWorld-handle-press-v3",
        family="MetaWorld",
        env_entry_point="planshape.tasks.metaworld.env:MetaWorldTask",
        models={"stages": "planshape.tasks.metaworld.handle:stages"},
        max_episode_steps=500,
        description="MetaWorld handle-press-v3: press a lever's handle down from above",
        kwargs={"env_name": "handle-press-v3"},
    )
)
register_task(
    TaskSpec(
        id="planshape/MetaWorld-plate-slide-v3",
        family="MetaWorld",
        env_entry_point="planshape.tasks.metaworld.env:MetaWorldTask",
        models={"stages": "planshape.tasks.metaworld.plate:stages"},
        max_episode_steps=500,
        description="MetaWorld plate-slide-v3: slide a plate across the table into a goal",
        kwargs={"env_name": "plate-slide-v3"},
    )
)
register_task(
    TaskSpec(
        id="planshape/MetaWorld-faucet-open-v3",
        family="MetaWorld",
        env_entry_point="planshape.tasks.metaworld.env:MetaWorldTask",
        models={"stages": "planshape.tasks.metaworld.faucet:stages"},
        max_episode_steps=500,
        description="MetaWorld faucet-open-v3: swing a faucet's handle round to open it",
        kwargs={"env_name": "faucet-open-v3"},
    )
)

# ---- gymnasium-robotics ----------------------------------------------------------------------

register_task(
    TaskSpec(
        id="planshape/PointMaze_UMaze-v3",
        family="PointMaze",
        env_entry_point="planshape.tasks.point_maze:point_maze",
        models={"grid": "planshape.tasks.point_maze:umaze_grid"},
        max_episode_steps=300,
        description="PointMaze UMaze: roll a ball round the U from its start cell to the goal",
        kwargs={"maze": "UMaze"},
    )
)
register_task(
    TaskSpec(
        id="planshape/PointMaze_Medium-v3",
        family="PointMaze",
        env_entry_point="planshape.tasks.point_maze:point_maze",
        models={"grid": "planshape.tasks.point_maze:medium_grid"},
        max_episode_steps=600,
        description="PointMaze Medium: roll a ball across the 8x8 maze, corner to corner",
        kwargs={"maze": "Medium"},
    )
)
register_task(
    TaskSpec(
        id="planshape/FetchReach-v4",
        family="FetchReach",
        env_entry_point="planshape.tasks.fetch:fetch",
        models={"stages": "planshape.tasks.fetch:fetch_reach_stages"},
        max_episode_steps=50,
        description="Fetch arm: move the gripper to a goal position",
        kwargs={"env_id": "FetchReach-v4"},
    )
)
register_task(
    TaskSpec(
        id="planshape/FetchPush-v4",
        family="FetchPush",
        env_entry_point="planshape.tasks.fetch:fetch",
        models={"stages": "planshape.tasks.fetch:fetch_push_stages"},
        max_episode_steps=50,
        description="Fetch arm: push a block to a goal on the table",
        kwargs={"env_id": "FetchPush-v4"},
    )
)

# ---- toy MDPs of the planar tasks, for planshape check-invariance -----------------------------
# Tabular reach, maze-reach and push on the tasks' own grid models, classifiers and hooks
# (planshape.tasks.planar.toys); the checker's random toys are the engine's own.

register_toy(
    "reach",
    "planshape.tasks.planar.toys:reach",
    "planar reach, real grid model (143 cells), reach and stay (continuing), γ=0.95",
)
register_toy(
    "reach-episodic",
    "planshape.tasks.planar.toys:reach_episodic",
    "planar reach, real grid model, the goal terminates the episode, γ=0.95",
)
register_toy(
    "maze-reach",
    "planshape.tasks.planar.toys:maze_reach",
    "planar maze-reach, real grid model with walls, 10% slip, continuing, γ=0.95",
)
register_toy(
    "reach-instance",
    "planshape.tasks.planar.toys:reach_instance",
    "planar reach-v1, one held-out instance of the distribution: wall, drawn goal, continuing",
)
register_toy(
    "push",
    "planshape.tasks.planar.toys:push",
    "planar push, Sokoban-like grid model on 0.12 m cells, box at goal terminates, γ=0.9",
)

__all__ = ["TaskSpec", "register_task"]
