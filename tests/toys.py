"""Small environments and abstract models defined for the tests only.

* :class:`ScriptedEnv` replays a given sequence of observations and termination flags, so a
  property test can drive the shaping wrapper through any trajectory.
* :class:`LineEnv` is a tiny continuous task: a point on [0, 1] moved by actions in [-1, 1]
  (0.1 per step), with places ``left``, ``middle``, ``right`` and goal ``right``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import gymnasium
import numpy as np

from planshape.planning.model import PddlTask, PredicateSignature
from planshape.shaping.abstraction import Abstraction
from planshape.shaping.progress import PlanProgress

PLACES = {"left": 0.0, "middle": 0.5, "right": 1.0}
RADIUS = 0.15

LINE_DOMAIN = """\
(define (domain line)
  (:requirements :strips :typing :negative-preconditions :equality)
  (:types place)
  (:predicates (at ?p - place) (adjacent ?a - place ?b - place))
  (:action move
    :parameters (?from - place ?to - place)
    :precondition (and (at ?from) (adjacent ?from ?to) (not (= ?from ?to)))
    :effect (and (at ?to) (not (at ?from)))))
"""

LINE_PROBLEM = """\
(define (problem line-right)
  (:domain line)
  (:objects left middle right - place)
  (:init (at left) (adjacent left middle) (adjacent middle left)
         (adjacent middle right) (adjacent right middle))
  (:goal (at right)))
"""


def at(obs: np.ndarray, place: str) -> np.ndarray:
    """Classifier of ``(at ?p)``: the point is within RADIUS of the place's centre."""
    return np.abs(obs[..., 0] - PLACES[place]) <= RADIUS


def line_task() -> PddlTask:
    """The line domain's PddlTask, built by hand (for tests that do not need the planner)."""
    return PddlTask(
        domain_name="line",
        problem_name="line-right",
        predicates={
            "at": PredicateSignature("at", ("place",)),
            "adjacent": PredicateSignature("adjacent", ("place", "place")),
        },
        types={"object": None, "place": "object"},
        objects={p: "place" for p in PLACES},
        init=frozenset(
            {("at", "left")}
            | {("adjacent", a, b) for a, b in [("left", "middle"), ("middle", "right")]}
            | {("adjacent", b, a) for a, b in [("left", "middle"), ("middle", "right")]}
        ),
        goal=frozenset({("at", "right")}),
        static_predicates=frozenset({"adjacent"}),
    )


def line_progress() -> PlanProgress:
    """Progress over the plan left -> middle -> right, with the ``at`` classifier."""
    subgoals = [frozenset({("at", p)}) for p in ("left", "middle", "right")]
    return PlanProgress(subgoals, Abstraction(line_task(), {"at": at}))


def write_line_model(folder: Path) -> tuple[Path, Path]:
    domain, problem = folder / "line-domain.pddl", folder / "line-problem.pddl"
    domain.write_text(LINE_DOMAIN)
    problem.write_text(LINE_PROBLEM)
    return domain, problem


class LineEnv(gymnasium.Env):
    """A point on [0, 1]; sparse reward 1 within RADIUS of the goal at 1.0."""

    metadata = {"render_modes": []}  # noqa: RUF012

    def __init__(self, terminate_on_success: bool = False, reward: str = "sparse"):
        self.observation_space = gymnasium.spaces.Box(0.0, 1.0, (1,), np.float64)
        self.action_space = gymnasium.spaces.Box(-1.0, 1.0, (1,), np.float32)
        self.terminate_on_success = terminate_on_success
        self.reward_kind = reward
        self._x = 0.0

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        super().reset(seed=seed)
        self._x = 0.0
        return np.array([self._x]), {"success": False}

    def step(self, action: Any):
        self._x = float(np.clip(self._x + 0.1 * float(np.clip(action[0], -1, 1)), 0.0, 1.0))
        success = abs(self._x - 1.0) <= RADIUS
        reward = float(success) if self.reward_kind == "sparse" else -abs(self._x - 1.0)
        terminated = success and self.terminate_on_success
        return np.array([self._x]), reward, terminated, False, {"success": success}


class ScriptedEnv(gymnasium.Env):
    """Replays ``observations[0]`` on reset, then one observation per step with the given
    rewards and termination/truncation flags."""

    metadata = {"render_modes": []}  # noqa: RUF012

    def __init__(self, observations, rewards, terminated, truncated):
        self.observation_space = gymnasium.spaces.Box(-np.inf, np.inf, (1,), np.float64)
        self.action_space = gymnasium.spaces.Discrete(2)
        self.script = (list(observations), list(rewards), list(terminated), list(truncated))
        self._k = 0

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        super().reset(seed=seed)
        self._k = 0
        return np.array([self.script[0][0]]), {}

    def step(self, action: Any):
        observations, rewards, terminated, truncated = self.script
        self._k += 1
        k = self._k
        obs = np.array([observations[k]])
        return obs, rewards[k - 1], terminated[k - 1], truncated[k - 1], {}
