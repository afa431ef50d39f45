"""Which of many equal regions of the plane contain a point: the classifiers' per-step fast path.

Region classifiers (waypoint discs, grid cells) answer a batch of observations with numpy; for
the one observation of a shaping step a few small numpy operations cost more than the test
itself. :class:`RegionIndex` hashes the regions into square buckets as wide as a region, so a
point is tested only against the (at most four) regions that overlap its bucket.

Example:
    >>> index = RegionIndex([(0.0, 0.0), (0.1, 0.0), (0.2, 0.0)], size=0.05, square=True)
    >>> index.containing(0.12, 0.01), index.containing(0.5, 0.5)
    ([1], [])
    >>> RegionIndex([(0.0, 0.0)], size=0.05, square=True, closed=True).containing(0.05, 0.0)
    [0]
"""

from __future__ import annotations

import math
from collections.abc import Sequence


class RegionIndex:
    """Point-in-region lookup for regions of one size: squares of half side ``size`` or discs
    of radius ``size`` centred at ``centres``.

    Args:
        centres: the regions' centres, ``(x, y)`` each; results are positions in this list,
            in increasing order.
        size: half side (squares) or radius (discs), > 0.
        square: squares (the max-norm) rather than discs.
        closed: whether the boundary belongs to the region (``<=``) or not (``<``).
    """

    def __init__(
        self,
        centres: Sequence[Sequence[float]],
        size: float,
        square: bool = False,
        closed: bool = False,
    ):
        if not size > 0:
            raise ValueError(f"region size must be positive, not {size}")
        self.size = float(size)
        self.square = square
        self.closed = closed
        self._width = 2.0 * self.size
        self._buckets: dict[tuple[int, int], list[tuple[int, float, float]]] = {}
        for index, (cx, cy) in enumerate(centres):
            cx, cy = float(cx), float(cy)
            for bx in range(self._bucket(cx - self.size), self._bucket(cx + self.size) + 1):
                for by in range(self._bucket(cy - self.size), self._bucket(cy + self.size) + 1):
                    self._buckets.setdefault((bx, by), []).append((index, cx, cy))

    def _bucket(self, value: float) -> int:
        return math.floor(value / self._width)

    def containing(self, x: float, y: float) -> list[int]:
        """Positions (in ``centres``) of the regions that contain the point ``(x, y)``."""
        candidates = self._buckets.get((self._bucket(x), self._bucket(y)))
        if not candidates:
            return []
        size, closed = self.size, self.closed
        found = []
        for index, cx, cy in candidates:
            if self.square:
                gap = max(abs(x - cx), abs(y - cy))
                inside = gap <= size if closed else gap < size
            else:
                gap = (x - cx) ** 2 + (y - cy) ** 2
                inside = gap <= size * size if closed else gap < size * size
            if inside:
                found.append(index)
        return found
