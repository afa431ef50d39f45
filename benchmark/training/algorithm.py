"""Pairing shaped environments with stable-baselines3 learners.

The shaping wrapper's γ must equal the learner's discount (correctness rule 1); here a mismatch
is an error, not a warning.

Example:
    >>> import gymnasium, planshape
    >>> from stable_baselines3 import PPO
    >>> from stable_baselines3.common.env_util import make_vec_env
    >>> venv = make_vec_env("planshape/Reach-v0", n_envs=2, env_kwargs=dict(
    ...     reward="shaped", potential="plan-based", model="multi", gamma=0.99))  # doctest: +SKIP
    >>> model = make_algorithm(PPO, venv)  # doctest: +SKIP
    >>> model.gamma  # doctest: +SKIP
    0.99
"""

from __future__ import annotations

from typing import Any

import gymnasium
import numpy as np
from stable_baselines3.common.base_class import BaseAlgorithm
from stable_baselines3.common.vec_env import VecEnv

from planshape.errors import GammaMismatchError

try:  # the VecEnv below is stable-baselines3's DummyVecEnv with one copy less
    from stable_baselines3.common.vec_env import DummyVecEnv
except ImportError:  # pragma: no cover - stable-baselines3 is a dependency
    DummyVecEnv = object  # type: ignore[assignment,misc]

GAMMA_ATTRIBUTE = "shaping_gamma"


def shaping_gammas(env: gymnasium.Env | VecEnv) -> list[float]:
    """The shaping γ of every shaped environment in ``env`` (empty when none is shaped)."""
    if isinstance(env, VecEnv):
        if not env.has_attr(GAMMA_ATTRIBUTE):
            return []
        return [float(g) for g in env.get_attr(GAMMA_ATTRIBUTE)]
    try:
        return [float(env.get_wrapper_attr(GAMMA_ATTRIBUTE))]
    except AttributeError:
        return []


def check_gamma(gamma: float, env: gymnasium.Env | VecEnv) -> None:
    """Raise :class:`GammaMismatchError` unless every shaping γ in ``env`` equals ``gamma``."""
    wrong = sorted({g for g in shaping_gammas(env) if g != float(gamma)})
    if wrong:
        raise GammaMismatchError(
            f"the environment shapes with gamma={wrong[0]} but the learner discounts with "
            f"gamma={gamma}; potential-based shaping preserves the optimal policy only when "
            "they are equal. Make the environment with the learner's gamma."
        )


def make_algorithm(
    algorithm: type[BaseAlgorithm], env: gymnasium.Env | VecEnv, **kwargs: Any
) -> BaseAlgorithm:
    """Construct ``algorithm(policy, env, **kwargs)`` with the learner's γ checked against the
    shaping γ. Without ``gamma=``, the learner takes the γ the environment was shaped with.
    """
    gammas = shaping_gammas(env)
    if gammas:
        kwargs.setdefault("gamma", gammas[0])
        check_gamma(kwargs["gamma"], env)
    policy = kwargs.pop("policy", "MultiInputPolicy" if _has_dict_obs(env) else "MlpPolicy")
    return algorithm(policy, env, **kwargs)


def _has_dict_obs(env: gymnasium.Env | VecEnv) -> bool:
    return isinstance(env.observation_space, gymnasium.spaces.Dict)


class FreshInfoVecEnv(DummyVecEnv):  # type: ignore[misc,valid-type]
    """stable-baselines3's ``DummyVecEnv`` without its deep copy of every step's infos.

    ``DummyVecEnv.step_wait`` returns ``deepcopy(infos)`` so that an environment that reuses
    its info dict between steps cannot change what the learner was given. Every planshape task
    (and the wrappers around it) returns a new dict on every step, and ``DummyVecEnv`` replaces
    its entries rather than mutating them after the step, so a shallow copy of the list gives
    the learner the same infos: the numbers of a run do not change (a test trains with both).
    The copy is 13 % of a PPO run on Push-v1 under cProfile; measured side by side without the
    profiler, PPO trains 3.4 % (sparse) and 4.1 % (shaped) faster without it. Use it for
    environments that return a fresh info dict on every step.
    """

    def step_wait(self):
        for env_idx in range(self.num_envs):
            obs, self.buf_rews[env_idx], terminated, truncated, info = self.envs[env_idx].step(
                self.actions[env_idx]
            )
            self.buf_dones[env_idx] = terminated or truncated
            info["TimeLimit.truncated"] = truncated and not terminated
            if self.buf_dones[env_idx]:
                info["terminal_observation"] = obs
                obs, self.reset_infos[env_idx] = self.envs[env_idx].reset()
            self.buf_infos[env_idx] = info
            self._save_obs(env_idx, obs)
        return (
            self._obs_from_buf(),
            np.copy(self.buf_rews),
            np.copy(self.buf_dones),
            list(self.buf_infos),
        )
