"""The shared body of the planar tasks: physics stepping, the workspace rule, seeding, reward
variants and the ``info`` every step reports. Each task module only says what it observes,
where its goal is and how far it is from it.

Step semantics (from the paper's released code):

* the action is clipped to ``[-1, 1]²``; the servo target is the end effector's *current*
  position plus ``step_size · action``;
* a target outside the workspace is **rejected**: the end effector holds its position for that
  step and ``info["move_rejected"]`` is true (the paper's code skips the move likewise; a
  non-finite action is rejected the same way);
* walls and the box are real MuJoCo contacts, so a blocked end effector stops at the wall
  (``wall_contact = "slide"``); a task with ``wall_contact = "reject"`` (reach-v1, as the
  paper's reaching code does: it undoes a move after which the arm touches the wall) rejects a
  move whose target, or the midpoint on the way to it, brings the end effector within its
  radius of a wall: the end effector holds its position and ``info["move_rejected"]`` is true;
* the environment never terminates and never truncates: success does not end the episode
  (the task is to reach the goal and stay there), and the horizon is left to Gymnasium's
  ``TimeLimit`` (``max_episode_steps`` at registration).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, ClassVar, Literal

import gymnasium
import mujoco
import numpy as np
from gymnasium import spaces

from planshape.errors import BadInputError, UnknownIdError
from planshape.tasks.planar.geometry import PlanarGeometry, Point, Rect
from planshape.tasks.planar.model import PHYSICS, PlanarPhysics, planar_mjcf
from planshape.tasks.planar.render import draw
from planshape.tasks.planar.versions import planar_version

RewardVariant = Literal["sparse", "dense"]
REWARD_VARIANTS: tuple[str, ...] = ("sparse", "dense")

# Rejection sampling of random starts and goals gives up after this many draws (only reachable
# with a custom geometry whose regions leave no room).
_MAX_DRAWS = 1000


class PlanarEnv(gymnasium.Env[np.ndarray, np.ndarray]):
    """Base class of :class:`ReachEnv`, :class:`PushEnv` and :class:`MazeReachEnv`.

    Subclasses set :attr:`task`, :attr:`entities` and the hooks ``_default_goal``,
    ``_goal_region``, ``_task_distance``, ``_dense_reward`` and, with a box or walls,
    :attr:`has_box` / :attr:`walls`.

    Args:
        reward: ``"sparse"`` (1.0 on success, else 0.0) or ``"dense"`` (the task's hand-crafted
            dense reward, see the subclass).
        randomize_start: draw the start (end effector, and the box in push) from
            ``self.np_random`` on every reset instead of the paper's fixed start.
        randomize_goal: draw the goal from the task's goal region on every reset.
        render_mode: ``None`` or ``"rgb_array"`` (a top-down picture, see ``render.py``).
        version: ``"v0"`` or ``"v1"``, the geometry and physics of that task version (see
            :mod:`planshape.tasks.planar.versions`).
        geometry: a custom geometry instead of the version's.
        instances: ``None`` (a fixed task), or ``"train"`` / ``"eval"``: every episode is one
            instance of the task's distribution (:mod:`planshape.tasks.planar.instances`), drawn
            from that set with ``self.np_random``, or chosen with ``reset(options={"instance":
            k})``. The goal is then appended to the observation (one policy for every goal),
            and ``info["instance"]`` holds the episode's :class:`Instance`.
    """

    metadata: ClassVar[dict[str, Any]] = {
        "render_modes": ["rgb_array"],
        "render_fps": round(1.0 / PHYSICS.control_dt),  # the same in every version
    }

    task: ClassVar[str] = ""
    has_box: ClassVar[bool] = False
    entities: ClassVar[Mapping[str, slice]] = {"ee": slice(0, 2)}
    """Where each entity's (x, y) lies in the observation."""
    wall_contact: ClassVar[str] = "slide"
    """What a wall does to the end effector: ``"slide"`` (a MuJoCo contact) or ``"reject"``
    (a move that would touch it is not made)."""

    def __init__(
        self,
        reward: RewardVariant = "sparse",
        randomize_start: bool = False,
        randomize_goal: bool = False,
        render_mode: str | None = None,
        version: str = "v0",
        geometry: PlanarGeometry | None = None,
        instances: str | None = None,
    ) -> None:
        if reward not in REWARD_VARIANTS:
            raise UnknownIdError(
                "reward variant",
                str(reward),
                REWARD_VARIANTS,
                hint=f"the {self.task} environment implements 'sparse' and 'dense'; "
                "'shaped' is applied by gymnasium.make on a registered planshape/ id",
            )
        if render_mode not in (None, "rgb_array"):
            raise BadInputError(
                f"{self.task}: render_mode={render_mode!r} is not supported; use None or "
                "'rgb_array' (a top-down picture drawn without OpenGL)"
            )
        self.reward_variant: RewardVariant = reward
        self.randomize_start = bool(randomize_start)
        self.randomize_goal = bool(randomize_goal)
        self.render_mode = render_mode
        #: points drawn on every rendered frame (planshape.results.videos draws the plan's subgoals)
        self.render_marks: list[tuple[float, float]] = []
        chosen = planar_version(version)
        self.version = version
        self.geometry = geometry = geometry or chosen.geometry
        self.physics: PlanarPhysics = chosen.physics

        self._model = mujoco.MjModel.from_xml_string(
            planar_mjcf(geometry, box=self.has_box, walls=self.walls, physics=self.physics)
        )
        self._data = mujoco.MjData(self._model)
        self._frame_skip = self.physics.frame_skip
        self._step_size = float(geometry.step_size)
        self._threshold = float(geometry.success_threshold)
        (self._x_lo, self._y_lo) = geometry.workspace.low
        (self._x_hi, self._y_hi) = geometry.workspace.high
        self._dense = reward == "dense"
        self._instances: tuple[Any, ...] = ()
        if instances is not None:
            from planshape.tasks.planar.instances import instance_set

            self._instances = instance_set(self.task).split(instances)
        self.instance: Any = None
        """This episode's instance (None for a fixed task)."""
        self._goal = np.array(self._default_goal(), dtype=np.float64)
        self._gx, self._gy = float(self._goal[0]), float(self._goal[1])
        self._rejecting_walls = self.walls if self.wall_contact == "reject" else ()
        #: v1 computes a move's target from the position clipped to the workspace (what the
        #: learner observes); v0 from the raw position, kept for its stored runs
        self._target_from_observation = version != "v0"
        self._reach_clearance = float(geometry.ee_radius)
        self._detour_reached = False
        #: the task distance after the previous step (the paper's push reward reads it)
        self._previous_distance = math.nan

        self.action_space = spaces.Box(-1.0, 1.0, shape=(2,), dtype=np.float32)
        low, high = self._observation_bounds()
        self.observation_space = spaces.Box(low, high, dtype=np.float32)
        self._obs_bounds = (low.astype(np.float64).tolist(), high.astype(np.float64).tolist())
        # A view of the observed coordinates in MjData (its buffers never move).
        self._qpos_obs = self._data.qpos[: self._model.nq]

    # ---- hooks -------------------------------------------------------------------------------

    @property
    def walls(self) -> tuple[Rect, ...]:
        """Static walls of this task (none by default)."""
        return ()

    def _default_goal(self) -> tuple[float, float]:
        raise NotImplementedError

    def _goal_region(self) -> Rect:
        raise NotImplementedError

    def _task_distance(self, q: list[float]) -> float:
        """The task's distance to its goal (the paper's final-distance metric), from the
        observed coordinates ``q`` (qpos as Python floats)."""
        raise NotImplementedError

    def _dense_reward(self, q: list[float], distance: float) -> float:
        raise NotImplementedError

    def _detour_reward(self, q: list[float], distance: float, detour: tuple[Point, ...]) -> float:
        """The paper's dense reward of its reaching tasks (``_get_reward_with_subgoal``): until
        the end effector has once come within the success threshold of the detour point nearest
        to it, −(its distance to that point + that point's distance to the goal); from then on,
        −(its distance to the goal). The latch is not in the observation, as in the paper; it
        resets on ``reset``. Without detour points: −distance."""
        if not detour:
            return -distance
        x, y = q[0], q[1]
        near = min(detour, key=lambda p: math.hypot(x - p[0], y - p[1]))
        to_near = math.hypot(x - near[0], y - near[1])
        if to_near < self._threshold:
            self._detour_reached = True
        if self._detour_reached:
            return -distance
        return -(to_near + math.hypot(self._gx - near[0], self._gy - near[1]))

    def _touches_wall(self, x: float, y: float, tx: float, ty: float) -> bool:
        """Whether a move to ``(tx, ty)`` (or its midpoint) brings the end effector within its
        radius of a rejecting wall."""
        mx, my = (x + tx) / 2, (y + ty) / 2
        r = self._reach_clearance
        return any(
            wall.distance((tx, ty)) < r or wall.distance((mx, my)) < r
            for wall in self._rejecting_walls
        )

    def _sample_start(self) -> None:
        """Write a random start into qpos (default: the end effector anywhere in the workspace,
        clear of walls, not already successful)."""
        region = self.geometry.ee_start_region
        for _ in range(_MAX_DRAWS):
            ee = region.sample(self.np_random)
            if self._ee_start_ok(ee):
                self._data.qpos[0:2] = ee
                return
        raise BadInputError(f"{self.task}: found no valid random start in {_MAX_DRAWS} draws")

    def _sample_goal(self) -> np.ndarray:
        return self._goal_region().sample(self.np_random)

    # ---- shared machinery --------------------------------------------------------------------

    def _observation_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        ws = self.geometry.workspace
        low, high = list(ws.low), list(ws.high)
        if self.has_box:
            bb = self.geometry.box_bounds
            low += bb.low
            high += bb.high
        if self._instances:  # the goal, which changes between instances
            low += ws.low
            high += ws.high
        return np.array(low, dtype=np.float32), np.array(high, dtype=np.float32)

    def _ee_start_ok(self, ee: np.ndarray) -> bool:
        clearance = self.geometry.ee_radius + 0.005
        if any(wall.contains(ee, clearance) for wall in self.walls):
            return False
        return bool(np.hypot(ee[0] - self._gx, ee[1] - self._gy) >= 2 * self._threshold)

    def _observation(self, q: list[float]) -> np.ndarray:
        # The servo overshoots its target by micrometres at most, but an observation on a
        # bound must stay inside the space: clip (in Python: cheaper than numpy for 2-4 values).
        lo, hi = self._obs_bounds
        if self._instances:
            q = [*q, self._gx, self._gy]
        clipped = [min(max(a, a_lo), a_hi) for a, a_lo, a_hi in zip(q, lo, hi, strict=True)]
        obs = np.array(clipped, dtype=np.float32)
        # read-only: a fresh array every step that nothing downstream may change, so that a
        # potential can be handed it as it is (planshape.shaping.potentials.read_only); copy it to
        # edit
        obs.flags.writeable = False
        return obs

    def _info(
        self, q: list[float], distance: float, success: bool, rejected: bool
    ) -> dict[str, Any]:
        info: dict[str, Any] = {
            "success": success,
            "distance": distance,
            "move_rejected": rejected,
            "ee_position": np.array(q[0:2]),
            "goal_position": self._goal.copy(),
        }
        if self.has_box:
            info["box_position"] = np.array(q[2:4])
        return info

    @property
    def goal(self) -> np.ndarray:
        """This episode's goal (of the end effector, or of the box in push); a copy."""
        return self._goal.copy()

    @property
    def ee_position(self) -> np.ndarray:
        """The end effector's current (x, y); a copy."""
        return self._data.qpos[0:2].copy()

    @property
    def model(self) -> mujoco.MjModel:
        """The MuJoCo model (read it, do not edit it)."""
        return self._model

    @property
    def data(self) -> mujoco.MjData:
        """The MuJoCo data of the current state."""
        return self._data

    def render(self) -> np.ndarray | None:
        """A top-down RGB picture of the current state when ``render_mode="rgb_array"``."""
        if self.render_mode != "rgb_array":
            return None
        q = self._data.qpos
        box = (float(q[2]), float(q[3])) if self.has_box else None
        ee = (float(q[0]), float(q[1]))
        return draw(self.geometry, ee, self._goal, self.walls, box, self.render_marks)

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        """Start an episode.

        ``options`` may override this episode's positions: ``"goal"``, ``"ee_start"`` and, in
        push, ``"box_start"`` (each an (x, y) pair); they take precedence over the
        ``randomize_*`` draws. With instances, ``"instance"`` (an index into the set) chooses
        the episode's instance, and ``"ee_start"``/``"box_start"`` still apply on top.
        """
        super().reset(seed=seed)
        options = options or {}
        self._detour_reached = False
        model, data = self._model, self._data
        mujoco.mj_resetData(model, data)
        if "instance" in options and not self._instances:
            raise BadInputError(f"{self.task}: option 'instance' needs instances='train'/'eval'")
        if self._instances:
            self.instance = self._chosen_instance(options)
            self._set_goal(self.instance.goal)
            data.qpos[0:2] = self.instance.ee_start
            if self.has_box:
                data.qpos[2:4] = self.instance.box_start
        else:
            if "goal" in options:
                self._set_goal(np.asarray(options["goal"], dtype=np.float64).reshape(2))
            elif self.randomize_goal:
                self._set_goal(self._sample_goal())
            else:
                self._set_goal(self._default_goal())
            if self.randomize_start:  # after the goal: a start is drawn clear of it
                self._sample_start()
            else:
                self._set_default_start()
        if "ee_start" in options:
            data.qpos[0:2] = np.asarray(options["ee_start"], dtype=np.float64).reshape(2)
        if "box_start" in options:
            if not self.has_box:
                raise BadInputError(f"{self.task}: option 'box_start' needs a task with a box")
            data.qpos[2:4] = np.asarray(options["box_start"], dtype=np.float64).reshape(2)
        ee = data.qpos[0:2]
        if not self.geometry.in_workspace(ee):
            raise BadInputError(
                f"{self.task}: end-effector start {tuple(ee)} is outside the workspace "
                f"{self.geometry.workspace}"
            )
        if any(wall.distance(ee) < self.geometry.ee_radius for wall in self.walls):
            raise BadInputError(f"{self.task}: end-effector start {tuple(ee)} overlaps a wall")
        data.ctrl[0:2] = data.qpos[0:2]
        mujoco.mj_forward(model, data)

        q = self._qpos_obs.tolist()
        distance = self._task_distance(q)
        self._previous_distance = distance
        info = self._info(q, distance, distance < self._threshold, False)
        if self.instance is not None:
            info["instance"] = self.instance
        return self._observation(q), info

    def _set_goal(self, goal: Any) -> None:
        self._goal = np.array(goal, dtype=np.float64).reshape(2)
        self._gx, self._gy = float(self._goal[0]), float(self._goal[1])

    def _chosen_instance(self, options: dict[str, Any]) -> Any:
        """This episode's instance: ``options["instance"]`` (an index into the set), or one
        drawn with ``self.np_random``."""
        n = len(self._instances)
        if "instance" in options:
            k = options["instance"]
            if isinstance(k, bool) or not isinstance(k, int | np.integer) or not 0 <= k < n:
                raise BadInputError(
                    f"{self.task}: option 'instance' must be an index in [0, {n}), not {k!r}"
                )
        else:
            k = int(self.np_random.integers(n))
        return self._instances[int(k)]

    def _set_default_start(self) -> None:
        self._data.qpos[0:2] = self.geometry.ee_start

    def step(self, action: np.ndarray) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        """Move the end effector by ``step_size · clip(action, -1, 1)`` unless that leaves the
        workspace (see the module docstring); ``terminated`` and ``truncated`` are always
        False."""
        data = self._data
        x, y = data.qpos[0:2].tolist()
        if self._target_from_observation:
            # the servo may rest micrometres past a workspace bound; from there a move with no
            # component across the bound would count as leaving the workspace
            x = min(max(x, self._x_lo), self._x_hi)
            y = min(max(y, self._y_lo), self._y_hi)
        ax, ay = action
        ax = float(ax)
        ay = float(ay)
        # Clip to [-1, 1]; NaN falls through the comparisons and fails the workspace test below.
        ax = -1.0 if ax < -1.0 else (1.0 if ax > 1.0 else ax)
        ay = -1.0 if ay < -1.0 else (1.0 if ay > 1.0 else ay)
        tx = x + self._step_size * ax
        ty = y + self._step_size * ay
        rejected = not (self._x_lo <= tx <= self._x_hi and self._y_lo <= ty <= self._y_hi)
        if self._rejecting_walls and not rejected:
            rejected = self._touches_wall(x, y, tx, ty)
        ctrl = data.ctrl
        if rejected:
            ctrl[0] = x
            ctrl[1] = y
        else:
            ctrl[0] = tx
            ctrl[1] = ty
        mujoco.mj_step(self._model, data, self._frame_skip)

        q = self._qpos_obs.tolist()
        distance = self._task_distance(q)
        success = distance < self._threshold
        reward = self._dense_reward(q, distance) if self._dense else float(success)
        self._previous_distance = distance
        info = self._info(q, distance, success, rejected)
        return self._observation(q), reward, False, False, info
