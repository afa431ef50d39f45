"""Which regions of the plane contain a point, for the region classifiers.

* :class:`RegionIndex`: discs or squares (of one size or several) that may overlap or
  leave gaps. Region classifiers answer a batch of observations with numpy; for the one
  observation of a shaping step a few small numpy operations cost more than the test itself, so
  the index hashes the regions into square buckets as wide as the largest region and tests a
  point only against the few regions that overlap its bucket.
* :class:`MembershipCells`: which of a :class:`RegionIndex`'s regions contain a point,
  remembered per cell of a fine square lattice wherever it is the same at every point of the
  cell (tested exactly near the regions' rims): a *key* for the region classifiers, so that
  the shaping step looks an answer up as it does on a grid model.
* :class:`Lattice`: the cells of a square grid that tiles the plane. A point is in exactly one
  cell, found by rounding, on the batch path and the one-point path alike. Squares tested one by
  one would leave points on a shared edge in no cell or, where rounding puts two centres a hair
  closer than the pitch, in two.

Example:
    >>> index = RegionIndex([(0.0, 0.0), (0.1, 0.0), (0.2, 0.0)], size=0.05, square=True)
    >>> index.containing(0.12, 0.01), index.containing(0.5, 0.5)
    ([1], [])
    >>> grid = Lattice([(0.0, 0.0), (0.1, 0.0)], pitch=0.1)
    >>> grid.containing(0.06, 0.0), grid.contains(np.array([0.06, 0.0]), grid.centres).tolist()
    ([1], [False, True])
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np


class RegionIndex:
    """Point-in-region lookup for squares of half side ``size`` or discs of radius ``size``
    centred at ``centres``; ``size`` and ``square`` are one value for every region or one per
    region (the waypoint discs and the smaller discs behind the box in one index).

    Args:
        centres: the regions' centres, ``(x, y)`` each; results are positions in this list,
            in increasing order.
        size: half side (squares) or radius (discs), > 0: a number, or one per region.
        square: squares (the max-norm) rather than discs, for all regions or per region.
            Boundaries are outside (``<``).

    Example:
        >>> mixed = RegionIndex([(0.0, 0.0), (0.1, 0.0)], size=[0.06, 0.05], square=[False, True])
        >>> mixed.containing(0.05, 0.0), mixed.containing(0.055, 0.0)  # a boundary is outside
        ([0], [0, 1])
    """

    def __init__(
        self,
        centres: Sequence[Sequence[float]],
        size: float | Sequence[float],
        square: bool | Sequence[bool] = False,
    ):
        centres = [(float(cx), float(cy)) for cx, cy in centres]
        per_region = isinstance(size, Sequence)
        sizes = [float(v) for v in size] if per_region else [float(size)] * len(centres)
        squares = list(square) if isinstance(square, Sequence) else [square] * len(centres)
        if len(sizes) != len(centres) or len(squares) != len(centres):
            raise ValueError("give one size and one shape per region, or one for all")
        for value in sizes if per_region else [float(size)]:
            if not value > 0:
                raise ValueError(f"region size must be positive, not {value}")
        #: per region: centre x, centre y, half side or radius, square
        self.regions = [
            (cx, cy, r, bool(sq)) for (cx, cy), r, sq in zip(centres, sizes, squares, strict=True)
        ]
        self._width = 2.0 * max(sizes, default=1.0)
        # per bucket, the regions overlapping it: (position, centre, half side or squared
        # radius, square)
        self._buckets: dict[tuple[int, int], list[tuple[int, float, float, float, bool]]] = {}
        for index, ((cx, cy), r, sq) in enumerate(zip(centres, sizes, squares, strict=True)):
            limit = r if sq else r * r
            for bx in range(self._bucket(cx - r), self._bucket(cx + r) + 1):
                for by in range(self._bucket(cy - r), self._bucket(cy + r) + 1):
                    self._buckets.setdefault((bx, by), []).append((index, cx, cy, limit, sq))

    @classmethod
    def union(cls, indexes: Sequence[RegionIndex]) -> RegionIndex:
        """One index over the regions of ``indexes``, in their order.

        Example:
            >>> near, far = RegionIndex([(0.0, 0.0)], 0.1), RegionIndex([(1.0, 0.0)], 0.2)
            >>> both = RegionIndex.union([near, far])
            >>> both.containing(0.95, 0.0), both.regions[1]
            ([1], (1.0, 0.0, 0.2, False))
        """
        regions = [region for index in indexes for region in index.regions]
        return cls(
            [(cx, cy) for cx, cy, _, _ in regions],
            [size for _, _, size, _ in regions],
            [square for _, _, _, square in regions],
        )

    def _bucket(self, value: float) -> int:
        return math.floor(value / self._width)

    def containing(self, x: float, y: float) -> list[int]:
        """Positions (in ``centres``) of the regions that contain the point ``(x, y)``."""
        candidates = self._buckets.get((self._bucket(x), self._bucket(y)))
        if not candidates:
            return []
        found = []
        for index, cx, cy, limit, square in candidates:
            if square:
                inside = max(abs(x - cx), abs(y - cy)) < limit
            else:
                inside = (x - cx) ** 2 + (y - cy) ** 2 < limit
            if inside:
                found.append(index)
        return found


#: a cell of :class:`MembershipCells` not classified yet (None marks a cell on a rim)
_UNSEEN = object()


class MembershipCells:
    """:meth:`RegionIndex.containing` as a tuple, remembered per cell of a square lattice of
    side ``cell`` for the cells that no region's boundary crosses.

    A cell that every region either contains whole or misses whole (with a relative margin of
    1e-9 on the squared radius or the half side, far above rounding) has one answer at all its
    points: it is computed once, at the cell's first visit, and looked up after. A cell that a
    boundary crosses is answered by the index, point by point. So the answer is always the
    index's, and for the region classifiers it is a key (the same key, the same regions, the
    same atoms hold) that costs two divisions and a dictionary lookup.

    Example:
        >>> index = RegionIndex([(0.0, 0.0), (0.1, 0.0)], size=0.05)
        >>> cells = MembershipCells(index, cell=0.01)
        >>> cells.containing(0.0, 0.0), cells.containing(0.049, 0.0), cells.containing(0.3, 0.3)
        ((0,), (0,), ())
    """

    def __init__(self, index: RegionIndex, cell: float):
        if not cell > 0:
            raise ValueError(f"cell side must be positive, not {cell}")
        self._index = index
        self._cell = float(cell)
        self._answers: dict[tuple[int, int], tuple[int, ...] | None] = {}

    def containing(self, x: float, y: float) -> tuple[int, ...]:
        """Positions of the regions that contain ``(x, y)``, in increasing order."""
        cell = self._cell
        key = (math.floor(x / cell), math.floor(y / cell))  # NaN raises, as the index does
        answer = self._answers.get(key, _UNSEEN)
        if answer is _UNSEEN:
            if len(self._answers) >= 1 << 16:
                self._answers.clear()
            answer = self._answers[key] = self._uniform(key)
        if answer is None:  # a region's boundary crosses the cell
            return tuple(self._index.containing(x, y))
        return answer  # type: ignore[return-value]

    def _uniform(self, key: tuple[int, int]) -> tuple[int, ...] | None:
        """The regions containing the whole cell ``key`` when no region's boundary crosses it
        (else None). The cell is widened by a millionth of its side: a point whose division
        rounds into the next cell lies within that of it."""
        slack = self._cell * 1e-6
        x0, y0 = key[0] * self._cell - slack, key[1] * self._cell - slack
        x1, y1 = (key[0] + 1) * self._cell + slack, (key[1] + 1) * self._cell + slack
        inside = []
        for position, (cx, cy, r, square) in enumerate(self._index.regions):
            # the cell's nearest and farthest offsets from the centre, per axis
            near_x, near_y = max(x0 - cx, 0.0, cx - x1), max(y0 - cy, 0.0, cy - y1)
            far_x, far_y = max(abs(x0 - cx), abs(x1 - cx)), max(abs(y0 - cy), abs(y1 - cy))
            if square:
                whole, none = (
                    max(far_x, far_y) < r * (1 - 1e-9),
                    max(near_x, near_y) > r * (1 + 1e-9),
                )
            else:
                limit = r * r
                whole = far_x * far_x + far_y * far_y < limit * (1 - 1e-9)
                none = near_x * near_x + near_y * near_y > limit * (1 + 1e-9)
            if whole:
                inside.append(position)
            elif not none:
                return None
        return tuple(inside)


class Lattice:
    """The cells of a square grid of side ``pitch`` centred at ``centres``, which must lie on
    one lattice (their offsets from the first are whole multiples of ``pitch``, up to rounding).

    A point belongs to the cell whose lattice index ``round((p − origin) / pitch)`` equals the
    centre's; both paths compute it in float64 with round-half-even, so they always agree.
    """

    def __init__(self, centres: Sequence[Sequence[float]], pitch: float):
        if not pitch > 0:
            raise ValueError(f"lattice pitch must be positive, not {pitch}")
        self.centres = np.asarray(centres, dtype=np.float64).reshape(-1, 2)
        self.pitch = float(pitch)
        self.origin = self.centres[0].copy() if len(self.centres) else np.zeros(2)
        self._ox, self._oy = self.origin.tolist()
        self._cells = {self.cell(x, y): i for i, (x, y) in enumerate(self.centres.tolist())}

    def cell(self, x: float, y: float) -> tuple[int, int]:
        """The lattice index of the cell that contains ``(x, y)`` (inside the grid or not)."""
        return round((x - self._ox) / self.pitch), round((y - self._oy) / self.pitch)

    def containing(self, x: float, y: float) -> list[int]:
        """Positions (in ``centres``) of the cell that contains ``(x, y)``: one, or none
        outside the grid."""
        hit = self._cells.get(self.cell(x, y))
        return [] if hit is None else [hit]

    def contains(self, points: np.ndarray, centres: np.ndarray) -> np.ndarray:
        """``points`` (..., 2) against the cells centred at ``centres`` (k, 2), which lie on this
        lattice: shape (..., k)."""
        # float64 first: float32 observations would round differently from the one-point path
        where = np.rint((np.asarray(points, np.float64) - self.origin) / self.pitch)
        cells = np.rint((np.asarray(centres, np.float64) - self.origin) / self.pitch)
        return (where[..., None, :] == cells).all(axis=-1)
