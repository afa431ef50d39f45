"""gymnasium-robotics tasks (PointMaze, Fetch): API conformance for every reward variant,
scripted controllers that walk the plan's subgoals (the proof that a model and its classifiers
agree), seeding, the generated maze model and the error for a model that misses a classifier."""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

import gymnasium
import numpy as np
import pytest

import planshape  # noqa: F401  (registers the tasks)
from planshape.planning.grid import Cell
from planshape.shaping.registration import abstract_model, task_ids, task_spec
from planshape.tasks import point_maze

TASKS = [t for t in task_ids() if t.startswith(("planshape/PointMaze", "planshape/Fetch"))]
MAZES = [t for t in TASKS if "PointMaze" in t]
REWARDS = ["sparse", "dense", "shaped"]
GAMMA = 0.99


def make(task_id: str, reward: str = "sparse", **kwargs: Any) -> gymnasium.Env:
    if reward == "shaped":
        kwargs.setdefault("gamma", GAMMA)
    return gymnasium.make(task_id, reward=reward, **kwargs)


def test_the_suite_has_the_mazes_and_fetch_tasks() -> None:
    assert {t.split("/")[1] for t in TASKS} >= {
        "PointMaze_UMaze-v3",
        "PointMaze_Medium-v3",
        "FetchReach-v4",
        "FetchPush-v4",
    }


# ---- API conformance ---------------------------------------------------------------------------


@pytest.mark.parametrize("task_id", TASKS, ids=str)
def test_info_reports_success_and_distance(task_id: str) -> None:
    env = make(task_id, "dense")
    obs, info = env.reset(seed=0)
    distance = float(np.linalg.norm(obs["achieved_goal"] - obs["desired_goal"]))
    assert info["success"] is False and info["distance"] == pytest.approx(distance)
    obs, reward, *_, info = env.step(env.action_space.sample())
    distance = float(np.linalg.norm(obs["achieved_goal"] - obs["desired_goal"]))
    assert isinstance(info["success"], bool) and info["distance"] == pytest.approx(distance)
    dense = math.exp(-distance) if "PointMaze" in task_id else -distance  # their reward_type
    assert reward == pytest.approx(dense, rel=1e-5)


# ---- scripted controllers that walk the plan ---------------------------------------------------

Controller = Callable[[Mapping[str, np.ndarray], int, Any], np.ndarray]


def maze_controller(obs: Mapping[str, np.ndarray], progress: int, env: gymnasium.Env) -> np.ndarray:
    """Roll towards the centre of the next subgoal's cell; after the last, to the goal itself."""
    subgoals = env.get_wrapper_attr("progress").subgoals
    if progress < len(subgoals) - 1:
        target = env.get_wrapper_attr("geometry").locate(subgoals[progress + 1])["ball"]
    else:
        target = obs["desired_goal"]
    velocity = obs["observation"][2:4]
    return np.clip(5.0 * (target - obs["achieved_goal"]) - velocity, -1.0, 1.0)


def fetch_reach_controller(obs: Mapping[str, np.ndarray], progress: int, env: Any) -> np.ndarray:
    return np.append(np.clip(10.0 * (obs["desired_goal"] - obs["achieved_goal"]), -1, 1), 0.0)


def fetch_push_controller(obs: Mapping[str, np.ndarray], progress: int, env: Any) -> np.ndarray:
    """Until ``touching`` holds, and whenever the gripper is not lined up behind the block (seen
    from the goal): rise, come over the point behind the block, go down. Then push the block
    through to the goal."""
    gripper, block, goal = obs["observation"][0:3], obs["observation"][3:6], obs["desired_goal"]
    heading = (goal - block)[:2] / max(float(np.linalg.norm((goal - block)[:2])), 1e-6)
    behind = np.append(block[:2] - 0.06 * heading, block[2])
    offset = block[:2] - gripper[:2]
    lined_up = (
        float(offset @ heading) > 0.02
        and abs(float(offset[0] * heading[1] - offset[1] * heading[0])) < 0.02
        and abs(gripper[2] - block[2]) < 0.02
    )
    if progress >= 1 and lined_up:
        target, gain = np.append(goal[:2] - 0.05 * heading, block[2]), 5.0
    elif np.linalg.norm(gripper[:2] - behind[:2]) > 0.015:
        high = block[2] + 0.07
        target = (
            behind + np.array([0.0, 0.0, 0.07])
            if gripper[2] > high - 0.02
            else np.append(gripper[:2], high)
        )
        gain = 10.0
    else:
        target, gain = behind, 10.0
    return np.append(np.clip(gain * (target - gripper), -1, 1), 0.0)


CONTROLLERS: dict[str, Controller] = {
    "planshape/PointMaze_UMaze-v3": maze_controller,
    "planshape/PointMaze_Medium-v3": maze_controller,
    "planshape/FetchReach-v4": fetch_reach_controller,
    "planshape/FetchPush-v4": fetch_push_controller,
}


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("task_id", TASKS, ids=str)
def test_controller_walking_the_plan_succeeds_and_progress_reaches_the_end_in_order(
    task_id: str, seed: int
) -> None:
    """The controller sees only the plan's subgoals (through ``locate``) and the progress the
    classifiers report; it reaches the task's success, and progress walks every subgoal in
    order up to the last."""
    env = make(task_id, "shaped", potential="plan-based")
    final = env.get_wrapper_attr("progress").final
    obs, info = env.reset(seed=seed)
    progress, success_at = [info["progress"]], None
    for t in range(1, task_spec(task_id).max_episode_steps + 1):
        action = CONTROLLERS[task_id](obs, progress[-1], env)
        obs, _, terminated, truncated, info = env.step(action.astype(np.float32))
        progress.append(info["progress"])
        if info["success"] and success_at is None:
            success_at = t
        if (success_at is not None and progress[-1] == final) or terminated or truncated:
            break
    assert success_at is not None, f"no success in {t} steps (progress {max(progress)}/{final})"
    assert progress[-1] == final, f"progress reached {max(progress)} of {final}"
    assert progress == sorted(progress)
    assert sorted(set(progress)) == list(range(final + 1)), "a subgoal was skipped"


# ---- seeding and the maze model ----------------------------------------------------------------


@pytest.mark.parametrize("task_id", MAZES, ids=str)
def test_maze_starts_and_ends_in_its_fixed_cells(task_id: str) -> None:
    maze = point_maze.MAZES[task_spec(task_id).kwargs["maze"]]
    env = make(task_id)
    sim_maze = env.unwrapped.sim.maze
    for seed in range(3):
        obs, _ = env.reset(seed=seed)
        start = sim_maze.cell_xy_to_rowcol(obs["achieved_goal"])
        goal = sim_maze.cell_xy_to_rowcol(obs["desired_goal"])
        assert tuple(start) == maze.reset_cell and tuple(goal) == maze.goal_cell
    assert env.unwrapped.sim.continuing_task is False


@pytest.mark.parametrize("task_id", MAZES, ids=str)
def test_maze_grid_model_matches_the_maze(task_id: str) -> None:
    """One cell object per map cell, neighbours exactly between adjacent free cells, centres
    from the environment's own ``cell_rowcol_to_xy``, and the plan is a shortest path."""
    maze = point_maze.MAZES[task_spec(task_id).kwargs["maze"]]
    model = abstract_model(task_spec(task_id))
    env = make(task_id, "shaped", potential="plan-based")
    task = env.get_wrapper_attr("progress").abstraction.task
    free = {(r, c) for r, row in enumerate(maze.layout) for c, v in enumerate(row) if v == 0}
    edges = {(atom[1], atom[2]) for atom in task.init if atom[0] == "neighbors"}
    expected = {
        (f"cell_{r}_{c}", f"cell_{r + dr}_{c + dc}")
        for r, c in free
        for dr, dc in ((0, 1), (1, 0), (0, -1), (-1, 0))
        if (r + dr, c + dc) in free
    }
    assert edges == expected
    sim_maze = env.unwrapped.sim.maze
    for r, c in free:
        np.testing.assert_allclose(
            model.geometry.centres[f"cell_{r}_{c}"], sim_maze.cell_rowcol_to_xy(np.array([r, c]))
        )
    subgoals = env.get_wrapper_attr("progress").subgoals
    assert len(subgoals) - 1 == shortest_path_length(free, maze.reset_cell, maze.goal_cell)


def shortest_path_length(free: set[Cell], start: Cell, goal: Cell) -> int:
    """Breadth-first search over 4-neighbouring free cells."""
    distance, frontier = {start: 0}, [start]
    while frontier and goal not in distance:
        cell = frontier.pop(0)
        r, c = cell
        for nxt in ((r + 1, c), (r - 1, c), (r, c + 1), (r, c - 1)):
            if nxt in free and nxt not in distance:
                distance[nxt] = distance[cell] + 1
                frontier.append(nxt)
    return distance[goal]


def test_maze_classifier_puts_the_ball_in_exactly_one_cell() -> None:
    model = point_maze.umaze_grid()
    centres = model.geometry.centres
    in_cell = model.classifiers["robot_at"].fn
    names = sorted(centres)
    for name in names:
        obs = {"achieved_goal": centres[name] + 0.3, "desired_goal": np.zeros(2)}
        held = in_cell(np.asarray(obs), [(n,) for n in names])
        assert [n for n, h in zip(names, held, strict=True) if h] == [name]


# ---- models ------------------------------------------------------------------------------------


@pytest.mark.parametrize("task_id", TASKS, ids=str)
def test_distance_potential_runs_on_the_geometry(task_id: str) -> None:
    env = make(task_id, "shaped", potential="distance-varying")
    _, info = env.reset(seed=0)
    assert info["potential"] < 0
    *_, info = env.step(env.action_space.sample())
    assert math.isfinite(info["shaping"])


def test_maze_cells_tile_the_plane_even_on_their_edges():
    """A ball on the edge between two cells is in exactly one (closed squares put it in two)."""
    from planshape.tasks.point_maze import InCell

    centres = {f"cell_{r}_{c}": np.array([c - 0.5, 0.5 - r]) for r in range(2) for c in range(2)}
    in_cell = InCell(centres)
    groundings = [(name,) for name in centres]
    for x in (-0.9, -0.5, 0.0, np.nextafter(0.0, 1.0), 0.5, 0.9):  # x = 0: the inner edge
        for y in (-0.9, 0.0, np.nextafter(0.0, -1.0), 0.5, 0.9):
            obs = {"achieved_goal": np.array([x, y])}
            hits = in_cell(obs, groundings)
            assert hits.sum() == 1, (x, y)
            assert in_cell.holding(obs, groundings) == np.flatnonzero(hits).tolist()
