"""Helpers the reference potentials share: a per-plan cache and a fast point distance.

They are not part of the potential API (:mod:`planshape.shaping.potentials`); a submitted
potential may use them as any baseline does.

Example:
    >>> point_distance([0.0, 0.0], [3.0, 4.0])
    5.0
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, Generic, TypeVar

import numpy as np

__all__ = ["IdentityCache", "point_distance"]

_Value = TypeVar("_Value")


class IdentityCache(Generic[_Value]):
    """Values computed once per object, compared by identity: for potentials that precompute
    something per plan (``ctx.subgoals``) or per bound model. Each key is kept alive, so its id
    is never reused while cached, and the cache pickles empty (ids belong to one process).

    Example:
        >>> cache = IdentityCache()
        >>> plan = [("a",), ("b",)]
        >>> cache.get(plan, lambda: len(plan)), cache.get(plan, lambda: -1)
        (2, 2)
    """

    def __init__(self) -> None:
        self._items: dict[int, tuple[Any, _Value]] = {}

    def get(self, key: Any, build: Callable[[], _Value]) -> _Value:
        hit = self._items.get(id(key))
        if hit is None or hit[0] is not key:
            value = build()
            self._items[id(key)] = (key, value)
            return value
        return hit[1]

    def __getstate__(self) -> dict[str, Any]:
        return {"_items": {}}


def point_distance(a: Any, b: Any) -> float:
    """Euclidean distance between two points given as arrays or sequences of floats.

    For potentials that measure with the ``Geometry`` hooks: ``math.dist`` on plain floats is
    several times faster than on numpy arrays, and φ runs on every environment step.

    Example:
        >>> point_distance(np.array([0.0, 3.0]), (4.0, 0.0))
        5.0
    """
    if isinstance(a, np.ndarray):
        a = a.tolist()
    if isinstance(b, np.ndarray):
        b = b.tolist()
    return math.dist(a, b)
