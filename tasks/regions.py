"""Which regions of the plane contain a point, for the region classifiers.

* :class:`RegionIndex`: regions of one size (waypoint discs or squares) that may overlap or
  leave gaps. Region classifiers answer a batch of observations with numpy; for the one
  observation of a shaping step a few small numpy operations cost more than the test itself, so
  the index hashes the regions into square buckets as wide as a region and tests a point only
  against the (at most four) regions that overlap its bucket.
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
    """Point-in-region lookup for regions of one size: squares of half side ``size`` or discs
    of radius ``size`` centred at ``centres``.

    Args:
        centres: the regions' centres, ``(x, y)`` each; results are positions in this list,
            in increasing order.
        size: half side (squares) or radius (discs), > 0.
        square: squares (the max-norm) rather than discs. Boundaries are outside (``<``).
    """

    def __init__(self, centres: Sequence[Sequence[float]], size: float, square: bool = False):
        if not size > 0:
            raise ValueError(f"region size must be positive, not {size}")
        self.size = float(size)
        self.square = square
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
        size = self.size
        found = []
        for index, cx, cy in candidates:
            if self.square:
                inside = max(abs(x - cx), abs(y - cy)) < size
            else:
                inside = (x - cx) ** 2 + (y - cy) ** 2 < size * size
            if inside:
                found.append(index)
        return found


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
