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
from stable_baselines3.common.base_class import BaseAlgorithm
from stable_baselines3.common.vec_env import VecEnv

from planshape.errors import GammaMismatchError

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
