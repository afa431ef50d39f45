"""The spatial index behind the region classifiers' one-observation path."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planshape.tasks.regions import RegionIndex

#: multiples of 1/16 and power-of-two sizes, so that points exactly on a boundary are exact
coordinate = st.integers(-16, 16).map(lambda k: k / 16)


def brute_force(centres, size, square, x, y):
    found = []
    for i, (cx, cy) in enumerate(centres):
        if square:
            gap, bound = max(abs(x - cx), abs(y - cy)), size
        else:
            gap, bound = (x - cx) ** 2 + (y - cy) ** 2, size * size
        if gap < bound:
            found.append(i)
    return found


@settings(max_examples=300, deadline=None)
@given(
    centres=st.lists(st.tuples(coordinate, coordinate), min_size=1, max_size=12),
    size=st.sampled_from([1 / 16, 1 / 8, 1 / 4]),
    square=st.booleans(),
    pick=st.integers(0, 11),
    offset=st.tuples(
        st.sampled_from([-1.0, -0.5, 0.0, 0.5, 1.0]), st.sampled_from([-1.5, -1.0, 0.0, 0.25, 1.0])
    ),
)
def test_index_finds_exactly_the_regions_that_contain_the_point(
    centres, size, square, pick, offset
):
    """Points are placed on, inside and just outside region boundaries (offsets of ±size)."""
    cx, cy = centres[pick % len(centres)]
    x, y = cx + offset[0] * size, cy + offset[1] * size
    index = RegionIndex(centres, size, square=square)
    assert index.containing(x, y) == brute_force(centres, size, square, x, y)


def test_a_grid_of_cells_gives_one_cell_per_interior_point():
    centres = [(0.05 * i, 0.05 * j) for i in range(10) for j in range(10)]
    index = RegionIndex(centres, 0.025, square=True)
    rng = np.random.default_rng(0)
    for x, y in rng.uniform(0.0, 0.45, (200, 2)):
        assert index.containing(x, y) == brute_force(centres, 0.025, True, x, y)


def test_size_must_be_positive():
    with pytest.raises(ValueError, match="positive"):
        RegionIndex([(0.0, 0.0)], 0.0)
