"""One MetaWorld v3 task as a plain Gymnasium environment: reward variants, seeding, metrics.

:class:`MetaWorldTask` drives the task's ``SawyerXYZEnv`` directly (not ``Meta-World/MT1``,
whose stack of wrappers re-samples one of 50 pre-drawn goals on every reset with its own
generator and lets the inner environment raise when stepped past its horizon):

* **Observation**: MetaWorld's 39-dimensional ``Box`` with the goal position visible in
  ``obs[36:39]``, as in MT1, and, with ``observe_tcp=True`` on a task with one object, the
  fingertip centre ``tcp_center`` in the second object's otherwise zero-padded slot
  ``obs[11:14]`` (and one step earlier in ``obs[29:32]``, by MetaWorld's own frame stacking).
  MetaWorld's success tests measure from ``tcp_center``, which the other numbers do not
  determine (see :mod:`planshape.tasks.metaworld.observation`); with it observed, a classifier
  can test exactly what ``info["success"]`` tests. MetaWorld's scripted experts and its
  ``evaluate_state`` do not read that slot.
* **Reward**: ``reward="sparse"`` pays ``float(info["success"])``; ``reward="dense"`` is
  MetaWorld's own (v2) shaped reward, in [0, 10].
* **Seeding**: ``reset(seed=s)`` seeds the task's generator, which draws the object and goal
  positions of the episode from the task's own random-reset box (the distribution MT1 takes its
  50 goals from). The same seed gives the same episode; a ``reset()`` without a seed draws the
  next positions from the same generator, so the goal changes between episodes but a seeded
  sequence of episodes is reproducible.
* **Episode end**: MetaWorld never terminates; it truncates after ``max_path_length`` steps
  (500 by default, the registered ``max_episode_steps``) and refuses to step further, which
  this wrapper reports as :class:`gymnasium.error.ResetNeeded` with a message that says what to
  do. Success does not end the episode.
* **Reset observation**: recomputed after a forward pass of the simulator, because MetaWorld
  computes it before the positions it has just set are propagated (window-open and
  window-close showed the handle where the previous episode left it).
* **info**: ``success`` (bool) and ``distance``, the task's own distance to its goal (see
  :data:`DISTANCES`), after every step and after ``reset``.

Example:
    >>> env = MetaWorldTask("reach-v3", reward="sparse")  # doctest: +SKIP
    >>> obs, info = env.reset(seed=0)  # doctest: +SKIP
    >>> obs.shape, info["success"]  # doctest: +SKIP
    ((39,), False)
"""

from __future__ import annotations

import types
from typing import Any, ClassVar, SupportsFloat

import gymnasium
import mujoco
import numpy as np
from metaworld.env_dict import ALL_V3_ENVIRONMENTS

from planshape.errors import BadInputError, UnknownIdError
from planshape.tasks.metaworld import observation as layout

REWARDS = ("sparse", "dense")


def _info_distance(_obs: np.ndarray, info: dict[str, Any]) -> float:
    """MetaWorld's ``obj_to_target``: the quantity its success test compares to a radius."""
    return float(info["obj_to_target"])


def _door_distance(obs: np.ndarray, _info: dict[str, Any]) -> float:
    """door-open-v3 reports ``obj_to_target = 0``; its success is ``|handle_x − goal_x| ≤ 0.08``,
    so the handle's x-distance to the goal is the distance."""
    return float(abs(obs[layout.OBJECT][0] - obs[layout.GOAL][0]))


#: How each task's ``info["distance"]`` is computed, by MetaWorld name; tasks not listed use
#: MetaWorld's ``obj_to_target`` (reach: fingertips to goal; push and pick-place: puck to goal;
#: drawer-open and drawer-close: handle to goal; button-press-topdown and button-press: the
#: button's height or depth to the goal's; window-open and window-close: handle's x to goal's x).
DISTANCES = {"door-open-v3": _door_distance}


def _observe_tcp(sim: Any) -> bool:
    """Make ``sim``'s per-frame observation carry ``tcp_center`` in the second object's slot.

    The 18 numbers of one frame come from ``_get_curr_obs_combined_no_goal``, which ``_get_obs``
    calls for the current frame and remembers as the previous one, so wrapping it (on this
    instance) puts the fingertip centre in both frames, in the step's observation, in the
    observation MetaWorld's ``evaluate_state`` is given and in the last stable observation it
    returns after a simulator exception. It is read after the same ``mj_forward`` as the
    ``tcp_center`` of MetaWorld's reward and success, so the two are the same numbers.

    Returns whether the slot was free (tasks with a second object keep MetaWorld's layout).
    """
    if len(sim._get_pos_objects()) + len(sim._get_quat_objects()) > 7:
        return False  # a second object fills obs[11:18]
    # A bound method, not a closure, so that a deep copy of the simulator reads its own state.
    sim._get_curr_obs_combined_no_goal = types.MethodType(_frame_with_tcp, sim)
    sim._prev_obs = sim._get_curr_obs_combined_no_goal()
    return True


def _frame_with_tcp(sim: Any) -> np.ndarray:
    """MetaWorld's 18 numbers of one frame, with ``tcp_center`` in ``[11:14]``."""
    combined = type(sim)._get_curr_obs_combined_no_goal(sim)
    combined[layout.TCP] = sim.tcp_center
    return combined


class MetaWorldTask(gymnasium.Env):
    """A MetaWorld v3 task with a sparse or dense reward (see the module docstring).

    The MetaWorld environment is held in :attr:`sim`, not wrapped: MetaWorld's environments
    define ``compute_reward``, and checkers (stable-baselines3's among them) would take an
    environment whose ``unwrapped`` has one for a goal-conditioned ``GoalEnv``.

    Args:
        env_name: MetaWorld's name of the task, e.g. ``"reach-v3"``.
        reward: ``"sparse"`` (success, 0 or 1) or ``"dense"`` (MetaWorld's reward).
        max_path_length: steps after which MetaWorld truncates the episode; keep it equal to
            the ``max_episode_steps`` given to ``gymnasium.make``.
        render_mode: passed to MetaWorld (``"rgb_array"``, ``"human"``, …).
        observe_tcp: write ``tcp_center`` into ``obs[11:14]`` (a task with one object only).
        **env_kwargs: further keyword arguments of the MetaWorld environment class (camera,
            image size).

    Attributes:
        observes_tcp: whether ``obs[11:14]`` holds ``tcp_center`` (``observe_tcp=True``).
    """

    metadata: ClassVar[dict[str, Any]] = {"render_modes": ["human", "rgb_array", "depth_array"]}

    def __init__(
        self,
        env_name: str,
        reward: str = "sparse",
        max_path_length: int = 500,
        render_mode: str | None = None,
        observe_tcp: bool = False,
        **env_kwargs: Any,
    ):
        if env_name not in ALL_V3_ENVIRONMENTS:
            raise UnknownIdError(
                "MetaWorld environment", env_name, ALL_V3_ENVIRONMENTS, hint="v3 names only"
            )
        if reward not in REWARDS:
            raise UnknownIdError("reward variant", reward, REWARDS, hint=f"for {env_name}")
        if max_path_length < 1:
            raise BadInputError(f"{env_name}: max_path_length must be positive")
        sim = ALL_V3_ENVIRONMENTS[env_name](render_mode=render_mode, **env_kwargs)
        # What MT1 does through set_task(), without its fixed list of 50 goals: make the goal
        # visible, and draw object and goal positions from the env's own seeded generator.
        sim._partially_observable = False
        del sim.sawyer_observation_space  # a cached property computed for the hidden goal
        sim.observation_space = sim.sawyer_observation_space
        sim._set_task_called = True
        sim._freeze_rand_vec = False
        sim.seeded_rand_vec = True
        sim.max_path_length = max_path_length
        self.observes_tcp = bool(observe_tcp) and _observe_tcp(sim)
        if observe_tcp and not self.observes_tcp:
            raise BadInputError(
                f"{env_name}: observe_tcp=True needs the second object's slot obs[11:18], which "
                "this task uses; make it with observe_tcp=False"
            )
        self.sim = sim
        self.env_name = env_name
        self.reward_variant = reward
        self.max_path_length = max_path_length
        self.render_mode = render_mode
        self.metadata = {**self.metadata, "render_fps": sim.metadata.get("render_fps")}
        self.observation_space = sim.observation_space
        self.action_space = sim.action_space
        self._distance = DISTANCES.get(env_name, _info_distance)
        self._needs_reset = True

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        super().reset(seed=seed)
        if seed is not None:
            # MetaWorld's reset ignores its seed argument; seed() is how it takes one.
            self.sim.seed(seed)
        _, info = self.sim.reset()
        obs = self._refreshed_observation()
        _, evaluation = self.sim.evaluate_state(obs, np.zeros(4, dtype=np.float32))
        info["success"] = bool(evaluation["success"])
        info["distance"] = self._distance(obs, evaluation)
        self._needs_reset = False
        return obs, info

    def _refreshed_observation(self) -> np.ndarray:
        """The observation of the state ``reset`` left, computed after ``mj_forward``.

        Some tasks move bodies and joints in ``reset_model`` without a forward pass (window-open
        and window-close set the window's position and slide joint), so the observation
        MetaWorld returns shows their handle where the previous episode left it.
        """
        mujoco.mj_forward(self.sim.model, self.sim.data)
        self.sim._prev_obs = self.sim._get_curr_obs_combined_no_goal()
        return self.sim._get_obs().astype(np.float64)

    def step(self, action: Any) -> tuple[np.ndarray, SupportsFloat, bool, bool, dict[str, Any]]:
        if self._needs_reset:
            raise gymnasium.error.ResetNeeded(
                f"{self.env_name}: call reset() before step(); MetaWorld episodes end after "
                f"max_path_length={self.max_path_length} steps (pass a larger max_path_length "
                "together with max_episode_steps for longer episodes)"
            )
        obs, reward, terminated, truncated, info = self.sim.step(action)
        success = bool(info["success"])
        info["success"] = success
        info["distance"] = self._distance(obs, info)
        self._needs_reset = bool(terminated or truncated)
        reward = float(success) if self.reward_variant == "sparse" else float(reward)
        return obs, reward, bool(terminated), bool(truncated), info

    def render(self) -> Any:
        return self.sim.render()

    def close(self) -> None:
        self.sim.close()
