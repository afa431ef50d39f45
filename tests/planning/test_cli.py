"""`planshape plan`: output, --json shape, exit statuses 0/1/2/3 and one-line errors."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from planshape.cli import main
from planshape.planning import DRIVER_ENV
from tests.planning.conftest import DATA


def run(capsys, *argv):
    status = main(["plan", *map(str, argv)])
    out, err = capsys.readouterr()
    return status, out, err


def test_human_readable_plan(capsys, domain, problem):
    status, out, err = run(capsys, domain, problem)
    assert status == 0 and not err
    assert "plan: 4 action(s), cost 4, search astar-lmcut" in out
    assert "static atoms (in every state, not shown): 4 of connected" in out
    assert "  s0: (at depot) (item-at cup kitchen)" in out
    assert "  1. (go depot kitchen)" in out
    assert "  s4: (at depot) (delivered cup)" in out


def test_json_shape_and_cache(capsys, domain, problem):
    status, out, _ = run(capsys, domain, problem, "--json", "--search", "lama-first")
    assert status == 0
    data = json.loads(out)
    assert data["actions"] == [
        "(go depot kitchen)",
        "(pick cup kitchen)",
        "(go kitchen depot)",
        "(unload cup depot)",
    ]
    assert len(data["subgoals"]) == 5
    assert "(connected depot kitchen)" in data["subgoals"][0]  # full states, static atoms too
    assert "(delivered cup)" in data["subgoals"][-1]
    assert (data["cost"], data["search"], data["from_cache"]) == (4, "lama-first", False)
    _, again, _ = run(capsys, domain, problem, "--json", "--search", "lama-first")
    assert json.loads(again)["from_cache"] is True
    _, fresh, _ = run(capsys, domain, problem, "--json", "--search", "lama-first", "--no-cache")
    assert json.loads(fresh)["from_cache"] is False


def test_unsolvable_exits_1(capsys, domain):
    status, out, err = run(capsys, domain, DATA / "delivery-unsolvable.pddl", "--json")
    assert status == 1
    assert json.loads(out)["solvable"] is False
    assert err.count("\n") == 1 and "delivery-unsolvable.pddl has no plan" in err


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (
            [DATA / "malformed-domain.pddl", DATA / "delivery-problem.pddl"],
            r"malformed-domain.pddl:5: syntax error",
        ),
        ([DATA / "delivery-domain.pddl", DATA / "absent.pddl"], r"absent.pddl: cannot read"),
        (
            [DATA / "delivery-domain.pddl", DATA / "delivery-problem.pddl", "--search", "astar"],
            r"unknown search 'astar'",
        ),
        (
            [DATA / "delivery-domain.pddl", DATA / "delivery-problem.pddl", "--timeout", "0"],
            r"--timeout must be positive",
        ),
    ],
)
def test_bad_input_exits_2_with_one_line(capsys, argv, message):
    import re

    status, out, err = run(capsys, *argv)
    assert status == 2 and not out
    assert err.startswith("planshape plan: error: ") and err.count("\n") == 1
    assert re.search(message, err), err
    assert "Traceback" not in err


def test_missing_planner_exits_2(capsys, domain, problem, tmp_path, monkeypatch):
    monkeypatch.setenv(DRIVER_ENV, str(tmp_path / "nowhere" / "fast-downward.py"))
    status, _, err = run(capsys, domain, problem, "--no-cache")
    assert status == 2 and "Fast Downward driver not found" in err


def test_timeout_exits_3(capsys, domain, problem):
    status, _, err = run(capsys, domain, problem, "--no-cache", "--timeout", "0.001")
    assert status == 3 and "did not finish within 0.001 s" in err


def test_usage_errors_exit_2(capsys):
    assert main([]) == 2
    assert main(["plan"]) == 2
    assert main(["--help"]) == 0
    capsys.readouterr()


def test_python_dash_m(domain, problem):
    result = subprocess.run(
        [sys.executable, "-m", "planshape.cli", "plan", str(domain), str(problem), "--json"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stderr
    assert len(json.loads(result.stdout)["actions"]) == 4
