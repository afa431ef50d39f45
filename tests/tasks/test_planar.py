"""The planar MuJoCo tasks: API conformance, the workspace rule, walls, pushing, oracles,
determinism and the never-terminating success."""

from __future__ import annotations

import math
import warnings

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env as gymnasium_check_env
from stable_baselines3.common.env_checker import check_env as sb3_check_env

from planshape.errors import BadInputError, UnknownIdError
from planshape.tasks.planar import (
    GEOMETRY,
    ORACLE_STEPS,
    PAPER_HORIZON,
    RECOMMENDED_HORIZONS,
    MazeReachEnv,
    PlanarEnv,
    PushEnv,
    ReachEnv,
    run_oracle,
)

ENVS = {"reach": ReachEnv, "push": PushEnv, "maze-reach": MazeReachEnv}
ENTRY_POINTS = {
    "reach": "planshape.tasks.planar.reach:ReachEnv",
    "push": "planshape.tasks.planar.push:PushEnv",
    "maze-reach": "planshape.tasks.planar.maze_reach:MazeReachEnv",
}
UP = np.array([0.0, 1.0], dtype=np.float32)
DOWN = np.array([0.0, -1.0], dtype=np.float32)
STILL = np.zeros(2, dtype=np.float32)


def test_id(task: str) -> str:
    """A temporary Gymnasium id (the suite's own ids come from the task registration)."""
    env_id = f"planshape-test/Planar-{task}-v0"
    if env_id not in gymnasium.registry:
        gymnasium.register(env_id, entry_point=ENTRY_POINTS[task])
    return env_id


test_id.__test__ = False  # a helper, not a test


# ---- API conformance ---------------------------------------------------------------------------


@pytest.mark.parametrize("reward", ["sparse", "dense"])
@pytest.mark.parametrize("task", ENVS)
def test_gymnasium_env_checker(task: str, reward: str) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the checker's warnings are problems too
        gymnasium_check_env(ENVS[task](reward=reward), skip_render_check=True)


@pytest.mark.parametrize("reward", ["sparse", "dense"])
@pytest.mark.parametrize("task", ENVS)
def test_sb3_env_checker(task: str, reward: str) -> None:
    sb3_check_env(ENVS[task](reward=reward), warn=True)


@pytest.mark.parametrize("task", ENVS)
def test_checker_with_random_start_and_goal(task: str) -> None:
    env = ENVS[task](randomize_start=True, randomize_goal=True)
    gymnasium_check_env(env, skip_render_check=True)


@pytest.mark.parametrize("task", ENVS)
def test_make_through_entry_point(task: str) -> None:
    env = gymnasium.make(test_id(task), max_episode_steps=5, reward="dense")
    obs, _ = env.reset(seed=0)
    assert env.observation_space.contains(obs)
    assert env.unwrapped.reward_variant == "dense"
    for _ in range(5):
        obs, reward, terminated, truncated, _ = env.step(env.action_space.sample())
        assert isinstance(reward, float) and reward <= 0.0
    assert truncated and not terminated  # the horizon is TimeLimit's, not the environment's


@pytest.mark.parametrize("task", ENVS)
def test_info_keys_on_reset_and_step(task: str) -> None:
    env = ENVS[task]()
    keys = {"success", "distance", "move_rejected", "ee_position", "goal_position"}
    if task == "push":
        keys.add("box_position")
    _, info = env.reset(seed=0)
    assert set(info) == keys
    _, _, _, _, info = env.step(UP)
    assert set(info) == keys
    assert isinstance(info["success"], bool) and isinstance(info["distance"], float)


def test_observation_layouts() -> None:
    reach_obs, _ = ReachEnv().reset(seed=0)
    push_obs, _ = PushEnv().reset(seed=0)
    maze_obs, _ = MazeReachEnv().reset(seed=0)
    np.testing.assert_allclose(reach_obs, GEOMETRY.ee_start, atol=1e-6)
    np.testing.assert_allclose(maze_obs, GEOMETRY.ee_start, atol=1e-6)
    np.testing.assert_allclose(push_obs, [*GEOMETRY.ee_start, *GEOMETRY.box_start], atol=1e-6)
    assert PushEnv.entities == {"ee": slice(0, 2), "box": slice(2, 4)}
    assert ReachEnv().observation_space.low.tolist() == pytest.approx([0.23, -0.35])
    assert ReachEnv().observation_space.high.tolist() == pytest.approx([0.78, 0.30])


def test_bad_arguments_say_what_is_known() -> None:
    with pytest.raises(UnknownIdError, match="'sparse', 'dense'|dense, sparse"):
        ReachEnv(reward="shaped")
    with pytest.raises(BadInputError, match="render_mode"):
        ReachEnv(render_mode="human")
    with pytest.raises(BadInputError, match="box_start"):
        ReachEnv().reset(options={"box_start": (0.5, 0.0)})
    with pytest.raises(BadInputError, match="outside the workspace"):
        ReachEnv().reset(options={"ee_start": (0.1, 0.0)})
    with pytest.raises(BadInputError, match="overlaps a wall"):
        MazeReachEnv().reset(options={"ee_start": (0.5, -0.2)})


# ---- geometry and motion -----------------------------------------------------------------------


def test_geometry_is_the_papers() -> None:
    assert GEOMETRY.workspace.low == (0.23, -0.35) and GEOMETRY.workspace.high == (0.78, 0.30)
    assert GEOMETRY.ee_start == (0.45, -0.32)
    assert (GEOMETRY.reach_goal, GEOMETRY.box_start, GEOMETRY.box_goal, GEOMETRY.maze_goal) == (
        (0.50, 0.26),
        (0.35, -0.10),
        (0.50, 0.20),
        (0.50, 0.00),
    )
    walls = [(w.center, w.half_extents) for w in GEOMETRY.maze_walls]
    assert walls == [
        ((0.50, -0.20), (0.10, 0.01)),
        ((0.40, -0.03), (0.01, 0.18)),
        ((0.60, -0.03), (0.01, 0.18)),
    ]


def test_one_step_moves_two_centimetres_per_unit_action() -> None:
    env = ReachEnv()
    env.reset(seed=0, options={"ee_start": (0.5, 0.0)})
    obs, *_ = env.step(np.array([1.0, -0.5], dtype=np.float32))
    np.testing.assert_allclose(obs, [0.52, -0.01], atol=2e-4)
    obs, *_ = env.step(np.array([5.0, -5.0], dtype=np.float32))  # clipped to [-1, 1]
    np.testing.assert_allclose(obs, [0.54, -0.03], atol=2e-4)


def test_move_leaving_the_workspace_is_rejected() -> None:
    env = ReachEnv()
    obs, _ = env.reset(seed=0)
    obs, _, _, _, info = env.step(DOWN)  # -0.32 -> -0.34: inside
    assert not info["move_rejected"] and obs[1] == pytest.approx(-0.34, abs=2e-4)
    for _ in range(3):  # -0.34 -> -0.36: outside, so the end effector holds its position
        before = obs
        obs, _, _, _, info = env.step(DOWN)
        assert info["move_rejected"]
        np.testing.assert_allclose(obs, before, atol=1e-4)
    # The whole move is rejected, not clipped: its x part is not applied either.
    obs, _, _, _, info = env.step(np.array([1.0, -1.0], dtype=np.float32))
    assert info["move_rejected"] and obs[0] == pytest.approx(0.45, abs=1e-4)
    for _ in range(20):  # left to the bound x = 0.23 and beyond
        obs, _, _, _, info = env.step(np.array([-1.0, 0.0], dtype=np.float32))
        assert env.observation_space.contains(obs)
    assert obs[0] == pytest.approx(0.23, abs=2e-4) and info["move_rejected"]


def test_non_finite_action_is_rejected() -> None:
    env = ReachEnv()
    obs, _ = env.reset(seed=0)
    obs2, _, _, _, info = env.step(np.array([np.nan, 0.5], dtype=np.float32))
    assert info["move_rejected"]
    np.testing.assert_allclose(obs2, obs, atol=1e-6)


def test_walls_block_the_end_effector() -> None:
    env = MazeReachEnv()
    env.reset(seed=0)
    highest = -math.inf
    for _ in range(PAPER_HORIZON):
        _, _, _, _, info = env.step(UP)
        highest = max(highest, info["ee_position"][1])
    bottom_wall = GEOMETRY.maze_walls[0]
    assert highest < bottom_wall.high[1]  # never through the wall (y = -0.19)
    # ... and at most a few millimetres into it (contact at y = -0.21 - radius).
    assert highest < bottom_wall.low[1] - GEOMETRY.ee_radius + 0.005
    assert highest > bottom_wall.low[1] - GEOMETRY.ee_radius - 0.01  # it did reach the wall


def test_end_effector_slides_along_a_wall() -> None:
    env = MazeReachEnv()
    env.reset(seed=0, options={"ee_start": (0.45, -0.24)})
    for _ in range(3):
        obs, *_ = env.step(np.array([1.0, 1.0], dtype=np.float32))
    assert obs[0] == pytest.approx(0.51, abs=2e-3)  # the x part goes on, frictionless
    assert obs[1] < -0.225


def test_box_moves_only_when_pushed() -> None:
    env = PushEnv()
    obs, _ = env.reset(seed=0)
    box_start = obs[2:].copy()
    for action in ([1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [-1.0, 0.0]) * 2:  # around, not touching
        obs, *_ = env.step(np.array(action, dtype=np.float32))
    np.testing.assert_array_equal(obs[2:], box_start)

    obs, _ = env.reset(seed=0, options={"ee_start": (0.35, -0.16)})
    for _ in range(8):
        obs, _, _, _, info = env.step(UP)
    moved = obs[3] - box_start[1]
    assert 0.12 < moved < 0.17  # about 0.02 per step once in contact
    assert obs[2] == pytest.approx(box_start[0], abs=1e-3)  # straight push, no sideways drift
    resting = obs[2:].copy()
    for _ in range(2):
        obs, *_ = env.step(STILL)
    assert np.abs(obs[2:] - resting).max() < 0.005  # stops within millimetres
    resting = obs[2:].copy()
    for _ in range(5):
        obs, *_ = env.step(STILL)
    np.testing.assert_allclose(obs[2:], resting, atol=1e-4)  # then at rest
    assert info["distance"] == pytest.approx(
        math.dist(info["box_position"], GEOMETRY.box_goal), abs=1e-9
    )


def test_diagonal_push_drags_the_box_along() -> None:
    env = PushEnv()
    obs, _ = env.reset(seed=0, options={"ee_start": (0.35, -0.16)})
    for _ in range(8):
        obs, *_ = env.step(np.array([0.5, 1.0], dtype=np.float32))
    dx, dy = obs[2] - 0.35, obs[3] + 0.10
    assert dy > 0.1 and dx / dy == pytest.approx(0.5, abs=0.1)  # the box follows the motion


# ---- rewards and success -----------------------------------------------------------------------


@pytest.mark.parametrize("task", ENVS)
def test_success_does_not_terminate_and_is_held(task: str) -> None:
    """The oracle reaches the goal and stays; the environment itself never ends an episode."""
    env = ENVS[task]()
    run = run_oracle(env, 100)
    assert run.first_success is not None and run.final_success
    for _ in range(20):
        _, reward, terminated, truncated, info = env.step(STILL)
        assert (reward, terminated, truncated, info["success"]) == (1.0, False, False, True)


@pytest.mark.parametrize("task", ENVS)
def test_sparse_reward_pays_only_on_success(task: str) -> None:
    env = ENVS[task]()
    env.reset(seed=0)
    for _ in range(10):
        _, reward, _, _, info = env.step(env.action_space.sample())
        assert reward == (1.0 if info["success"] else 0.0)
        assert info["success"] == (info["distance"] < GEOMETRY.success_threshold)


def test_dense_rewards() -> None:
    for env in (ReachEnv(reward="dense"), MazeReachEnv(reward="dense")):
        env.reset(seed=0)
        _, reward, _, _, info = env.step(UP)
        assert reward == pytest.approx(-info["distance"])
        assert info["distance"] == pytest.approx(
            math.dist(info["ee_position"], info["goal_position"])
        )
    env = PushEnv(reward="dense")
    env.reset(seed=0)
    _, reward, _, _, info = env.step(UP)
    ee_to_box = math.dist(info["ee_position"], info["box_position"])
    assert reward == pytest.approx(-(ee_to_box + info["distance"]))


# ---- oracles and horizons ----------------------------------------------------------------------


@pytest.mark.parametrize("task", ENVS)
def test_oracle_succeeds_within_the_recommended_horizon(task: str) -> None:
    horizon = RECOMMENDED_HORIZONS[task]
    env = gymnasium.make(test_id(task), max_episode_steps=horizon)
    run = run_oracle(env, 10 * horizon, seed=0)
    assert run.steps == horizon  # stopped by TimeLimit
    assert run.first_success == ORACLE_STEPS[task]
    assert run.final_success


def test_reach_and_maze_need_more_than_the_papers_horizon() -> None:
    # Reach: y must rise from -0.32 to above 0.26 - 0.05 at 0.02 per step: 27 steps at least.
    assert math.ceil((GEOMETRY.reach_goal[1] - 0.05 - GEOMETRY.ee_start[1]) / 0.02) > 26
    for task in ("reach", "maze-reach"):
        run = run_oracle(ENVS[task](), PAPER_HORIZON)
        assert run.first_success is None
    assert ORACLE_STEPS["push"] <= PAPER_HORIZON


def test_maze_oracle_goes_around_the_walls() -> None:
    run = run_oracle(MazeReachEnv(), RECOMMENDED_HORIZONS["maze-reach"])
    path = np.array(run.observations)
    clearance = min(w.distance(p) for p in path for w in GEOMETRY.maze_walls)
    assert clearance > GEOMETRY.ee_radius - 0.002  # never pressed into a wall
    assert path[:, 1].max() > GEOMETRY.maze_walls[1].high[1] + GEOMETRY.ee_radius  # over the top


@pytest.mark.parametrize("task", ENVS)
def test_oracle_from_random_starts_and_goals(task: str) -> None:
    env = ENVS[task](randomize_start=True, randomize_goal=True)
    for seed in range(10):
        assert run_oracle(env, 100, seed=seed).final_success, f"seed {seed}"


# ---- seeding and randomization -----------------------------------------------------------------


def _rollout(env: PlanarEnv, seed: int, steps: int = 30) -> np.ndarray:
    obs, _ = env.reset(seed=seed)
    env.action_space.seed(seed)
    trajectory = [obs]
    for _ in range(steps):
        obs, *_ = env.step(env.action_space.sample())
        trajectory.append(obs)
    return np.array(trajectory)


@pytest.mark.parametrize("task", ENVS)
def test_same_seed_same_trajectory(task: str) -> None:
    a = ENVS[task](randomize_start=True, randomize_goal=True)
    b = ENVS[task](randomize_start=True, randomize_goal=True)
    np.testing.assert_array_equal(_rollout(a, 3), _rollout(b, 3))
    np.testing.assert_array_equal(a.goal, b.goal)
    np.testing.assert_array_equal(_rollout(a, 3), _rollout(a, 3))  # reset restores everything
    assert not np.array_equal(_rollout(a, 3)[0], _rollout(a, 4)[0])


@pytest.mark.parametrize("task", ENVS)
def test_default_start_and_goal_are_fixed(task: str) -> None:
    env = ENVS[task]()
    first, _ = env.reset(seed=1)
    goal = env.goal
    second, _ = env.reset(seed=2)
    np.testing.assert_array_equal(first, second)
    np.testing.assert_array_equal(goal, env.goal)


def test_random_starts_and_goals_are_valid() -> None:
    maze, push = (
        MazeReachEnv(randomize_start=True, randomize_goal=True),
        PushEnv(randomize_start=True, randomize_goal=True),
    )
    for seed in range(50):
        obs, info = maze.reset(seed=seed)
        assert maze.observation_space.contains(obs) and not info["success"]
        assert all(w.distance(obs) > GEOMETRY.ee_radius for w in GEOMETRY.maze_walls)
        assert GEOMETRY.maze_goal_region.contains(maze.goal)
        obs, info = push.reset(seed=seed)
        assert push.observation_space.contains(obs) and not info["success"]
        gap = np.abs(obs[:2] - obs[2:]).max()
        assert gap > GEOMETRY.box_half_size + GEOMETRY.ee_radius
        assert GEOMETRY.goal_region.contains(push.goal)


def test_reset_options_override_positions() -> None:
    env = PushEnv()
    obs, info = env.reset(
        seed=0, options={"goal": (0.6, 0.1), "ee_start": (0.3, 0.2), "box_start": (0.6, 0.12)}
    )
    np.testing.assert_allclose(obs, [0.3, 0.2, 0.6, 0.12], atol=1e-6)
    np.testing.assert_array_equal(info["goal_position"], [0.6, 0.1])
    assert info["success"] and info["distance"] == pytest.approx(0.02)


@pytest.mark.parametrize("task", ["planshape/Reach-v1", "planshape/Push-v1"])
def test_positions_of_values_are_the_positions(task: str) -> None:
    """The geometry's positions from a flat observation's tolist() (what a step function that
    keys the classifiers from the same list uses) are its positions, float for float."""
    env = gymnasium.make(
        task, reward="shaped", potential="h-star-geodesic", model="grid", gamma=0.9
    )
    geometry = env.get_wrapper_attr("geometry")
    obs, _ = env.reset(seed=0)
    for action in np.random.default_rng(0).uniform(-1, 1, (30, 2)):
        assert geometry.positions_of_values(obs.tolist()) == geometry.positions(obs)
        obs, *_ = env.step(action.astype(np.float32))
    assert list(geometry.positions(obs)) == (["ee"] if "Reach" in task else ["ee", "box"])
