"""The spatial index behind the region classifiers' one-observation path."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planshape.tasks.regions import MembershipCells, RegionIndex

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


@settings(max_examples=200, deadline=None)
@given(
    centres=st.lists(st.tuples(coordinate, coordinate), min_size=1, max_size=8),
    sizes=st.lists(st.sampled_from([1 / 16, 1 / 8, 1 / 4, 0.3]), min_size=8, max_size=8),
    squares=st.lists(st.booleans(), min_size=8, max_size=8),
    cell=st.sampled_from([1 / 64, 0.01, 0.037]),
    seed=st.integers(0, 2**16),
)
def test_membership_cells_answer_as_the_index_on_both_sides_of_every_rim(
    centres, sizes, squares, cell, seed
):
    """Points just inside and just outside each region's rim (and on it), in a random order,
    so that a cell a rim crosses is often first seen from one side and then asked about a
    point on the other: remembering that cell's answer would be caught."""
    n = len(centres)
    index = RegionIndex(centres, sizes[:n], square=squares[:n])
    cells = MembershipCells(index, cell)
    rng = np.random.default_rng(seed)
    points = []
    for (cx, cy), r in zip(centres, sizes, strict=False):
        angles = rng.uniform(0, 2 * np.pi, 40)
        for scale in (1 - 1e-3, 1.0, 1 + 1e-3, 1 - 0.5 * cell / r, 1 + 0.5 * cell / r):
            points += np.column_stack(
                [cx + scale * r * np.cos(angles), cy + scale * r * np.sin(angles)]
            ).tolist()
            points += [[cx + scale * r, cy], [cx, cy - scale * r], [cx + scale * r, cy + r]]
    rng.shuffle(points)
    for x, y in points:
        assert cells.containing(x, y) == tuple(index.containing(x, y)), (x, y)


def test_membership_cells_remember_only_cells_no_rim_crosses():
    index = RegionIndex([(0.0, 0.0)], 0.1)
    cells = MembershipCells(index, 0.01)
    assert cells.containing(0.0, 0.0) == (0,) and cells.containing(0.5, 0.5) == ()
    assert cells.containing(0.0999, 0.0) == (0,) and cells.containing(0.1001, 0.0) == ()
    remembered = cells._answers
    assert remembered[(0, 0)] == (0,) and remembered[(50, 50)] == ()
    assert remembered[(9, 0)] is None and remembered[(10, 0)] is None  # the rim crosses them
    with pytest.raises(ValueError):  # as RegionIndex and Lattice: no region for NaN
        cells.containing(float("nan"), 0.0)
