"""gymnasium-robotics tasks: PointMaze (UMaze, Medium) and Fetch (Reach, Push), with their PDDL
models, classifiers and subgoal geometry.

Every task is a :class:`GoalTask`: the gymnasium-robotics environment with its own reward
(``reward="sparse"`` or ``"dense"`` selects its ``reward_type``), ``info["success"]`` (its
``is_success``/``success`` flag) and ``info["distance"]`` (``‖achieved_goal − desired_goal‖``)
after ``reset`` and every step. Observations are its dictionaries
``{"observation", "achieved_goal", "desired_goal"}``.

* **PointMaze** runs episodically (``continuing_task=False``: reaching the goal terminates) with
  a fixed reset cell and goal cell, so one plan serves every episode. The seed draws the
  gymnasium-robotics position noise (±0.25 cells) of the start; the goal is the goal cell's
  centre, without noise, so that success (within 0.45 of the goal) implies that the ball is in
  the goal cell: the plan's last subgoal holds whenever the task succeeds. (With a noisy goal
  the success disc reaches into neighbouring cells and an episode could end one subgoal short.)
  The ``grid`` model is generated from the maze map (:func:`planshape.planning.grid_pddl`):
  one object per cell, ``(neighbors a b)`` between adjacent free cells, ``(robot_at c)`` true
  when the ball's ``achieved_goal`` lies in cell ``c``'s square; ``locate`` gives the cell's
  centre. Wall cells stay declared objects (``grid_pddl`` declares every cell), with no
  neighbours, so no plan visits them and their ``robot_at`` never holds.
* **Fetch**: ``gripper-at`` (FetchReach) and ``at-goal`` (FetchPush) are the environment's own
  success test, distance below 5 cm; ``touching`` holds when the gripper is within
  ``FETCH_TOUCHING`` = 7 cm of the block's centre (pushing contact is at 4–6 cm) and level with
  it (heights within ``FETCH_LEVEL`` = 2 cm; a gripper passing over the block does not count).

Example:
    >>> import gymnasium, planshape
    >>> env = gymnasium.make("planshape/PointMaze_UMaze-v3")  # doctest: +SKIP
    >>> obs, info = env.reset(seed=0)  # doctest: +SKIP
    >>> sorted(obs), info["success"]  # doctest: +SKIP
    (['achieved_goal', 'desired_goal', 'observation'], False)
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar, SupportsFloat

import gymnasium
import gymnasium_robotics
import numpy as np
from gymnasium_robotics.envs.maze import maps
from gymnasium_robotics.envs.maze.maze_v4 import Maze

from planshape.abstraction import Vectorized
from planshape.errors import BadInputError, UnknownIdError
from planshape.planning.grid import Cell, GridNames, cell_name, grid_pddl
from planshape.planning.model import AbstractState
from planshape.regions import Lattice
from planshape.registration import AbstractModel
from planshape.tasks.common import distance, generated_file, pddl_file
from planshape.tasks.displacement import DisplacementGeometry

REWARDS = ("sparse", "dense")
#: FetchPush's ``touching``: gripper to block centre, and their height difference
FETCH_TOUCHING = 0.07
FETCH_LEVEL = 0.02

gymnasium.register_envs(gymnasium_robotics)


# --------------------------------------------------------------------------- the environment


class GoalTask(gymnasium.Env):
    """A gymnasium-robotics goal environment with ``success`` and ``distance`` in ``info``.

    The environment is held in :attr:`sim`, not wrapped: its ``compute_reward`` would make
    checkers (stable-baselines3's among them) take this task for a goal-conditioned ``GoalEnv``,
    whose reward ``compute_reward(achieved, desired)`` must reproduce; a shaped reward cannot.

    Args:
        sim: the unwrapped gymnasium-robotics environment.
    """

    def __init__(self, sim: gymnasium.Env):
        self.sim = sim
        self.observation_space = sim.observation_space
        self.action_space = sim.action_space
        self.metadata = dict(sim.metadata)
        self.render_mode = sim.render_mode

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        super().reset(seed=seed)
        obs, info = self.sim.reset(seed=seed, options=options)
        if "success" not in info:  # Fetch reports success only after a step
            info["success"] = self.sim._is_success(obs["achieved_goal"], obs["desired_goal"])
        return obs, self._metrics(obs, info)

    def step(
        self, action: Any
    ) -> tuple[dict[str, np.ndarray], SupportsFloat, bool, bool, dict[str, Any]]:
        obs, reward, terminated, truncated, info = self.sim.step(action)
        if "is_success" in info:
            info["success"] = info["is_success"]
        return obs, float(reward), bool(terminated), bool(truncated), self._metrics(obs, info)

    @staticmethod
    def _metrics(obs: Mapping[str, np.ndarray], info: dict[str, Any]) -> dict[str, Any]:
        info["success"] = bool(info["success"])
        info["distance"] = float(np.linalg.norm(obs["achieved_goal"] - obs["desired_goal"]))
        return info

    def render(self) -> Any:
        return self.sim.render()

    def close(self) -> None:
        self.sim.close()


def _check_reward(reward: str, where: str) -> None:
    if reward not in REWARDS:
        raise UnknownIdError("reward variant", reward, REWARDS, hint=f"for {where}")


# --------------------------------------------------------------------------- PointMaze


@dataclass(frozen=True)
class MazeTask:
    """A PointMaze maze with the cells where every episode starts and ends.

    Attributes:
        env_id: the gymnasium-robotics id.
        layout: the maze map, 1 = wall, 0 = free.
        reset_cell: ``(row, column)`` of the start.
        goal_cell: ``(row, column)`` of the goal.
    """

    env_id: str
    layout: Sequence[Sequence[int]]
    reset_cell: Cell
    goal_cell: Cell

    def maze_map(self) -> list[list[int | str]]:
        """The layout with ``"r"`` at the reset cell and ``"g"`` at the goal cell."""
        rows: list[list[int | str]] = [list(row) for row in self.layout]
        for (r, c), mark in ((self.reset_cell, maps.RESET), (self.goal_cell, maps.GOAL)):
            if rows[r][c] != 0:
                raise BadInputError(f"{self.env_id}: cell {(r, c)} is a wall, not free")
            rows[r][c] = mark
        return rows

    def walls(self) -> set[Cell]:
        return {(r, c) for r, row in enumerate(self.layout) for c, v in enumerate(row) if v == 1}

    def cell_centres(self) -> dict[str, np.ndarray]:
        """Object name -> the cell's centre in world coordinates (gymnasium-robotics' own
        ``cell_rowcol_to_xy``, PointMaze's scale of 1 and height of 0.4)."""
        maze = Maze(self.maze_map(), maze_size_scaling=1.0, maze_height=0.4)
        return {
            cell_name((r, c)): np.asarray(maze.cell_rowcol_to_xy(np.array([r, c])), dtype=float)
            for r in range(len(self.layout))
            for c in range(len(self.layout[0]))
        }


#: The classic D4RL start and goal: UMaze from the bottom-left arm round to the top-left;
#: Medium from the top-left corner to the bottom-right.
MAZES: dict[str, MazeTask] = {
    "UMaze": MazeTask("PointMaze_UMaze-v3", maps.U_MAZE, reset_cell=(3, 1), goal_cell=(1, 1)),
    "Medium": MazeTask(
        "PointMaze_Medium-v3", maps.MEDIUM_MAZE, reset_cell=(1, 1), goal_cell=(6, 6)
    ),
}


def _maze(name: str) -> MazeTask:
    if name not in MAZES:
        raise UnknownIdError("maze", name, MAZES)
    return MAZES[name]


class PointMazeTask(GoalTask):
    """A PointMaze environment whose goal is the centre of the goal cell (see the module
    docstring); everything else is gymnasium-robotics' ``PointMazeEnv``."""

    def __init__(self, sim: gymnasium.Env, goal_xy: np.ndarray):
        super().__init__(sim)
        self.goal_xy = np.asarray(goal_xy, dtype=float)

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        obs, info = super().reset(seed=seed, options=options)
        self.sim.goal = self.goal_xy.copy()
        self.sim.update_target_site_pos()
        obs["desired_goal"] = self.goal_xy.copy()
        info["success"] = bool(np.linalg.norm(obs["achieved_goal"] - self.goal_xy) <= 0.45)
        return obs, self._metrics(obs, info)


def point_maze(maze: str = "UMaze", reward: str = "sparse", **kwargs: Any) -> PointMazeTask:
    """A PointMaze task: fixed start and goal cells, episodic (reaching the goal terminates).

    Args:
        maze: a key of :data:`MAZES`.
        reward: ``"sparse"`` (1 within 0.45 of the goal, else 0) or ``"dense"``
            (``exp(−distance)``), gymnasium-robotics' ``reward_type``.
        **kwargs: further keyword arguments of ``PointMazeEnv`` (``render_mode``, …).
    """
    task = _maze(maze)
    _check_reward(reward, task.env_id)
    sim = gymnasium.make(
        task.env_id,
        maze_map=task.maze_map(),
        continuing_task=False,
        reward_type=reward,
        **kwargs,
    ).unwrapped
    return PointMazeTask(sim, task.cell_centres()[cell_name(task.goal_cell)])


def achieved_goal(obs: Any) -> np.ndarray:
    """``obs["achieved_goal"]`` of a goal-environment observation.

    The abstraction layer hands classifiers ``np.asarray(obs)``, which turns a dictionary into a
    0-dimensional object array; this unwraps it.
    """
    return np.asarray(_as_dict(obs)["achieved_goal"], dtype=float)


def desired_goal(obs: Any) -> np.ndarray:
    """``obs["desired_goal"]`` (see :func:`achieved_goal`)."""
    return np.asarray(_as_dict(obs)["desired_goal"], dtype=float)


def _as_dict(obs: Any) -> Mapping[str, Any]:
    if isinstance(obs, Mapping):
        return obs
    if isinstance(obs, np.ndarray) and obs.dtype == object and obs.ndim == 0:
        return obs.item()
    raise BadInputError(
        f"expected one goal-environment observation (a dict with 'achieved_goal'), got "
        f"{type(obs).__name__}{getattr(obs, 'shape', '')}; batches of dict observations are "
        "not supported"
    )


@dataclass(frozen=True)
class InCell:
    """Vectorized classifier of ``(robot_at ?c)``: the ball lies in the cell. The cells tile the
    maze (:class:`planshape.regions.Lattice`), so the ball is in exactly one cell, also on an
    edge between two.

    Example:
        >>> import numpy as np
        >>> in_cell = InCell({"cell_0_0": np.array([0.0, 0.0]), "cell_0_1": np.array([1.0, 0.0])})
        >>> obs = {"achieved_goal": np.array([0.9, 0.2])}
        >>> groundings = [("cell_0_0",), ("cell_0_1",)]
        >>> in_cell(obs, groundings).tolist(), in_cell.holding(obs, groundings)
        ([False, True], [1])
    """

    centres: Mapping[str, np.ndarray]
    half_size: float = 0.5

    def __post_init__(self) -> None:
        names = list(self.centres)
        lattice = Lattice([self.centres[n] for n in names], 2 * self.half_size)
        object.__setattr__(self, "_lattice", lattice)
        object.__setattr__(self, "_names", names)

    def __call__(self, obs: Any, groundings: Sequence[tuple[str, ...]]) -> np.ndarray:
        centres = np.stack([self.centres[g[0]] for g in groundings])
        return self._lattice.contains(achieved_goal(obs), centres)  # type: ignore[attr-defined]

    def holding(self, obs: Any, groundings: Sequence[tuple[str, ...]]) -> list[int]:
        """The positions in ``groundings`` of the ball's cell (the one-observation path)."""
        x, y = achieved_goal(obs).tolist()
        names = self._names  # type: ignore[attr-defined]
        here = {names[i] for i in self._lattice.containing(x, y)}  # type: ignore[attr-defined]
        return [k for k, g in enumerate(groundings) if g[0] in here]


@dataclass(frozen=True)
class MazeGeometry:
    """``locate``: the centre of the subgoal's ``robot_at`` cell; ``positions``: the ball."""

    centres: Mapping[str, np.ndarray]
    at: str = "robot_at"
    #: one entity, the ball's position in the maze's frame
    shared_frame: ClassVar[bool] = True

    def locate(self, subgoal: AbstractState) -> dict[str, np.ndarray]:
        for atom in subgoal:
            if atom[0] == self.at:
                return {"ball": self.centres[atom[1]]}
        return {}

    def positions(self, obs: Any) -> dict[str, np.ndarray]:
        return {"ball": achieved_goal(obs)}


def maze_grid(maze: str) -> AbstractModel:
    """The ``grid`` model of a maze, generated from its map (see the module docstring)."""
    task = _maze(maze)
    rows, cols = len(task.layout), len(task.layout[0])
    names = GridNames(domain="pointmaze", problem=f"pointmaze-{maze.lower()}-grid")
    grid = grid_pddl(
        rows, cols, task.reset_cell, task.goal_cell, blocked_cells=task.walls(), names=names
    )
    centres = task.cell_centres()
    in_cell = InCell(centres)
    return AbstractModel(
        domain=generated_file("pointmaze-domain", grid.domain),
        problem=generated_file(f"pointmaze-{maze.lower()}-grid", grid.problem),
        classifiers={names.at: Vectorized(in_cell, holding=in_cell.holding)},
        geometry=MazeGeometry(centres, at=names.at),
    )


def umaze_grid() -> AbstractModel:
    """The UMaze's cell-by-cell model."""
    return maze_grid("UMaze")


def medium_grid() -> AbstractModel:
    """The Medium maze's cell-by-cell model."""
    return maze_grid("Medium")


# --------------------------------------------------------------------------- Fetch


def fetch(env_id: str = "FetchReach-v4", reward: str = "sparse", **kwargs: Any) -> GoalTask:
    """A Fetch task with its own sparse (−1/0) or dense (−distance) reward.

    Args:
        env_id: the gymnasium-robotics id, ``"FetchReach-v4"`` or ``"FetchPush-v4"``.
        reward: gymnasium-robotics' ``reward_type``.
        **kwargs: further keyword arguments of the Fetch environment (``render_mode``, …).
    """
    _check_reward(reward, env_id)
    return GoalTask(gymnasium.make(env_id, reward_type=reward, **kwargs).unwrapped)


def _success(obs: Any) -> np.ndarray:
    # Fetch's own test: distance strictly below distance_threshold (0.05 for Reach and Push).
    return distance(achieved_goal(obs), desired_goal(obs)) < 0.05


def gripper_at(obs: Any, _gripper: str, _location: str) -> np.ndarray:
    """FetchReach ``(gripper-at ?g ?l)``: the environment's success test."""
    return _success(obs)


def block_at_goal(obs: Any, _block: str) -> np.ndarray:
    """FetchPush ``(at-goal ?b)``: the environment's success test."""
    return _success(obs)


def touching(obs: Any, _gripper: str, _block: str) -> np.ndarray:
    """FetchPush ``(touching ?g ?b)``: the gripper within ``FETCH_TOUCHING`` of the block and
    level with it (within ``FETCH_LEVEL``)."""
    offset = gripper_to_block(obs)
    near = distance(offset, 0.0) <= FETCH_TOUCHING
    return near & (np.abs(offset[..., 2]) <= FETCH_LEVEL)


def achieved_to_goal(obs: Any) -> np.ndarray:
    """``achieved_goal − desired_goal``: the gripper (Reach) or the block (Push) to the goal."""
    return achieved_goal(obs) - desired_goal(obs)


def gripper_to_block(obs: Any) -> np.ndarray:
    """Gripper minus block, from ``observation[0:3]`` and ``observation[3:6]``."""
    observation = np.asarray(_as_dict(obs)["observation"], dtype=float)
    return observation[..., 0:3] - observation[..., 3:6]


def fetch_reach_stages() -> AbstractModel:
    """FetchReach: ``(move-gripper gripper target)``."""
    return AbstractModel(
        domain=pddl_file("fetch", "reach", "domain.pddl"),
        problem=pddl_file("fetch", "reach", "stages.pddl"),
        classifiers={"gripper-at": gripper_at},
        geometry=DisplacementGeometry(
            displacements={"gripper-to-goal": achieved_to_goal},
            targets={"gripper-at": ("gripper-to-goal", (0.0, 0.0, 0.0))},
        ),
    )


def fetch_push_stages() -> AbstractModel:
    """FetchPush: reach the block, push it to the goal."""
    return AbstractModel(
        domain=pddl_file("fetch", "push", "domain.pddl"),
        problem=pddl_file("fetch", "push", "stages.pddl"),
        classifiers={"touching": touching, "at-goal": block_at_goal},
        geometry=DisplacementGeometry(
            displacements={"gripper-to-block": gripper_to_block, "block-to-goal": achieved_to_goal},
            targets={
                "touching": ("gripper-to-block", (0.0, 0.0, 0.0)),
                "at-goal": ("block-to-goal", (0.0, 0.0, 0.0)),
            },
        ),
    )
