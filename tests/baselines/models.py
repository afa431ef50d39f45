"""The planar grid models, planned and bound once per test session."""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any

import numpy as np

from planshape.planning import PddlTask, Plan, load_task, solve
from planshape.shaping.abstraction import Abstraction
from planshape.shaping.potentials import ShapingContext
from planshape.shaping.progress import PlanProgress


@dataclass(frozen=True)
class Bound:
    """A task's abstract model with its plan, abstraction and progress tracker."""

    model: Any
    task: PddlTask
    plan: Plan
    abstraction: Abstraction
    progress: PlanProgress

    def ctx(self, obs, progress: int = 0, t: int = 0) -> ShapingContext:
        return ShapingContext(
            obs=np.asarray(obs, np.float32),
            progress=progress,
            t=t,
            subgoals=self.plan.subgoals,
            geometry=self.model.geometry,
            abstraction=self.abstraction,
        )


@functools.cache
def bound(factory: str) -> Bound:
    """``bound("maze_reach_grid")``: a model of :mod:`planshape.tasks.planar.abstract`."""
    from planshape.tasks.planar import abstract

    model = getattr(abstract, factory)()
    task = load_task(model.domain, model.problem)
    plan = solve(model.domain, model.problem, cache_dir=False)
    abstraction = Abstraction(task, model.classifiers)
    return Bound(model, task, plan, abstraction, PlanProgress(plan.subgoals, abstraction))
