"""subgoal_sequence: states computed by hand, and one error per way a plan can be wrong."""

from __future__ import annotations

import pytest

from planshape.errors import PlanValidationError
from planshape.planning import GroundAction, apply_action, load_task, subgoal_sequence

PLAN = ["(go depot kitchen)", "(pick cup kitchen)", "(go kitchen depot)", "(unload cup depot)"]


@pytest.fixture
def task(domain, problem):
    return load_task(domain, problem)


def test_states_match_a_hand_computation(task):
    static = task.static_atoms()
    states = subgoal_sequence(task, PLAN)
    assert [s - static for s in states] == [
        {("at", "depot"), ("item-at", "cup", "kitchen")},
        {("at", "kitchen"), ("item-at", "cup", "kitchen")},
        {("at", "kitchen"), ("carrying", "cup"), ("hands-full",)},
        {("at", "depot"), ("carrying", "cup"), ("hands-full",)},
        {("at", "depot"), ("delivered", "cup")},
    ]
    assert all(static <= s for s in states)  # static atoms are part of every state
    assert states[0] == task.init


def test_ground_actions_and_text_are_the_same(task):
    ground = [GroundAction("go", ("depot", "kitchen"))]
    assert apply_action(task, task.init, ground[0]) == apply_action(task, task.init, PLAN[0])


def test_failed_positive_precondition_names_step_action_and_atom(task):
    with pytest.raises(PlanValidationError) as caught:
        subgoal_sequence(task, ["(go depot kitchen)", "(go kitchen lab)", "(pick cup kitchen)"])
    message = str(caught.value)
    assert "step 3 (pick cup kitchen)" in message
    assert "precondition (at kitchen) does not hold" in message


def test_failed_negative_precondition(task):
    carrying = apply_action(task, task.init | {("item-at", "cup", "depot")}, "(pick cup depot)")
    with pytest.raises(PlanValidationError, match=r"\(not \(hands-full\)\) fails"):
        apply_action(task, carrying | {("item-at", "cup", "depot")}, "(pick cup depot)")


def test_failed_equality_and_inequality(task):
    state = task.init | {
        ("at", "kitchen"),
        ("carrying", "cup"),
        ("connected", "kitchen", "kitchen"),
    }
    with pytest.raises(
        PlanValidationError, match=r"precondition \(= kitchen depot\) does not hold"
    ):
        apply_action(task, state, "(unload cup kitchen)", step=7)
    with pytest.raises(PlanValidationError, match=r"\(not \(= kitchen kitchen\)\) fails"):
        apply_action(task, state, "(go kitchen kitchen)")


def test_goal_not_reached(task):
    with pytest.raises(PlanValidationError, match=r"misses the goal atom\(s\) \(delivered cup\)"):
        subgoal_sequence(task, PLAN[:3])


@pytest.mark.parametrize(
    ("action", "message"),
    [
        ("(fly depot kitchen)", r"unknown action 'fly'; the domain defines: go, pick, unload"),
        ("(go depot)", r"'go' takes 2 argument\(s\), 1 given"),
        ("(go depot garage)", r"unknown object 'garage'"),
        ("(go depot cup)", r"'cup' has type item, but parameter \?to of 'go' expects type place"),
    ],
)
def test_malformed_steps(task, action, message):
    with pytest.raises(PlanValidationError, match=rf"step 1 .*{message}"):
        subgoal_sequence(task, [action])
