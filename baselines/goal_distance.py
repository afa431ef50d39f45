"""Goal-distance potential: the hand-crafted dense reward's distance, used as a potential.

A control entry, not a planning-derived one: it reads only the positions and the goal, never the
plan's intermediate subgoals. With the entities in the ``locate`` hook's order e1, …, em (the end
effector, then the box) and g the place of the last one in the plan's final subgoal Ŝ[n],

    φ = −(|e1 − e2| + … + |e(m−1) − em| + |em − g|) / d0,

where d0 is the same chain measured at the places of Ŝ[0] (1 m if that is 0 or Ŝ[0] does not
place every entity), so φ ≈ −1 at the start and 0 at the goal. Each entity has to reach the next
one (the end effector the box) and the last one its goal, so the entities must be positions in
one frame (the geometry's ``shared_frame``) when there is more than one. On the planar tasks the
numerator is exactly the distance the hand-crafted dense reward pays (reach and maze-reach:
−|ee − goal|; push: −(|ee − box| + |box − goal|)), so ``goal-distance/<model>`` is the dense
reward made potential-based: it keeps the optimal policy of the sparse task, like every
potential here, and separates two questions the leaderboard would otherwise mix, namely what the
plan adds over the hand-crafted distance, and what keeping the optimal policy costs against the
dense reward itself (which changes the task).

Example:
    >>> from planshape.potentials import ShapingContext
    >>> from planshape.invariance.toys import PointGeometry
    >>> geometry = PointGeometry({"a": (0, 0), "b": (0, 2), "c": (1, 2)})
    >>> subgoals = [frozenset({("robot_at", p)}) for p in "abc"]
    >>> ctx = ShapingContext(obs=np.array([1.0, 1.0]), progress=0, t=0, subgoals=subgoals,
    ...                      geometry=geometry)
    >>> round(GoalDistance()(ctx), 3)  # 1 m from c, which is sqrt(5) m from a
    -0.447
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping
from typing import Any

import numpy as np

from planshape.errors import PotentialError
from planshape.potentials import IdentityCache, Potential, ShapingContext, point_distance

__all__ = ["GoalDistance", "chain_distance", "chained_entities"]


def chain_distance(positions: Mapping[str, Any], goal: Any) -> float:
    """|e1 − e2| + … + |em − goal| over the entities of ``positions`` in their order.

    Example:
        >>> chain_distance({"ee": (0, 0), "box": (3, 4)}, (3, 5))
        6.0
    """
    points = [*positions.values(), goal]
    return sum(point_distance(a, b) for a, b in itertools.pairwise(points))


def chained_entities(geometry: Any, obs: Any, who: str) -> list[str]:
    """The entities of ``geometry`` in the ``locate`` hook's order, checked to be chainable:
    |e1 − e2| only means something when the entities are positions in one frame, which a
    geometry declares with ``shared_frame = True`` (the planar tasks do; MetaWorld's and
    Fetch's entities are displacements such as hand-to-puck, which do not chain).

    Example:
        >>> from planshape.invariance.toys import PointGeometry
        >>> chained_entities(PointGeometry({}), np.zeros(2), "doc")
        ['ee']
    """
    order = list(geometry.positions(obs))
    if len(order) > 1 and not getattr(geometry, "shared_frame", False):
        raise PotentialError(
            f"potential {who!r} chains the distances between the entities {order}, but "
            f"{type(geometry).__name__} does not declare them positions in one frame "
            "(shared_frame = True); pick a potential that measures each entity to its own "
            "target, such as plan-distance"
        )
    return order


class GoalDistance(Potential):
    """φ = −(chain distance from the first entity through the others to the goal) / d0."""

    def __init__(self, scale: float = 1.0):
        super().__init__(scale)
        self._goals: IdentityCache[tuple[list[float], float]] = IdentityCache()

    def _goal(self, ctx: ShapingContext, geometry: Any) -> tuple[list[float], float]:
        """The last entity's place in Ŝ[n] and d0, once per plan."""
        subgoals = ctx.subgoals
        final = geometry.locate(subgoals[-1])
        order = chained_entities(geometry, ctx.obs, self.name)
        if not order or order[-1] not in final:
            raise PotentialError(
                f"potential {self.name!r}: the plan's final subgoal places no "
                f"{order[-1] if order else 'entity'!r}, so there is no goal to measure to; "
                "use it with a model whose goal places the last entity of the locate hook"
            )
        goal = np.asarray(final[order[-1]], float).tolist()
        start = geometry.locate(subgoals[0])
        if all(e in start for e in order):
            d0 = chain_distance({e: start[e] for e in order}, goal)
        else:
            d0 = 0.0
        return goal, d0 if d0 > 0 else 1.0

    def potential(self, ctx: ShapingContext) -> float:
        geometry = ctx.require_geometry(self.name)
        goal, d0 = self._goals.get(ctx.subgoals, lambda: self._goal(ctx, geometry))
        return -chain_distance(geometry.positions(ctx.obs), goal) / d0
