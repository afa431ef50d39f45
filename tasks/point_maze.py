"""PointMaze (UMaze, Medium) of gymnasium-robotics, with its grid model, classifier and
subgoal geometry.

PointMaze runs episodically (``continuing_task=False``: reaching the goal terminates) with a
fixed reset cell and goal cell, so one plan serves every episode. The seed draws the
gymnasium-robotics position noise (±0.25 cells) of the start; the goal is the goal cell's
centre, without noise, so that success (within 0.45 of the goal) implies that the ball is in
the goal cell: the plan's last subgoal holds whenever the task succeeds. (With a noisy goal
the success disc reaches into neighbouring cells and an episode could end one subgoal short.)
The ``grid`` model is generated from the maze map (:func:`planshape.planning.grid_pddl`): one
object per cell, ``(neighbors a b)`` between adjacent free cells, ``(robot_at c)`` true when
the ball's ``achieved_goal`` lies in cell ``c``'s square; ``locate`` gives the cell's centre.
Wall cells stay declared objects (``grid_pddl`` declares every cell), with no neighbours, so
no plan visits them and their ``robot_at`` never holds.

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
from typing import Any, ClassVar

import gymnasium
import numpy as np
from gymnasium_robotics.envs.maze import maps
from gymnasium_robotics.envs.maze.maze_v4 import Maze

from planshape.errors import BadInputError, UnknownIdError
from planshape.planning.grid import Cell, GridNames, cell_name, grid_pddl
from planshape.planning.model import AbstractState
from planshape.shaping.abstraction import Vectorized
from planshape.shaping.registration import AbstractModel
from planshape.tasks.common import generated_file
from planshape.tasks.goal_env import GoalTask, achieved_goal, check_reward
from planshape.tasks.regions import Lattice


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
    check_reward(reward, task.env_id)
    sim = gymnasium.make(
        task.env_id,
        maze_map=task.maze_map(),
        continuing_task=False,
        reward_type=reward,
        **kwargs,
    ).unwrapped
    return PointMazeTask(sim, task.cell_centres()[cell_name(task.goal_cell)])


@dataclass(frozen=True)
class InCell:
    """Vectorized classifier of ``(robot_at ?c)``: the ball lies in the cell. The cells tile the
    maze (:class:`planshape.tasks.regions.Lattice`), so the ball is in exactly one cell, also on an
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
