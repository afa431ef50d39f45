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
    >>> from planshape.shaping.potentials import ShapingContext
    >>> from planshape.invariance.toys import PointGeometry
    >>> geometry = PointGeometry({"a": (0, 0), "b": (0, 2), "c": (1, 2)})
    >>> subgoals = [frozenset({("robot_at", p)}) for p in "abc"]
    >>> ctx = ShapingContext(obs=np.array([1.0, 1.0]), progress=0, t=0, subgoals=subgoals,
    ...                      geometry=geometry)
    >>> round(GoalDistance()(ctx), 3)  # 1 m from c, which is sqrt(5) m from a
    -0.447
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from planshape.baselines.plan_path import PlanPath, Polyline, chain_distance, chained_entities
from planshape.errors import PotentialError
from planshape.shaping.potentials import Geometry

__all__ = ["GoalDistance", "chain_distance", "chained_entities"]


class GoalDistance(PlanPath):
    """φ = −(chain distance from the first entity through the others to the goal) / d0: a
    :class:`PlanPath` whose path is the goal alone."""

    def _path(self, geometry: Geometry, subgoals: Sequence[Any], entity: str) -> Polyline:
        final = geometry.locate(subgoals[-1])
        if entity not in final:
            raise PotentialError(
                f"potential {self.name!r}: the plan's final subgoal places no {entity!r}, so "
                "there is no goal to measure to; use it with a model whose goal places the "
                "last entity of the locate hook"
            )
        return Polyline([np.asarray(final[entity], float)])

    #: only the path differs from plan-path's, so its step function is plan-path's
    specialize = PlanPath.specialize
