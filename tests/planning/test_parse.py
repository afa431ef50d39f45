"""load_task: every PddlTask field, and one clear error per kind of bad input."""

from __future__ import annotations

import pytest

from planshape.errors import PDDLError
from planshape.planning import PredicateSignature, grid_pddl, load_task, parse_task
from tests.planning.conftest import DATA, line_of


def test_fields_of_a_typed_task_with_constants(domain, problem):
    task = load_task(domain, problem)
    assert (task.domain_name, task.problem_name) == ("delivery", "deliver-cup")
    assert task.types == {
        "object": None,
        "place": "object",
        "room": "place",
        "hall": "place",
        "item": "object",
    }
    # names are lower-cased (the problem writes Kitchen and DEPOT); constants are objects too
    assert task.objects == {"depot": "hall", "kitchen": "room", "lab": "room", "cup": "item"}
    assert task.predicates["item-at"] == PredicateSignature("item-at", ("item", "place"))
    assert task.predicates["hands-full"].arity == 0
    assert task.static_predicates == {"connected"}
    assert task.fluent_predicates == {"at", "item-at", "carrying", "hands-full", "delivered"}
    assert task.init == {
        ("at", "depot"),
        ("item-at", "cup", "kitchen"),
        ("connected", "depot", "kitchen"),
        ("connected", "kitchen", "depot"),
        ("connected", "kitchen", "lab"),
        ("connected", "lab", "kitchen"),
    }
    assert task.goal == {("delivered", "cup")}
    assert task.objects_of_type("place") == ("depot", "kitchen", "lab")
    assert (task.domain_file, task.problem_file) == (str(domain), str(problem))


def test_action_schemas_keep_negative_preconditions_and_equalities(domain, problem):
    actions = load_task(domain, problem).actions
    assert sorted(actions) == ["go", "pick", "unload"]
    go, pick, unload = actions["go"], actions["pick"], actions["unload"]
    assert go.parameters == (("?from", "place"), ("?to", "place"))
    assert go.not_equal == (("?from", "?to"),)
    assert pick.negative == (("hands-full",),)
    assert unload.equal == (("?p", "depot"),)
    assert set(unload.delete) == {("carrying", "?i"), ("hands-full",)}


def test_parsing_a_30x30_grid_takes_well_under_a_second():
    grid = grid_pddl(30, 30, start=(0, 0), goal=(29, 29))
    task = parse_task(grid.domain, grid.problem)
    assert len(task.objects) == 900
    assert len(task.static_atoms()) == 4 * 30 * 29


def test_malformed_file_names_file_and_line(problem):
    with pytest.raises(PDDLError) as caught:
        load_task(DATA / "malformed-domain.pddl", problem)
    assert caught.value.file == DATA / "malformed-domain.pddl"
    assert caught.value.line == 5  # where the parser meets ':action' inside ':predicates'
    assert "malformed-domain.pddl:5:" in str(caught.value)
    assert "parenthesis" in str(caught.value)


def test_unclosed_parenthesis_at_the_end(domain, variant):
    bad = variant("delivery-problem.pddl", "(delivered cup))))", "(delivered cup)))")
    with pytest.raises(PDDLError, match=r"problem ends early: a parenthesis is not closed"):
        load_task(domain, bad)


def test_empty_file(domain, tmp_path):
    (tmp_path / "empty.pddl").write_text("\n")
    with pytest.raises(PDDLError, match=r"empty.pddl: the problem file is empty"):
        load_task(domain, tmp_path / "empty.pddl")


def test_missing_file(domain, tmp_path):
    with pytest.raises(PDDLError, match=r"missing\.pddl: cannot read PDDL file"):
        load_task(domain, tmp_path / "missing.pddl")


def test_unknown_predicate_in_problem(domain, variant):
    bad = variant("delivery-problem.pddl", "(item-at cup kitchen)", "(item-in cup kitchen)")
    with pytest.raises(PDDLError) as caught:
        load_task(domain, bad)
    assert caught.value.file == bad
    assert caught.value.line == line_of(bad, "(item-in cup kitchen)")
    assert "unknown predicate 'item-in' in :init" in str(caught.value)
    assert "did you mean 'item-at'" in str(caught.value)


def test_unknown_predicate_in_goal(domain, variant):
    bad = variant("delivery-problem.pddl", "(and (delivered cup))", "(and (deliverd cup))")
    with pytest.raises(PDDLError, match=r"unknown predicate 'deliverd' in :goal") as caught:
        load_task(domain, bad)
    assert caught.value.line == line_of(bad, "(deliverd cup)")


def test_unknown_predicate_in_action(variant, problem):
    bad = variant("delivery-domain.pddl", "(item-at ?i ?p) (not", "(item-on ?i ?p) (not")
    with pytest.raises(PDDLError) as caught:
        load_task(bad, problem)
    assert caught.value.file == bad
    assert caught.value.line == line_of(bad, "(item-on ?i ?p)")
    assert "unknown predicate 'item-on' in the precondition of action 'pick'" in str(caught.value)


def test_unknown_type_in_problem(domain, variant):
    bad = variant("delivery-problem.pddl", "cup - item", "cup - thing")
    with pytest.raises(PDDLError) as caught:
        load_task(domain, bad)
    assert caught.value.file == bad
    assert caught.value.line == line_of(bad, "cup - thing")
    assert "unknown type 'thing' in object 'cup'" in str(caught.value)


def test_unknown_type_in_action(variant, problem):
    bad = variant("delivery-domain.pddl", "(?i - item ?p - place)", "(?i - item ?p - spot)")
    with pytest.raises(PDDLError) as caught:
        load_task(bad, problem)
    assert caught.value.file == bad
    assert caught.value.line == line_of(bad, "- spot")
    assert "unknown type 'spot'; declared types: hall, item, place, room" in str(caught.value)


def test_undeclared_variable_or_constant_in_action(variant, problem):
    bad = variant("delivery-domain.pddl", ":effect (and (at ?to)", ":effect (and (at ?too)")
    with pytest.raises(PDDLError, match=r"variable \?too in the effect of action 'go' is not a"):
        load_task(bad, problem)
    bad = variant("delivery-domain.pddl", "(= ?p depot)", "(= ?p store)")
    with pytest.raises(PDDLError, match=r"'store'") as caught:
        load_task(bad, problem)
    assert caught.value.line == line_of(bad, "store")


def test_unknown_object_and_wrong_type_in_init(domain, variant):
    bad = variant("delivery-problem.pddl", "(item-at cup kitchen)", "(item-at cup garage)")
    with pytest.raises(
        PDDLError, match=r"unknown object 'garage' in \(item-at cup garage\)"
    ) as caught:
        load_task(domain, bad)
    assert caught.value.line == line_of(bad, "(item-at cup garage)")
    bad = variant("delivery-problem.pddl", "(item-at cup kitchen)", "(item-at kitchen cup)")
    with pytest.raises(
        PDDLError, match=r"'kitchen' has type room, but 'item-at' expects type item"
    ):
        load_task(domain, bad)


def test_wrong_arity(domain, variant):
    bad = variant("delivery-problem.pddl", "(item-at cup kitchen)", "(item-at cup)")
    with pytest.raises(PDDLError, match=r"'item-at' takes 2 argument\(s\), 1 given in :init"):
        load_task(domain, bad)


def test_problem_for_another_domain(domain, variant):
    bad = variant("delivery-problem.pddl", "(:domain delivery)", "(:domain logistics)")
    with pytest.raises(PDDLError, match=r"for domain 'logistics'.*defines 'delivery'"):
        load_task(domain, bad)


def test_unsupported_constructs_are_named(variant, problem):
    bad = variant(
        "delivery-domain.pddl",
        ":precondition (and (at ?p) (carrying ?i) (= ?p depot))",
        ":precondition (or (at ?p) (carrying ?i))",
        ":equality)",
        ":equality :disjunctive-preconditions)",
    )
    with pytest.raises(PDDLError, match=r"unsupported construct \(or .* supports STRIPS") as caught:
        load_task(bad, problem)
    assert caught.value.line == line_of(bad, "(or (at ?p)")


def test_missing_requirement_is_reported_with_the_file(variant, problem):
    bad = variant(
        "delivery-domain.pddl",
        ":precondition (and (at ?p) (carrying ?i) (= ?p depot))",
        ":precondition (or (at ?p) (carrying ?i))",
    )
    with pytest.raises(
        PDDLError, match=r"add :disjunctive-preconditions to :requirements"
    ) as caught:
        load_task(bad, problem)
    assert caught.value.file == bad and caught.value.line == line_of(bad, "(:requirements")


def test_negative_goal_is_rejected(domain, variant):
    bad = variant("delivery-problem.pddl", "(and (delivered cup))", "(and (not (at depot)))")
    with pytest.raises(PDDLError, match=r"unsupported construct \(not \(at depot\)\) in :goal"):
        load_task(domain, bad)
