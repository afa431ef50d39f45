"""Potential-based reward shaping as a :class:`gymnasium.Wrapper`.

On every step the wrapper classifies the new observation, moves plan progress forward, evaluates
φ on the augmented state (observation, progress, time) and returns R + F with

    F = γ·φ(s') − φ(s),

obeying the correctness rules of ARCHITECTURE.md:

1. γ is a required argument and must equal the learner's discount
   (:func:`planshape.training.algorithm.check_gamma` refuses a mismatch).
2. φ(s') = 0 when the episode *terminates*; on truncation φ(s') is used as usual, so that a
   learner that bootstraps on truncation stays correct.
3. φ(s) is the value stored at the previous step, never recomputed with newer progress, so over
   an episode Σ γ^t F_t = γ^T φ_T − φ_0.
4. Progress and the time index reset on ``reset()``.

Place the wrapper *inside* each environment of a vectorized env (stable-baselines3's VecEnv
handles truncation bootstrapping outside it), which is what ``gymnasium.make(id,
reward="shaped", ...)`` gives.

Example:
    >>> import gymnasium
    >>> import planshape
    >>> env = gymnasium.make("planshape/Reach-v0", reward="shaped", potential="plan-based",
    ...                      model="multi", gamma=0.99)  # doctest: +SKIP
    >>> obs, info = env.reset(seed=0)  # doctest: +SKIP
    >>> obs, reward, done, cut, info = env.step(env.action_space.sample())  # doctest: +SKIP
    >>> info["reward_original"] + info["shaping"] == reward  # doctest: +SKIP
    True
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, SupportsFloat

import gymnasium

from planshape.errors import BadInputError
from planshape.shaping.potentials import Geometry, Potential, ShapingContext, StepPotential
from planshape.shaping.progress import PlanProgress


class PotentialShaping(gymnasium.Wrapper):
    """Adds F = γ·φ(s') − φ(s) to the reward of ``env``.

    Args:
        env: the task environment with its own (sparse or dense) reward.
        potential: φ, see :class:`planshape.shaping.potentials.Potential`; the wrapper shapes with
            ``potential.for_discount(gamma)`` (a potential defined through the learner's
            discount takes it from here).
        progress: the plan's subgoals and the reached test (:class:`PlanProgress`).
        gamma: the learner's discount, 0 < γ ≤ 1. Required: a shaping γ that differs from the
            learner's changes the optimal policy.
        geometry: the task's ``locate``/``positions`` hooks, for potentials that use distances.
        plans: for a task-instance distribution, instance -> (progress, geometry): on every
            ``reset`` the wrapper reads the episode's instance from ``info["instance"]`` and
            shapes the episode with that instance's plan (``progress`` and ``geometry`` are then
            those of the current episode; before the first reset, those given). The plan
            changes only on ``reset``.

    ``info`` gains, on every step: ``reward_original`` (the reward before shaping),
    ``shaping`` (F), ``potential`` (φ of the new state as used in F), ``progress`` (max_idx);
    the task's own ``success`` passes through. After ``reset`` it gains ``potential`` and
    ``progress``.
    """

    def __init__(
        self,
        env: gymnasium.Env,
        potential: Potential,
        progress: PlanProgress,
        *,
        gamma: float,
        geometry: Geometry | None = None,
        plans: Callable[[Any], tuple[PlanProgress, Geometry | None]] | None = None,
    ):
        super().__init__(env)
        if isinstance(gamma, bool) or not isinstance(gamma, int | float) or not 0 < gamma <= 1:
            raise BadInputError(
                f"gamma must be a number in (0, 1], the learner's discount; got {gamma!r}"
            )
        self.shaping_gamma = float(gamma)
        self.potential = potential.for_discount(self.shaping_gamma)
        self.progress = progress
        self.geometry = geometry
        self._plans = plans
        self._max_idx = 0
        self._t = 0
        self._phi_prev = 0.0
        # the potential specialized to the current plan (Potential.specialize), and for what
        self._step_phi: StepPotential | None = None
        self._timed = False
        self._specialized_for: tuple[Any, ...] = (None, None, None)

    def _context(self, obs: Any) -> ShapingContext:
        return ShapingContext(
            obs=obs,
            progress=self._max_idx,
            t=self._t,
            subgoals=self.progress.subgoals,
            geometry=self.geometry,
            abstraction=self.progress.abstraction,
        )

    def _phi(self, obs: Any) -> float:
        step_phi = self._step_phi
        if step_phi is not None:
            raw = (
                step_phi(obs, self._max_idx, self._t)
                if self._timed
                else step_phi(obs, self._max_idx)
            )
            if type(raw) is float:  # as Potential.__call__: scale, then check finiteness
                value = self.potential.scale * raw
                if value - value == 0.0:
                    return value
        return self.potential(self._context(obs))  # which names what is wrong, if anything

    def _specialize(self, obs: Any) -> None:
        """Fetch the potential's per-plan step function when the plan or potential changed."""
        key = (self.potential, self.progress, self.geometry)
        if any(a is not b for a, b in zip(key, self._specialized_for, strict=True)):
            self._step_phi = self.potential.step_function(self._context(obs))
            self._timed = self.potential.time_dependent  # its step function takes t too
            self._specialized_for = key

    def reset(self, **kwargs: Any) -> tuple[Any, dict[str, Any]]:
        obs, info = self.env.reset(**kwargs)
        if self._plans is not None:
            if info.get("instance") is None:
                raise BadInputError(
                    f"{self.env}: shaping per instance needs info['instance'] from reset; the "
                    "environment reported none"
                )
            self.progress, self.geometry = self._plans(info["instance"])
        self._t = 0
        self._max_idx = int(self.progress.initial(obs))
        self._specialize(obs)
        self._phi_prev = self._phi(obs)
        info["potential"] = self._phi_prev
        info["progress"] = self._max_idx
        return obs, info

    def step(self, action: Any) -> tuple[Any, SupportsFloat, bool, bool, dict[str, Any]]:
        obs, reward, terminated, truncated, info = self.env.step(action)
        self._t += 1
        self._max_idx = int(self.progress.advance(self._max_idx, obs))
        phi = 0.0 if terminated else self._phi(obs)
        shaping = self.shaping_gamma * phi - self._phi_prev
        self._phi_prev = phi
        info["reward_original"] = reward
        info["shaping"] = shaping
        info["potential"] = phi
        info["progress"] = self._max_idx
        return obs, float(reward) + shaping, terminated, truncated, info

    @property
    def per_instance(self) -> bool:
        """Whether each episode is shaped with its own instance's plan."""
        return self._plans is not None

    @property
    def max_idx(self) -> int:
        """The current episode's progress (read-only)."""
        return self._max_idx
