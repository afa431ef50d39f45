"""Fast Downward runs: every named search, exit codes, time limit, missing driver, plan files."""

from __future__ import annotations

import re
import time
from pathlib import Path

import pytest

from planshape.errors import (
    PDDLError,
    PlannerError,
    PlannerMissingError,
    PlannerTimeoutError,
    UnknownIdError,
    UnsolvableError,
)
from planshape.planning import (
    DRIVER_ENV,
    OPTIMAL_SEARCHES,
    SEARCHES,
    GroundAction,
    find_driver,
    load_task,
    parse_plan,
    run_fast_downward,
    subgoal_sequence,
)
from planshape.planning.fast_downward import _exit_error
from tests.planning.conftest import DATA

TWO_ITEMS = DATA / "delivery-two-items.pddl"


@pytest.mark.parametrize("search", sorted(SEARCHES))
def test_every_search_finds_a_valid_plan(domain, search):
    result = run_fast_downward(domain, TWO_ITEMS, search=search, timeout=30)
    task = load_task(domain, TWO_ITEMS)
    states = subgoal_sequence(task, result.actions)  # raises unless the plan is valid
    assert task.goal <= states[-1]
    assert result.cost == len(result.actions)
    if search in OPTIMAL_SEARCHES:
        assert result.cost == 10  # fetch the two items one after the other


def test_unknown_search(domain, problem):
    with pytest.raises(UnknownIdError, match=r"unknown search 'astar-lmcat'; did you mean"):
        run_fast_downward(domain, problem, search="astar-lmcat")


def test_unsolvable(domain):
    with pytest.raises(UnsolvableError, match=r"delivery-unsolvable.pddl has no plan"):
        run_fast_downward(domain, DATA / "delivery-unsolvable.pddl")


def test_timeout_kills_the_planner_and_names_files_and_limit(domain, problem):
    # Starting Python alone takes longer than 1 ms, so this limit is always exceeded.
    started = time.perf_counter()
    with pytest.raises(PlannerTimeoutError) as caught:
        run_fast_downward(domain, problem, timeout=0.001)
    assert time.perf_counter() - started < 5
    message = str(caught.value)
    assert "within 0.001 s" in message
    assert "delivery-domain.pddl" in message and "delivery-problem.pddl" in message


def test_missing_driver(domain, problem, tmp_path, monkeypatch):
    monkeypatch.setenv(DRIVER_ENV, str(tmp_path / "no-fast-downward.py"))
    with pytest.raises(PlannerMissingError, match=r"no-fast-downward.py.*PLANSHAPE_FAST_DOWNWARD"):
        run_fast_downward(domain, problem)


def test_driver_is_found_without_importing_up_fast_downward():
    import sys

    assert find_driver().name == "fast-downward.py"
    assert "up_fast_downward" not in sys.modules


def test_plan_file_with_comments():
    actions, cost = parse_plan(
        "; header\n(Go A b)  ; first\n\n(pick cup b)\n; cost = 7 (general)\n"
    )
    assert actions == (GroundAction("go", ("a", "b")), GroundAction("pick", ("cup", "b")))
    assert cost == 7
    assert parse_plan("(noop)\n") == ((GroundAction("noop", ()),), None)


def test_unreadable_plan_line():
    with pytest.raises(PlannerError, match=r"sas_plan:2: cannot read plan step"):
        parse_plan("(go a b)\ngo b c\n", "sas_plan")


@pytest.mark.parametrize(
    ("code", "error", "message"),
    [
        (10, UnsolvableError, "the translator proved it unsolvable"),
        (12, UnsolvableError, "incomplete search gbfs-ff gave up"),
        (22, PlannerError, "the search ran out of memory"),
        (31, PDDLError, "translator rejected d.pddl and p.pddl: .*bad token"),
        (33, PlannerError, "rejected its configuration.*bad token"),
        (-9, PlannerError, "killed by signal 9"),
    ],
)
def test_exit_codes(code, error, message):
    err = _exit_error(code, "noise\nError: bad token\n", "gbfs-ff", "d.pddl", "p.pddl", 60)
    assert type(err) is error
    assert re.search(message, str(err)), str(err)


def test_a_planner_traceback_becomes_one_line_and_a_log_file():
    output = (
        "INFO     Running translator.\n"
        "Traceback (most recent call last):\n"
        '  File "translate.py", line 10, in <module>\n'
        "    main()\n"
        '  File "pddl_parser.py", line 99, in parse\n'
        "    raise SystemExit(1)\n"
        "translate.pddl_parser.parsing_functions.ParseError: unknown symbol :foo\n"
        "translate exit code: 31\n"
    )
    err = _exit_error(31, output, "astar-lmcut", "d.pddl", "p.pddl", 60)
    message = str(err)
    assert "ParseError: unknown symbol :foo" in message
    assert "Traceback" not in message and 'File "' not in message and "\n" not in message
    log = re.search(r"whole output: (\S+)\)", message).group(1)
    assert Path(log).read_text(encoding="utf-8") == output
