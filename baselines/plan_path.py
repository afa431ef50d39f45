"""Plan-path potential: the way still to go along the plan's path, read off the observation.

The plan moves each entity through a sequence of places; the last entity in the ``locate``
hook's order (the box in push, the end effector in reach and maze-reach) is the one the goal is
about, and its places over Ŝ[0], …, Ŝ[n] form a polyline P from its start to its goal. With
e1, …, em the entities in that order,

    φ = −(|e1 − e2| + … + |e(m−1) − em| + rest(em)) / d0,

    rest(x) = min over points q of P of  |x − q| + (the length of P after q),

so each entity has to reach the next one (the end effector the box), and the last one has to
get onto the plan's path and follow it to the goal; d0 is the same quantity at Ŝ[0]'s places
(the path's length if Ŝ[0] does not place every entity, 1 m if that is 0), so φ ≈ −1 at the
start and 0 at the goal. The entities must be positions in one frame (the geometry's
``shared_frame``) when there is more than one.

What ``rest`` measures, in fact, is the way onto P's *last segment* and along it: the
minimum is always there. Each segment's value is the distance from x to its nearest point p
plus the length of P after p; the next segment's value is at most the straight way to that
segment's start plus the length after it, which by the triangle inequality is at most the
current segment's value. So the values never grow along P, and the earlier segments tie at
best (the tests find the least value on the last segment, up to a tie's rounding, at random
points around each planar task's plan). The plan's path before its last segment does not
enter φ: with the grid models, whose last segment is one cell into the goal, plan-path is the
``goal-distance`` control to within a cell, and walls are not respected anywhere
(h-star-geodesic respects them).

Unlike ``plan-distance`` it does not read the plan progress max_idx: φ is a function of the
observation alone, continuous, with no jump when a subgoal is reached or skipped. A learner's
critic, which sees the observation but not max_idx, can represent the shaped value exactly.
With the straight segment from em's start to its goal in place of P this is ``goal-distance``,
the hand-crafted dense reward's distance; the plan contributes only P's last segment (above).

Example:
    >>> from planshape.shaping.potentials import ShapingContext
    >>> from planshape.invariance.toys import PointGeometry
    >>> geometry = PointGeometry({"a": (0, 0), "b": (0, 2), "c": (1, 2)})
    >>> subgoals = [frozenset({("robot_at", p)}) for p in "abc"]
    >>> ctx = ShapingContext(obs=np.array([0.5, 1.0]), progress=0, t=0, subgoals=subgoals,
    ...                      geometry=geometry)
    >>> PlanPath()(ctx)  # 1 m up onto the last segment, then 0.5 m along it; the path is 3 m
    -0.5
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from planshape.baselines.common import IdentityCache, point_distance
from planshape.errors import PotentialError
from planshape.shaping.potentials import Geometry, Potential, ShapingContext, StepPotential

__all__ = ["PlanPath", "Polyline", "chain_distance", "chained_entities", "entity_path"]

#: per plan: the entities in the locate hook's order, the last one's path, d0
_Prepared = tuple[list[str], "Polyline", float]


def chain_distance(positions: Mapping[str, Any], goal: Any) -> float:
    """|e1 − e2| + … + |em − goal| over the entities of ``positions`` in their order.

    Example:
        >>> chain_distance({"ee": (0, 0), "box": (3, 4)}, (3, 5))
        6.0
    """
    total = 0.0  # link by link, as the step functions sum (sum() of floats may not)
    for a, b in itertools.pairwise([*positions.values(), goal]):
        total += point_distance(a, b)
    return total


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


class Polyline:
    """A path through points, with the distance still to go from any point onto it.

    Example:
        >>> path = Polyline([(0, 0), (0, 2), (1, 2)])
        >>> path.length, path.rest((0.0, 0.0)), path.rest((0.5, 1.0)), path.rest((1.0, 3.0))
        (3.0, 3.0, 1.5, 1.0)
    """

    #: a planar point's candidate segments are remembered per square cell of this fraction of
    #: the shortest segment (see :meth:`_candidates`)
    CELL_FRACTION = 1 / 8

    def __init__(self, points: Sequence[Any]):
        self.points = np.asarray(points, float)
        if len(self.points) == 0:
            raise ValueError("a path needs at least one point")
        lengths = np.linalg.norm(np.diff(self.points, axis=0), axis=1)
        # the length of the path after each segment's end
        after = np.concatenate([np.cumsum(lengths[::-1])[::-1][1:], [0.0]])[: len(lengths)]
        self.length = float(lengths.sum())
        self._lengths, self._after = lengths, after
        # per segment, in plain floats (φ runs on every step; numpy is slow on 2-vectors):
        # start, step, squared length, length, length after its end
        self._segments = [
            (a.tolist(), (b - a).tolist(), float(n * n), float(n), float(rest))
            for a, b, n, rest in zip(self.points[:-1], self.points[1:], lengths, after, strict=True)
        ]
        # last segment first: the length after a segment only grows from there, and it bounds
        # the segment's value from below, so the search stops once it reaches the best value
        self._backwards = self._segments[::-1]
        self._first = self.points[0].tolist()
        positive = lengths[lengths > 0]
        self._cell = float(positive.min()) * self.CELL_FRACTION if positive.size else 1.0
        self._near: dict[tuple[int, int], list[tuple]] = {}

    def rest(self, x: Any) -> float:
        """min over points q of the path of |x − q| + the path's length after q."""
        if isinstance(x, np.ndarray):
            x = x.tolist()
        elif not isinstance(x, list):
            x = [float(v) for v in x]
        if not self._segments:
            return math.dist(x, self._first)
        if len(x) != 2:
            return self._rest_any(np.asarray(x, float))
        px, py = x
        cell = self._cell
        try:
            key = (math.floor(px / cell), math.floor(py / cell))
        except (ValueError, OverflowError):  # NaN or infinite: no cell, search every segment
            return _least(self._backwards, px, py)
        candidates = self._near.get(key)
        if candidates is None:
            candidates = self._candidates(key)
        return _least(candidates, px, py)

    def _candidates(self, key: tuple[int, int]) -> list[tuple]:
        """The segments that can give the least value somewhere in the square cell ``key``,
        in :attr:`_backwards`' order, remembered.

        A segment's value (its distance to x plus the way along it and after it) is
        2-Lipschitz in x: the distance to a segment is 1-Lipschitz, and so is the way left
        along it, (1 − t)·|d| with t the clamped projection. So within the cell, of
        half-diagonal r around its centre c, segment i can only be least where
        value_i(c) − 2r ≤ min_j value_j(c) + 2r; the others are left out (with 1e-9 m of
        slack for rounding). The least of the rest is the least of all, bit for bit: the
        least segments' floats are among them.
        """
        if len(self._near) >= 1 << 16:
            self._near.clear()
        cell = self._cell
        cx, cy = (key[0] + 0.5) * cell, (key[1] + 0.5) * cell
        values = [_least([segment], cx, cy) for segment in self._backwards]
        bound = min(values) + 4 * (cell * 0.70711) + 1e-9
        kept = [s for s, value in zip(self._backwards, values, strict=True) if value <= bound]
        self._near[key] = kept
        return kept

    def _rest_any(self, x: np.ndarray) -> float:
        """:meth:`rest` in any dimension, with numpy."""
        starts = self.points[:-1]
        steps = np.diff(self.points, axis=0)
        lengths, squared = self._lengths, self._lengths**2
        projected = np.einsum("ij,ij->i", x - starts, steps)
        t = np.clip(
            np.divide(projected, squared, out=np.zeros_like(squared), where=squared > 0), 0, 1
        )
        off = np.linalg.norm(x - (starts + t[:, None] * steps), axis=1)
        return float(np.min(off + (1.0 - t) * lengths + self._after))


def _least(segments: Sequence[tuple], px: float, py: float) -> float:
    """min over ``segments`` (each (start, step, squared length, length, length after it), the
    last segment of the path first, so in ascending order of the length after them) of the way
    from (px, py) onto the segment, along it and after it."""
    best = math.inf
    for (ax, ay), (dx, dy), squared, length, after in segments:
        if after >= best:  # this segment and every earlier one: value ≥ after ≥ best
            break
        ox, oy = px - ax, py - ay
        t = (ox * dx + oy * dy) / squared if squared else 0.0
        t = 0.0 if t < 0.0 else 1.0 if t > 1.0 else t
        value = math.hypot(ox - t * dx, oy - t * dy) + (1.0 - t) * length + after
        if value < best:
            best = value
    return best


def entity_path(geometry: Geometry, subgoals: Sequence[Any], entity: str) -> Polyline:
    """The places of ``entity`` over the plan's subgoals, repeated places dropped."""
    points: list[np.ndarray] = []
    for subgoal in subgoals:
        place = geometry.locate(subgoal).get(entity)
        if place is not None and (not points or not np.allclose(place, points[-1])):
            points.append(np.asarray(place, float))
    if not points:
        raise PotentialError(
            f"potential 'plan-path': no subgoal of the plan places {entity!r}, the last entity "
            "of the task's locate hook; use a model whose subgoals place it"
        )
    return Polyline(points)


class PlanPath(Potential):
    """φ = −(chain distance to the last entity + its way to go along the plan's path) / d0."""

    def __init__(self, scale: float = 1.0):
        super().__init__(scale)
        self._paths: IdentityCache[_Prepared] = IdentityCache()

    def _path(self, geometry: Geometry, subgoals: Sequence[Any], entity: str) -> Polyline:
        """The path the last entity has to follow: its places over the plan."""
        return entity_path(geometry, subgoals, entity)

    def _prepare(self, ctx: ShapingContext, geometry: Geometry) -> _Prepared:
        order = chained_entities(geometry, ctx.obs, self.name)
        path = self._path(geometry, ctx.subgoals, order[-1])
        start = geometry.locate(ctx.subgoals[0])
        if all(e in start for e in order):
            last = start[order[-1]]
            d0 = chain_distance({e: start[e] for e in order[:-1]}, last) + path.rest(last)
        else:
            d0 = path.length
        return order, path, d0 if d0 > 0 else 1.0

    def _prepared(self, ctx: ShapingContext) -> _Prepared:
        geometry = ctx.require_geometry(self.name)
        return self._paths.get(ctx.subgoals, lambda: self._prepare(ctx, geometry))

    def potential(self, ctx: ShapingContext) -> float:
        order, path, d0 = self._prepared(ctx)
        positions = ctx.require_geometry(self.name).positions(ctx.obs)
        last = positions[order[-1]]
        lead = chain_distance({e: positions[e] for e in order[:-1]}, last)
        return -(lead + path.rest(last)) / d0

    def specialize(self, ctx: ShapingContext) -> StepPotential | None:
        """:meth:`potential` for ``ctx``'s plan as a function of the observation (the same
        sums in the same order, so the same floats)."""
        order, path, d0 = self._prepared(ctx)
        positions = ctx.require_geometry(self.name).positions
        rest, last_entity = path.rest, order[-1]
        links = list(itertools.pairwise(order))

        def phi(obs: Any, progress: int) -> float:
            where = positions(obs)
            lead = 0.0  # summed as chain_distance sums, link by link
            for a, b in links:
                lead += math.dist(where[a], where[b])
            return -(lead + rest(where[last_entity])) / d0

        return phi
