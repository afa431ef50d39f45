"""Plan-distance potential: how much of the plan is left, counted in plan steps, with the step
being walked measured continuously.

The source paper's ``distance-varying`` potential pays for closing the straight-line distance
to the next subgoal only; the plan's length after it is ignored, so every subgoal resets the
potential, and the raw distance is in metres while reaching a subgoal is worth one plan step.
``plan-distance`` puts both on one scale:

    φ = −scale · (n − j + d / unit) / n,   j = min(max_idx + 1, n) the next subgoal,

where n is the plan length, n − j the plan steps left after the next subgoal, d the distance
between the first entity (in the ``locate`` hook's order: end effector, then box) that is
farther than ``tolerance`` from its place in Ŝ[j] and that place (0 when all are within), and
``unit`` the length of the plan step being walked: the distance that entity's place moves from
Ŝ[j − 1] to Ŝ[j]. On a grid model a step moves one cell, so unit = one cell (0.05 m) and
d/unit counts cells: a cell of the plan is worth one step, and because the plan goes around the
walls, it is the geodesic around them that pays, not the straight line through them. On a
waypoint model (``single``, ``multi``) unit is that segment's length, so walking any segment
is worth one step. If the measured entity does not move in that step, unit is the longest move
of any entity in it; if none moves, the mean move length over the plan (1 m if that is 0 too).

With ``measure="sum"`` (registered as ``plan-distance-sum``) d is the sum of d_e / unit_e over
every entity e of Ŝ[j] farther than ``tolerance`` from its place, not the first one's alone.
At tolerance 0 an entity is never exactly in its place, so ``plan-distance`` measures the first
entity of Ŝ[j] always: where a plan step keeps the hand in place and moves an object (MetaWorld's
stage models keep ``hand-at`` in the last subgoal while the drawer, window or button moves, and
the hand's place moves with the object), φ stays nearly flat while the object travels to its
goal. ``plan-distance-sum`` measures the object too. Where a model places one entity
(reach, maze-reach) the two are the same potential.

φ(s0) ≈ −1 at the plan's start, φ = 0 once the plan is done and every entity is in place, and
at the centre of the place of subgoal k with progress k, φ = −(n − k)/n: it rises by 1/n per
subgoal. φ depends on (observation, max_idx) only, so the optimal policy of the augmented MDP
is preserved (checked by ``planshape check-invariance --potential plan-distance``).

Example:
    >>> from planshape.shaping.potentials import ShapingContext
    >>> from planshape.invariance.toys import PointGeometry
    >>> geometry = PointGeometry({"a": (0, 0), "b": (0, 2), "c": (1, 2)})
    >>> subgoals = [frozenset({("robot_at", p)}) for p in "abc"]
    >>> ctx = ShapingContext(obs=np.array([0.0, 1.5]), progress=0, t=0, subgoals=subgoals,
    ...                      geometry=geometry)
    >>> PlanDistance()(ctx)  # next subgoal b, 0.5 of a 2 m step away, 1 step after it
    -0.625

    A last step that keeps the hand in place and moves a box: ``"first"`` measures the hand only
    (0.5 m from a place it never exactly reaches), ``"sum"`` the hand and the box (1 m from its
    goal):

    >>> from planshape.tasks.displacement import DisplacementGeometry
    >>> geometry = DisplacementGeometry(
    ...     displacements={"hand": lambda o: o[..., 0:2], "box": lambda o: o[..., 2:4]},
    ...     targets={"hand-at": ("hand", (0.0, 0.0)), "box-at": ("box", (3.0, 0.0))})
    >>> subgoals = [frozenset(), frozenset({("hand-at",)}),
    ...             frozenset({("hand-at",), ("box-at",)})]
    >>> ctx = ShapingContext(obs=np.array([0.5, 0.0, 2.0, 0.0]), progress=1, t=0,
    ...                      subgoals=subgoals, geometry=geometry)
    >>> float(PlanDistance()(ctx)), float(PlanDistance(measure="sum")(ctx))
    (-0.25, -0.75)
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from typing import Any, Literal

import numpy as np

from planshape.baselines.common import IdentityCache, point_distance
from planshape.errors import BadInputError
from planshape.shaping.potentials import Geometry, Potential, ShapingContext, StepPotential

__all__ = ["PlanDistance", "step_targets"]

#: per subgoal index j: (entity, place in Ŝ[j], unit) in the ``locate`` hook's order
StepTargets = list[list[tuple[str, list[float], float]]]


#: which entities of Ŝ[j] :class:`PlanDistance` measures
Measure = Literal["first", "sum"]


def step_targets(geometry: Geometry, subgoals: Sequence[Any]) -> StepTargets:
    """For every subgoal j, each entity's place in Ŝ[j] and the unit of the step into Ŝ[j]."""
    fluents = getattr(subgoals, "fluents", None)
    states = fluents if fluents is not None else subgoals
    places = [
        {e: np.asarray(v, float) for e, v in geometry.locate(state).items()} for state in states
    ]
    moves: list[dict[str, float]] = [{}]
    for before, after in itertools.pairwise(places):
        moves.append({e: float(np.linalg.norm(after[e] - before[e])) for e in after if e in before})
    lengths = [m for step in moves for m in step.values() if m > 0]
    fallback = float(np.mean(lengths)) if lengths else 1.0
    table: StepTargets = []
    for j, targets in enumerate(places):
        longest = max(moves[j].values(), default=0.0)
        table.append(
            [
                (
                    entity,
                    target.tolist(),
                    moves[j].get(entity, 0.0) or longest or fallback,
                )
                for entity, target in targets.items()
            ]
        )
    return table


class PlanDistance(Potential):
    """φ = −scale · (plan steps left after the next subgoal + distance to it in steps) / n.

    Args:
        scale: multiplies φ.
        tolerance: an entity within this distance (m) of its place counts as in place, and
            the next entity in the ``locate`` order is measured.
        normalize: divide by the plan length n (φ(s0) ≈ −1); ``False`` counts plan steps.
        measure: ``"first"``: d is the first entity of Ŝ[j] out of place's distance;
            ``"sum"``: the sum over every entity of Ŝ[j] out of place.
    """

    def __init__(
        self,
        scale: float = 1.0,
        tolerance: float = 0.0,
        normalize: bool = True,
        measure: Measure = "first",
    ):
        super().__init__(scale)
        if measure not in ("first", "sum"):
            raise BadInputError(f"plan-distance: measure={measure!r} is not 'first' or 'sum'")
        self.tolerance = float(tolerance)
        self.normalize = normalize
        self.measure: Measure = measure
        self._tables: IdentityCache[StepTargets] = IdentityCache()

    def _table(self, ctx: ShapingContext) -> StepTargets:
        geometry = ctx.require_geometry(self.name)
        return self._tables.get(ctx.subgoals, lambda: step_targets(geometry, ctx.subgoals))

    def steps_left(self, ctx: ShapingContext) -> float:
        """n − j + d/unit, before normalizing and scaling."""
        final = ctx.final
        if final <= 0:
            return 0.0
        j = ctx.next_index
        positions = ctx.require_geometry(self.name).positions(ctx.obs)
        return final - j + self._steps_to(self._table(ctx)[j], positions)

    def _steps_to(self, row: Sequence[tuple[str, list[float], float]], positions: Any) -> float:
        """d/unit of the entities ``row`` measures (their sum for ``measure="sum"``)."""
        steps = 0.0
        for entity, target, unit in row:
            distance = point_distance(positions[entity], target)
            if distance > self.tolerance:
                steps += distance / unit
                if self.measure == "first":
                    break
        return steps

    def potential(self, ctx: ShapingContext) -> float:
        left = self.steps_left(ctx)
        return -left / ctx.final if self.normalize and ctx.final > 0 else -left

    def specialize(self, ctx: ShapingContext) -> StepPotential | None:
        """:meth:`potential` for ``ctx``'s plan as a function of (observation, progress)."""
        final = ctx.final
        if final <= 0:
            return None
        table = self._table(ctx)
        positions = ctx.require_geometry(self.name).positions
        steps_to, normalize = self._steps_to, self.normalize

        def phi(obs: Any, progress: int) -> float:
            j = min(progress + 1, final)
            left = final - j + steps_to(table[j], positions(obs))
            return -left / final if normalize else -left

        return phi
