"""The ``-v1`` planar tasks are the source paper's (its ``main.py`` and ``envs/*_task.py``):
every constant taken from the paper is pinned here, and the behaviours that differ from v0
(reach's wall, push's cylinder, the paper's dense rewards and subgoals) are checked."""

from __future__ import annotations

import math
import warnings

import gymnasium
import mujoco
import numpy as np
import pytest

import planshape  # noqa: F401  (registers the tasks)
from planshape.tasks.planar import MazeReachEnv, PushEnv, ReachEnv, run_oracle
from planshape.tasks.planar.geometry import GEOMETRY, PAPER_GEOMETRY
from planshape.tasks.planar.model import PAPER_PHYSICS, PHYSICS
from planshape.tasks.planar.paper_models import PAPER_SUBGOALS, PUSH_CELL
from planshape.tasks.planar.versions import VERSIONS

UP = np.array([0.0, 1.0], dtype=np.float32)
STILL = np.zeros(2, dtype=np.float32)
V1 = {
    "reach": "planshape/Reach-v1",
    "push": "planshape/Push-v1",
    "maze-reach": "planshape/MazeReach-v1",
}


def test_every_constant_taken_from_the_paper() -> None:
    g = PAPER_GEOMETRY
    # the workspace, start, goals, step and success radius of all three tasks (unchanged in v1)
    assert (g.workspace.low, g.workspace.high) == ((0.23, -0.35), (0.78, 0.30))
    assert (g.ee_start, g.step_size, g.success_threshold) == ((0.45, -0.32), 0.02, 0.05)
    assert (g.reach_goal, g.box_start, g.box_goal, g.maze_goal) == (
        (0.50, 0.26),
        (0.35, -0.10),
        (0.50, 0.20),
        (0.50, 0.00),
    )
    # reaching_task.py with_obstacle=True: load_geom("box", size=[0.18, 0.01, 0.1], pos [0.5, 0.15])
    assert [(w.center, w.half_extents) for w in g.reach_walls] == [((0.5, 0.15), (0.18, 0.01))]
    # complex_reaching_task.py: the three maze walls
    assert [(w.center, w.half_extents) for w in g.maze_walls] == [
        ((0.50, -0.20), (0.10, 0.01)),
        ((0.40, -0.03), (0.01, 0.18)),
        ((0.60, -0.03), (0.01, 0.18)),
    ]
    # pushing_task.py: load_geom("cylinder", size=[0.05, 0.05], mass=1.), lateralFriction=0.9
    assert g.object_radius == 0.05
    assert (PAPER_PHYSICS.box_mass, PAPER_PHYSICS.box_friction) == (1.0, 0.9)
    # _subgoal*_pos of reaching_task.py and complex_reaching_task.py
    assert PAPER_SUBGOALS["reach"] == {
        "subgoal1": ((0.36, 0.0), (0.64, 0.0)),
        "subgoal2": ((0.23, 0.15), (0.76, 0.15)),
        "subgoal3": ((0.36, 0.26), (0.64, 0.26)),
    }
    assert PAPER_SUBGOALS["maze-reach"] == {
        "subgoal1": ((0.28, -0.08), (0.73, -0.08)),
        "subgoal2": ((0.40, 0.23), (0.60, 0.23)),
        "subgoal3": ((0.45, 0.10), (0.55, 0.10)),
    }
    assert g.reach_detour == PAPER_SUBGOALS["reach"]["subgoal2"]
    assert g.maze_detour == PAPER_SUBGOALS["maze-reach"]["subgoal2"]


def test_versions_and_registrations() -> None:
    assert VERSIONS["v0"].geometry is GEOMETRY and VERSIONS["v1"].geometry is PAPER_GEOMETRY
    assert GEOMETRY.reach_walls == () and GEOMETRY.object_radius is None  # v0 is unchanged
    for task, env_id in V1.items():
        env = gymnasium.make(env_id)
        assert env.unwrapped.version == "v1" and env.unwrapped.task == task
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # v0 is out of date, which Gymnasium says
            assert gymnasium.make(env_id.replace("-v1", "-v0")).unwrapped.version == "v0"


def test_v1_physics_moves_the_end_effector_as_v0() -> None:
    """The paper's 1 kg object comes with masses and damping scaled alike: kp/m and m/c are
    those of v0, so a free end effector follows the same trajectory."""
    assert PAPER_PHYSICS.servo_kp / PAPER_PHYSICS.ee_mass == PHYSICS.servo_kp / PHYSICS.ee_mass
    assert PAPER_PHYSICS.box_mass / PAPER_PHYSICS.box_damping == pytest.approx(
        PHYSICS.box_mass / PHYSICS.box_damping
    )
    a, b = ReachEnv(version="v0"), ReachEnv(version="v1")
    a.reset(seed=0), b.reset(seed=0)
    for _ in range(5):
        oa, *_ = a.step(UP)
        ob, *_ = b.step(UP)
    np.testing.assert_allclose(oa, ob, atol=1e-6)


def test_push_object_is_the_papers_cylinder() -> None:
    env = PushEnv(version="v1")
    model = env.model
    geom = model.geom("box")
    assert geom.type[0] == mujoco.mjtGeom.mjGEOM_CYLINDER
    assert geom.size[0] == pytest.approx(0.05)
    assert geom.friction[0] == pytest.approx(0.9)
    assert model.body("box").mass[0] == pytest.approx(1.0)


def test_reach_wall_undoes_moves_that_touch_it() -> None:
    env = ReachEnv(version="v1")
    env.reset(seed=0, options={"ee_start": (0.5, 0.06)})
    wall = PAPER_GEOMETRY.reach_walls[0]
    rejected = []
    for _ in range(8):
        obs, _, _, _, info = env.step(UP)
        rejected.append(info["move_rejected"])
        assert wall.distance(obs) >= PAPER_GEOMETRY.ee_radius - 1e-4  # never touches it
    assert obs[1] == pytest.approx(0.12, abs=2e-4) and rejected[-1] and not rejected[0]
    # beside the wall's end the way is free
    env.reset(seed=0, options={"ee_start": (0.29, 0.06)})
    for _ in range(8):
        obs, _, _, _, info = env.step(UP)
    assert obs[1] > 0.2 and not info["move_rejected"]


def test_reach_dense_reward_is_the_papers_subgoal_reward() -> None:
    env = ReachEnv(version="v1", reward="dense")
    env.reset(seed=0)
    _, reward, _, _, info = env.step(UP)
    ee, goal = info["ee_position"], info["goal_position"]
    near = min(PAPER_GEOMETRY.reach_detour, key=lambda p: math.dist(ee, p))
    assert near == (0.23, 0.15)  # the left end is nearer from the start
    assert reward == pytest.approx(-(math.dist(ee, near) + math.dist(near, goal)))
    # once within 0.05 m of a wall end, the reward is the distance to the goal, and stays so
    env.reset(seed=0, options={"ee_start": (0.27, 0.15)})
    _, reward, _, _, info = env.step(STILL)
    assert reward == pytest.approx(-info["distance"], abs=1e-9)
    for _ in range(4):
        _, reward, _, _, info = env.step(np.array([1.0, 0.0], dtype=np.float32))
    assert reward == pytest.approx(-info["distance"], abs=1e-9)
    env.reset(seed=1)  # the latch resets with the episode
    _, reward, _, _, info = env.step(UP)
    assert reward < -info["distance"]


def test_push_dense_reward_is_the_papers() -> None:
    env = PushEnv(version="v1", reward="dense")
    _, info = env.reset(seed=0)
    previous = info["distance"]
    _, reward, _, _, info = env.step(UP)  # far from the object: -d² + (previous - d)
    d = info["distance"]
    assert reward == pytest.approx(-(d**2) + (previous - d))
    assert math.dist(info["ee_position"], info["box_position"]) > 0.05


def test_maze_dense_reward_leads_over_a_side_wall() -> None:
    env = MazeReachEnv(version="v1", reward="dense")
    env.reset(seed=0)
    _, reward, _, _, info = env.step(UP)
    ee, goal = info["ee_position"], info["goal_position"]
    near = min(PAPER_GEOMETRY.maze_detour, key=lambda p: math.dist(ee, p))
    assert reward == pytest.approx(-(math.dist(ee, near) + math.dist(near, goal)))


def test_cylinder_is_pushed_along_the_line_of_centres() -> None:
    env = PushEnv(version="v1")
    direction = np.array([1.0, 1.0]) / math.sqrt(2)
    start = np.array(PAPER_GEOMETRY.box_start) - 0.08 * direction
    obs, _ = env.reset(seed=0, options={"ee_start": tuple(start)})
    for _ in range(8):
        obs, *_ = env.step(np.array([1.0, 1.0], dtype=np.float32))
    moved = obs[2:] - np.array(PAPER_GEOMETRY.box_start)
    assert np.linalg.norm(moved) > 0.1
    assert moved[0] == pytest.approx(moved[1], abs=0.01)  # diagonally, as pushed


@pytest.mark.parametrize(("task", "steps"), [("reach", 33), ("push", 27), ("maze-reach", 35)])
def test_oracle_succeeds_within_the_horizon(task: str, steps: int) -> None:
    env = gymnasium.make(V1[task])
    run = run_oracle(env, 1000, seed=0)
    assert run.steps == env.spec.max_episode_steps  # stopped by TimeLimit
    assert run.first_success == steps and run.final_success


def test_reach_oracle_goes_around_the_wall() -> None:
    run = run_oracle(ReachEnv(version="v1"), 50)
    wall = PAPER_GEOMETRY.reach_walls[0]
    path = np.array(run.observations)
    assert min(wall.distance(p) for p in path) >= PAPER_GEOMETRY.ee_radius
    assert path[:, 0].min() < wall.low[0] or path[:, 0].max() > wall.high[0]


def test_push_grid_cells_hold_the_papers_object_start() -> None:
    dx, dy = (b - a for a, b in zip(PAPER_GEOMETRY.box_start, PAPER_GEOMETRY.box_goal, strict=True))
    assert PAPER_GEOMETRY.contact_distance < PUSH_CELL
    assert dx / PUSH_CELL == pytest.approx(round(dx / PUSH_CELL))
    assert dy / PUSH_CELL == pytest.approx(round(dy / PUSH_CELL))
