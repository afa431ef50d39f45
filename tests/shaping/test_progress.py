"""When a subgoal counts as reached and how progress (max_idx) moves."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from planshape.shaping.abstraction import Abstraction
from planshape.shaping.progress import PlanProgress
from tests.toys import at, line_progress, line_task

PLAN = [frozenset({("at", p)}) for p in ("left", "middle", "right")]


def wide_at(obs, place):
    """Overlapping places: 0.3 is both left and middle."""
    return np.abs(obs[..., 0] - {"left": 0.0, "middle": 0.5, "right": 1.0}[place]) <= 0.3


def test_fluents_match_ignores_extra_atoms_but_exact_match_does_not():
    fluents = PlanProgress(PLAN, Abstraction(line_task(), {"at": wide_at}), match="fluents")
    exact = PlanProgress(PLAN, Abstraction(line_task(), {"at": wide_at}), match="exact")
    both = np.array([0.25])  # at(left) and at(middle) both hold
    assert fluents.reached(both).tolist() == [True, True, False]
    assert exact.reached(both).tolist() == [False, False, False]
    assert exact.reached(np.array([0.5])).tolist() == [False, True, False]


def test_static_atoms_in_subgoals_are_not_classified():
    plan = [s | {("adjacent", "left", "middle")} for s in PLAN]
    tracker = PlanProgress(plan, Abstraction(line_task(), {"at": at}))
    assert tracker.furthest(np.array([0.5])) == 1


def test_progress_starts_at_furthest_reached_and_at_least_zero():
    tracker = line_progress()
    assert tracker.initial(np.array([0.3])) == 0  # nothing reached
    assert tracker.initial(np.array([1.0])) == 2
    assert tracker.furthest(np.array([0.3])) == -1


def test_progress_skips_forward_and_never_moves_back():
    tracker = line_progress()
    assert tracker.advance(0, np.array([1.0])) == 2
    assert tracker.advance(2, np.array([0.0])) == 2
    assert tracker.advance(1, np.array([0.3])) == 1


@settings(max_examples=100, deadline=None)
@given(st.lists(st.floats(-0.2, 1.2), min_size=1, max_size=40))
def test_batch_progress_equals_one_at_a_time(xs):
    tracker = line_progress()
    observations = np.array(xs)[:, None]
    progress = np.zeros(len(xs), dtype=int)
    batch = tracker.advance(progress, observations)
    single = [tracker.advance(0, o) for o in observations]
    assert batch.tolist() == single
    # Along a trajectory progress is the running maximum of the furthest subgoal reached.
    running, expected = 0, []
    for o in observations:
        running = tracker.advance(running, o)
        expected.append(running)
    assert expected == list(
        np.maximum.accumulate([max(tracker.furthest(o), 0) for o in observations])
    )


SUBGOAL_SETS = [
    frozenset(),
    frozenset({("at", "left")}),
    frozenset({("at", "left"), ("at", "middle")}),
    frozenset({("at", "right")}),
    frozenset({("at", "middle")}),
    frozenset({("at", "middle"), ("at", "right")}),
]


@settings(max_examples=200, deadline=None)
@given(
    plan=st.lists(st.sampled_from(SUBGOAL_SETS), min_size=1, max_size=8),
    x=st.floats(-0.5, 1.5),
    floor=st.integers(-1, 8),
    match=st.sampled_from(["fluents", "exact"]),
)
def test_one_observation_path_agrees_with_the_matrix_test(plan, x, floor, match):
    """A single observation goes through sets (AtomEvaluator.holding); a batch through one
    matrix product. Overlapping places, multi-atom and empty subgoals, repeated subgoals and
    any progress floor must give the same answer."""
    tracker = PlanProgress(plan, Abstraction(line_task(), {"at": wide_at}), match=match)
    obs = np.array([x])
    reached = tracker.reached(obs[None])[0]  # the matrix path (a batch of one)
    hits = np.flatnonzero(reached)
    furthest = int(hits[-1]) if hits.size else -1
    floor = min(floor, tracker.final)
    assert tracker.furthest(obs) == furthest
    assert tracker.advance(floor, obs) == max(floor, furthest)
