"""The PDDL people write: what Fast Downward plans, planshape plans and replays (upper-case
keywords, the root type ``object``, action costs, requirements left out); what cannot be
replayed or is malformed is refused with exit 2, naming the construct and its line."""

from __future__ import annotations

import pytest

from planshape.cli import main
from planshape.planning import format_atom, solve

DOMAIN = """\
(define (domain blocks)
  (:requirements :strips :typing)
  (:types block)
  (:predicates (on ?x - block ?y - block) (clear ?x - block) (handempty))
  (:action stack
    :parameters (?x - block ?y - block)
    :precondition (and (clear ?x) (clear ?y) (handempty) (not (= ?x ?y)))
    :effect (and (on ?x ?y) (not (clear ?y)))))
"""
PROBLEM = """\
(define (problem two) (:domain blocks)
  (:objects a b - block)
  (:init (clear a) (clear b) (handempty))
  (:goal (on a b)))
"""
COST_DOMAIN = """\
(define (domain roads)
  (:requirements :strips :typing :action-costs)
  (:types place)
  (:predicates (at ?p - place) (road ?a - place ?b - place))
  (:functions (total-cost) - number (length ?a - place ?b - place) - number)
  (:action drive
    :parameters (?a - place ?b - place)
    :precondition (and (at ?a) (road ?a ?b))
    :effect (and (at ?b) (not (at ?a)) (increase (total-cost) (length ?a ?b)))))
"""
COST_PROBLEM = """\
(define (problem detour) (:domain roads)
  (:objects home town city - place)
  (:init (at home) (road home city) (road home town) (road town city)
         (= (length home city) 5) (= (length home town) 1) (= (length town city) 1)
         (= (total-cost) 0))
  (:goal (at city))
  (:metric minimize (total-cost)))
"""


def _plan(tmp_path, domain: str | bytes, problem: str | bytes = PROBLEM):
    files = []
    for name, text in (("domain.pddl", domain), ("problem.pddl", problem)):
        path = tmp_path / name
        path.write_bytes(text if isinstance(text, bytes) else text.encode())
        files.append(path)
    return files


def _subgoals(plan) -> list[list[str]]:
    """The fluent part of each subgoal state."""
    return [sorted(map(format_atom, state)) for state in plan.subgoals.fluents]


def test_upper_case_keywords_plan_as_lower_case_does(tmp_path):
    lower = solve(*_plan(tmp_path, DOMAIN), cache_dir=False)
    upper = solve(*_plan(tmp_path, DOMAIN.upper(), PROBLEM.upper()), cache_dir=False)
    assert _subgoals(upper) == _subgoals(lower) and upper.length == 1


def test_the_root_type_object_in_types_and_parameters(tmp_path):
    domain = DOMAIN.replace("(:types block)", "(:types block - object)").replace(
        "(clear ?x - block)", "(clear ?x - object)"
    )
    plan = solve(*_plan(tmp_path, domain), cache_dir=False)
    assert [str(a) for a in plan.actions] == ["(stack a b)"]
    assert _subgoals(plan) == [["(clear a)", "(clear b)"], ["(clear a)", "(on a b)"]]


def test_requirements_fast_downward_does_not_insist_on(tmp_path):
    # equality and negation used, neither :equality nor :negative-preconditions declared
    plan = solve(*_plan(tmp_path, DOMAIN), cache_dir=False)
    assert [str(a) for a in plan.actions] == ["(stack a b)"]


def test_action_costs_give_the_cheapest_plan_and_its_cost(tmp_path, capsys):
    domain, problem = _plan(tmp_path, COST_DOMAIN, COST_PROBLEM)
    plan = solve(domain, problem, cache_dir=False)
    assert [str(a) for a in plan.actions] == ["(drive home town)", "(drive town city)"]
    assert plan.cost == 2  # the direct road is one action of cost 5
    assert _subgoals(plan)[-1] == ["(at city)"]
    assert main(["plan", str(domain), str(problem), "--no-cache"]) == 0
    assert "cost 2" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("domain", "message"),
    [
        (
            DOMAIN.replace(":typing)", ":typing :fluents-x)"),
            "domain.pddl:2: unknown requirement ':fluents-x' (did you mean ':fluents'?)",
        ),
        (
            DOMAIN.replace("(handempty))", "(handempty)\n  (clear ?z - block))"),
            "domain.pddl:5: predicate 'clear' is declared twice (lines 4 and 5)",
        ),
        (
            DOMAIN[:-2] + "\n  (:action stack :parameters () :effect (handempty)))\n",
            "domain.pddl:9: action 'stack' is declared twice (lines 5 and 9)",
        ),
        (
            DOMAIN[:-2] + "\n  (:derived (handempty) (clear a)))\n",
            "domain.pddl:9: derived predicates (:derived) cannot be replayed into subgoals",
        ),
        ("; a comment\n\n; and another\n", "the domain file holds no PDDL, only comments"),
        (
            DOMAIN.replace("(:types block)", "(:types block - thing block - stuff thing stuff)"),
            "domain.pddl:3: type 'block' is declared twice, under thing and again",
        ),
        (
            DOMAIN.encode().replace(b"(handempty))", b"(handempty \xe9))"),
            "domain.pddl:4: not UTF-8 text: byte 0xe9",
        ),
    ],
    ids=[
        "unknown-requirement",
        "duplicate-predicate",
        "duplicate-action",
        "derived",
        "comments-only",
        "two-parents",
        "not-utf8",
    ],
)
def test_what_cannot_be_planned_or_replayed_exits_2_naming_it(tmp_path, capsys, domain, message):
    domain_file, problem_file = _plan(tmp_path, domain)
    for _ in range(2):  # the same message every time
        assert main(["plan", str(domain_file), str(problem_file), "--no-cache"]) == 2
        err = capsys.readouterr().err
        assert message in err and "Traceback" not in err, err


def test_an_arity_error_points_at_the_use_not_the_declaration(tmp_path, capsys):
    domain = DOMAIN.replace("(on ?x ?y) (not (clear ?y))", "(on ?x) (not (clear ?y))")
    domain_file, problem_file = _plan(tmp_path, domain)
    assert main(["plan", str(domain_file), str(problem_file), "--no-cache"]) == 2
    err = capsys.readouterr().err
    assert "domain.pddl:8: predicate 'on' takes 2 argument(s), 1 given" in err, err
