"""SubgoalStates: a lazy tuple of full states that compares, hashes and pickles like one."""

from __future__ import annotations

import operator
import pickle

from planshape.planning import GroundAction, Plan, SubgoalStates, format_atom, parse_atom

STATIC = frozenset({("link", "a", "b"), ("link", "b", "a")})
FLUENTS = [frozenset({("at", "a")}), frozenset({("at", "b")})]
FULL = tuple(STATIC | f for f in FLUENTS)


def test_behaves_like_the_tuple_of_full_states():
    states = SubgoalStates(STATIC, FLUENTS)
    assert len(states) == 2 and list(states) == list(FULL)
    assert states[-1] == FULL[-1] and states[0:1] == FULL[0:1]
    assert states == FULL and operator.eq(FULL, states)  # both ways round
    assert hash(states) == hash(FULL)
    assert states.index(FULL[1]) == 1 and FULL[1] in states
    assert states.static == STATIC and states.fluents == tuple(FLUENTS)


def test_static_atoms_may_come_lazily_and_are_built_once():
    calls = []

    def static():
        calls.append(1)
        return STATIC

    states = SubgoalStates(static, FLUENTS)
    assert states.fluents[1] == {("at", "b")} and not calls
    assert states[1] == FULL[1] and states[0] == FULL[0] and len(calls) == 1
    assert pickle.loads(pickle.dumps(states)) == FULL


def test_from_states_splits_by_predicate_and_keeps_the_states():
    states = SubgoalStates.from_states(FULL, {"link"})
    assert states.static == STATIC and states.fluents == tuple(FLUENTS)
    assert states[0] is FULL[0]


def test_plans_with_lazy_or_tuple_subgoals_are_equal():
    action = (GroundAction("go", ("a", "b")),)
    assert Plan(action, SubgoalStates(STATIC, FLUENTS), 1, "s") == Plan(action, FULL, 1, "s")


def test_atom_text_round_trip():
    assert parse_atom(format_atom(("at", "a"))) == ("at", "a")
    assert parse_atom(" (At  A) ") == ("at", "a")
