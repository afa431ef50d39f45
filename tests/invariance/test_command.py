"""``planshape check-invariance``: exit statuses, text and JSON output."""

from __future__ import annotations

import json
import sys

import pytest

from planshape.cli import main
from planshape.shaping.potentials import Potential, ShapingContext


class StaysAtZeroButBreaks(Potential):
    def potential(self, ctx: ShapingContext) -> float:
        raise RuntimeError("boom")


def run(capsys, *argv: str) -> tuple[int, str, str]:
    status = main(["check-invariance", *argv])
    out, err = capsys.readouterr()
    return status, out, err


def test_preserved_exits_0_with_a_table(capsys):
    status, out, _ = run(
        capsys, "--potential", "plan-based", "--mdp", "reach", "--mdp", "random-episodic"
    )
    assert status == 0
    assert out.startswith("potential plan-based: preserved on 6 of 6 checks")
    assert out.count("preserved") == 7 and "counterexample" not in out


def test_violated_exits_1_with_a_counterexample(capsys):
    status, out, _ = run(
        capsys, "--potential", "plan-based", "--mdp", "maze-reach", "--setting", "truncated"
    )
    assert status == 1
    assert "violated" in out and "counterexample on maze-reach" in out
    assert "optimal original {" in out and "Q shaped [" in out


def test_json_has_a_verdict_per_mdp(capsys):
    status, out, _ = run(
        capsys,
        "--potential",
        "planshape.baselines.paper:TimeVarying",
        "--mdp",
        "push",
        "--mdp",
        "random-continuing",
        "--json",
    )
    assert status == 0
    data = json.loads(out)
    assert data["potential"] == "planshape.baselines.paper:TimeVarying"
    assert [m["mdp"] for m in data["mdps"]] == ["push", "random-continuing"]
    check = data["mdps"][0]["checks"][0]
    assert check["preserved"] and check["time_dependent"] and check["status"] == "preserved"
    assert {"kind", "gamma", "horizon", "theory", "covered_by_theory"} <= set(check["setting"])


def test_violated_json_carries_the_counterexample(capsys):
    status, out, _ = run(
        capsys,
        "--potential",
        "time-varying",
        "--mdp",
        "random-episodic",
        "--setting",
        "truncated",
        "--json",
    )
    assert status == 1
    example = json.loads(out)["mdps"][0]["checks"][0]["counterexample"]
    assert {
        "state",
        "observation",
        "progress",
        "t",
        "original_optimal",
        "shaped_optimal",
        "q_original",
        "q_shaped",
        "regret",
        "harmful",
    } <= set(example)


def test_potential_arguments(capsys):
    status, out, _ = run(
        capsys,
        "--potential",
        "plan-based",
        "--arg",
        "scale=7.5",
        "--arg",
        "normalize=false",
        "--mdp",
        "random-episodic",
        "--json",
    )
    assert status == 0 and json.loads(out)["preserved"]


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--potential", "plan-base"], "did you mean 'plan-based'"),
        (["--potential", "no_such_module:Thing"], "cannot import module"),
        (["--potential", "planshape.baselines.paper:Nope"], "has no attribute 'Nope'"),
        (["--potential", "plan-based", "--mdp", "rech"], "unknown toy MDP 'rech'"),
        (["--potential", "plan-based", "--setting", "infinite"], "unknown setting"),
        (["--potential", "plan-based", "--arg", "scale"], "KEY=VALUE"),
        (["--potential", "plan-based", "--arg", "colour=3"], "cannot construct"),
        ([], "--potential ID|module:attr is required"),
        (
            ["--potential", f"{__name__}:StaysAtZeroButBreaks", "--mdp", "reach"],
            "raised RuntimeError at state",
        ),
    ],
)
def test_bad_input_exits_2_with_a_clear_message(capsys, argv, message):
    status, out, err = run(capsys, *argv)
    assert status == 2, (out, err)
    assert message in err and err.startswith("planshape check-invariance: error:")


def test_list(capsys):
    status, out, _ = run(capsys, "--list", "--json")
    data = json.loads(out)
    assert status == 0
    assert list(data["mdps"]) == [
        "reach",
        "reach-episodic",
        "maze-reach",
        "reach-instance",
        "push",
        "random-episodic",
        "random-continuing",
    ]
    assert "NOT covered" in data["settings"]["truncated"]


def test_controls_are_all_caught(capsys):
    status, out, _ = run(capsys, "--controls")
    assert status == 0
    assert out.count("caught:") == 6 and "6 of 6 controls caught, 3 of 3 refused" in out
    assert out.count("refused:") == 3 and "MISSED" not in out


def test_a_potential_in_the_current_folder(capsys, tmp_path, monkeypatch):
    (tmp_path / "my_fresh_potentials.py").write_text(
        "from planshape.baselines.paper import PlanBased\n\n"
        "class Doubled(PlanBased):\n"
        "    def potential(self, ctx):\n"
        "        return 2 * super().potential(ctx)\n"
    )
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(sys, "path", [p for p in sys.path if p not in ("", ".")])
    monkeypatch.delitem(sys.modules, "my_fresh_potentials", raising=False)
    status, out, _ = run(
        capsys, "--potential", "my_fresh_potentials:Doubled", "--mdp", "random-episodic"
    )
    assert status == 0 and "preserved on 3 of 3" in out
