"""The source paper's three potentials (Section 4.1), as reference leaderboard entries.

All three read only the context the shaping wrapper gives them. Scales are part of each entry's
definition and are stated here, because the paper tuned "a constant multiplier" by hand:

* ``plan-based``: φ = scale · max_idx / n, n the plan length. Normalising by n makes finishing
  the plan worth ``scale`` whatever the model's granularity (single, multi or grid); pass
  ``normalize=False`` for the paper's raw φ = max_idx.
* ``time-varying``: φ(ŝ, t) = scale · (max_idx / n) / (t + 1), where t counts the steps taken
  since reset (0 at reset, so the divisor is the paper's 1-based time step). Each state's φ is
  taken at its own time index, as in Devlin & Kudenko (2012).
* ``distance-varying``: φ = −scale · d, where d is the distance between an entity and where the
  next subgoal Ŝ[max_idx + 1] needs it; entities are taken in the priority order of the task's
  ``locate`` hook (the end effector first, then the object), and the first one that is farther
  than ``tolerance`` from its target is the one measured (φ = 0 when all are within).

Example:
    >>> from planshape.shaping.potentials import ShapingContext
    >>> ctx = ShapingContext(obs=None, progress=2, t=3, subgoals=(frozenset(),) * 5)
    >>> PlanBased()(ctx), TimeVarying()(ctx)
    (0.5, 0.125)
"""

from __future__ import annotations

from typing import Any

import numpy as np

from planshape.baselines.common import point_distance
from planshape.shaping.potentials import Potential, ShapingContext, StepPotential


def _fraction_done(ctx: ShapingContext, normalize: bool) -> float:
    if not normalize:
        return float(ctx.progress)
    return ctx.progress / ctx.final if ctx.final else 0.0


class PlanBased(Potential):
    """φ = scale · max_idx / n (Grzes & Kudenko 2008 with max_idx tracking)."""

    def __init__(self, scale: float = 1.0, normalize: bool = True):
        super().__init__(scale)
        self.normalize = normalize

    def potential(self, ctx: ShapingContext) -> float:
        return _fraction_done(ctx, self.normalize)

    def specialize(self, ctx: ShapingContext) -> StepPotential | None:
        """:meth:`potential` as a function of progress alone."""
        final = ctx.final
        if not self.normalize:
            return lambda obs, progress: float(progress)
        return (lambda obs, progress: progress / final) if final else (lambda obs, p: 0.0)


class TimeVarying(Potential):
    """φ(ŝ, t) = scale · (max_idx / n) / (t + 1): a subgoal pays less the later it is reached."""

    time_dependent = True

    def __init__(self, scale: float = 1.0, normalize: bool = True):
        super().__init__(scale)
        self.normalize = normalize

    def potential(self, ctx: ShapingContext) -> float:
        return _fraction_done(ctx, self.normalize) / (ctx.t + 1)

    def specialize(self, ctx: ShapingContext) -> StepPotential | None:
        """:meth:`potential` as a function of (progress, t) alone."""
        final = ctx.final
        if not self.normalize:
            return lambda obs, progress, t: float(progress) / (t + 1)
        if not final:
            return lambda obs, progress, t: 0.0
        return lambda obs, progress, t: progress / final / (t + 1)


class DistanceVarying(Potential):
    """φ = −scale · distance of the first unmet entity to its place in the next subgoal."""

    def __init__(self, scale: float = 1.0, tolerance: float = 0.05):
        super().__init__(scale)
        self.tolerance = tolerance

    def potential(self, ctx: ShapingContext) -> float:
        geometry = ctx.require_geometry(self.name)
        targets = geometry.locate(ctx.subgoals[ctx.next_index])
        positions = geometry.positions(ctx.obs)
        for entity, target in targets.items():
            distance = point_distance(positions[entity], target)
            if distance > self.tolerance:
                return -distance
        return 0.0

    def specialize(self, ctx: ShapingContext) -> StepPotential | None:
        """:meth:`potential` for ``ctx``'s plan as a function of (observation, progress): each
        subgoal's targets looked up once, as plain floats."""
        geometry = ctx.require_geometry(self.name)
        final, tolerance, positions = ctx.final, self.tolerance, geometry.positions
        targets = [
            [(entity, np.asarray(target).tolist()) for entity, target in located.items()]
            for located in (geometry.locate(subgoal) for subgoal in ctx.subgoals)
        ]

        def phi(obs: Any, progress: int) -> float:
            where = positions(obs)
            for entity, target in targets[min(progress + 1, final)]:
                distance = point_distance(where[entity], target)
                if distance > tolerance:
                    return -distance
            return 0.0

        return phi
