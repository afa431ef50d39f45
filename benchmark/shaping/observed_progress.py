"""The learner observes plan progress: ``max_idx / n`` appended to the task's observation.

A potential φ(s, max_idx) makes the shaped reward a function of the augmented state (s,
max_idx), the state the invariance argument is made in (ARCHITECTURE.md, rule 4). A learner
that sees only s trains on rewards that depend on a history it cannot see: on MetaWorld's
button-press, ``(hand-in-front)`` is reached anywhere in a slab in front of the button, so the
same observation comes with either progress, and φ differs by half the scale between them.
Telescoping keeps every policy's shaped return equal to its unshaped one less φ(s0), so the
ranking of policies is unchanged either way; what the hidden progress adds is noise in the
critic's targets. :class:`ObservedProgress` removes it by showing the learner max_idx / n, one
number in [0, 1], after the task's own observation.

Over a shaping wrapper (training) it reads the progress the wrapper publishes in
``info["progress"]``, so no step is classified twice. Without one (the evaluation environment,
where the deterministic policy is scored on the task's own reward) it tracks progress itself
with the plan's :class:`~planshape.shaping.progress.PlanProgress`, the same classifiers and
``advance`` as the shaping wrapper, so the policy sees the progress of its own episode. On a
task-instance distribution it reads ``info["instance"]`` on every ``reset`` and uses that
instance's plan.

Example:
    >>> import gymnasium
    >>> import planshape
    >>> from planshape.shaping.registration import observe_progress
    >>> env = observe_progress(gymnasium.make("planshape/Reach-v1"), "planshape/Reach-v1", "single")
    >>> obs, info = env.reset(seed=0)
    >>> obs.shape, float(obs[-1])  # the task's two numbers, then progress 0 of the plan's n
    ((3,), 0.0)
    >>> float(env.observation_space.high[-1])
    1.0
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import gymnasium
import numpy as np

from planshape.errors import BadInputError
from planshape.shaping.progress import PlanProgress

__all__ = ["ObservedProgress"]


class ObservedProgress(gymnasium.ObservationWrapper):
    """Appends ``max_idx / n`` to a ``Box`` observation (``n``: the plan's last subgoal index;
    a plan of no step shows 0).

    Args:
        env: the task environment (shaped or not); its observation space must be a flat Box.
        progress: the plan's subgoals and reached test.
        plans: for a task-instance distribution, instance -> the instance's
            :class:`PlanProgress`, switched on every ``reset`` from ``info["instance"]``.
    """

    def __init__(
        self,
        env: gymnasium.Env,
        progress: PlanProgress,
        plans: Callable[[Any], PlanProgress] | None = None,
    ):
        super().__init__(env)
        space = env.observation_space
        if not isinstance(space, gymnasium.spaces.Box) or len(space.shape) != 1:
            raise BadInputError(
                f"observe_progress: {env.spec.id if env.spec else env} has observation space "
                f"{space}, not a flat Box, so its plan progress cannot be appended to it; train "
                "this task without observe_progress (no --observe-progress, a profile without it)"
            )
        self.progress = progress
        self._plans = plans
        self._max_idx = 0
        self.observation_space = gymnasium.spaces.Box(
            np.append(space.low, 0.0).astype(space.dtype),
            np.append(space.high, 1.0).astype(space.dtype),
            dtype=space.dtype,
        )

    def reset(self, **kwargs: Any) -> tuple[Any, dict[str, Any]]:
        obs, info = self.env.reset(**kwargs)
        if self._plans is not None:
            self.progress = self._plans(info["instance"])
        shaped = info.get("progress")
        self._max_idx = int(self.progress.initial(obs) if shaped is None else shaped)
        return self.observation(obs), info

    def step(self, action: Any) -> tuple[Any, Any, bool, bool, dict[str, Any]]:
        obs, reward, terminated, truncated, info = self.env.step(action)
        shaped = info.get("progress")
        self._max_idx = int(self.progress.advance(self._max_idx, obs) if shaped is None else shaped)
        return self.observation(obs), reward, terminated, truncated, info

    def observation(self, observation: Any) -> np.ndarray:
        """The task's observation with ``max_idx / n`` after it."""
        final = self.progress.final
        fraction = self._max_idx / final if final > 0 else 0.0
        return np.append(observation, fraction).astype(self.observation_space.dtype)
