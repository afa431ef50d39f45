"""``planshape check-invariance``: run a potential on every toy MDP and print the verdicts.

Exit status: 0 when the optimal actions are preserved everywhere, 1 when they change anywhere,
2 on bad input (an unknown potential, toy or setting; a potential that fails on a toy).
With ``--controls`` it runs the negative controls instead, and exits 0 when the checker flags
every one of them (1 when one slips through).

Example:
    >>> from planshape.cli import main
    >>> main(["check-invariance", "--potential", "plan-based", "--mdp", "random-episodic",
    ...       "--setting", "discounted"])  # doctest: +ELLIPSIS
    potential plan-based: preserved on 1 of 1 checks
    ...
    0
"""

from __future__ import annotations

import argparse
import json
import sys
from typing import TYPE_CHECKING, Any

from planshape.commands import Handler, subcommand
from planshape.errors import BadInputError, UnknownIdError

if TYPE_CHECKING:
    from planshape.invariance.verdict import InvarianceReport

__all__ = ["render"]


@subcommand("check-invariance", "check exactly on toy MDPs that a potential keeps optimal actions")
def _setup(parser: argparse.ArgumentParser) -> Handler:
    parser.add_argument(
        "--potential", metavar="ID|module:attr", help="a registered potential id or module:attr"
    )
    parser.add_argument(
        "--arg",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="keyword argument of the potential (VALUE read as JSON if it parses), repeatable",
    )
    parser.add_argument(
        "--mdp", action="append", metavar="NAME", help="a toy MDP (repeatable; default: all)"
    )
    parser.add_argument(
        "--setting",
        action="append",
        metavar="NAME",
        help="discounted, finite-horizon, undiscounted, truncated, truncated-discounted "
        "(repeatable; default: the first three, which the theory covers)",
    )
    parser.add_argument("--controls", action="store_true", help="run the negative controls")
    parser.add_argument("--list", action="store_true", help="list toy MDPs and settings")
    parser.add_argument("--json", action="store_true", help="print the report as JSON")
    return _run


def _kwargs(pairs: list[str]) -> dict[str, Any]:
    kwargs: dict[str, Any] = {}
    for pair in pairs:
        key, sep, value = pair.partition("=")
        if not sep or not key:
            raise BadInputError(f"--arg {pair!r} must look like KEY=VALUE")
        try:
            kwargs[key] = json.loads(value)
        except json.JSONDecodeError:
            kwargs[key] = value
    return kwargs


def _run(args: argparse.Namespace) -> int:
    from planshape.invariance.registry import toy_description, toy_names
    from planshape.invariance.settings import PRESETS, THEORY

    if args.list:
        listing = {
            "mdps": {name: toy_description(name) for name in toy_names()},
            "settings": {name: THEORY[kind] for name, (kind, _) in PRESETS.items()},
        }
        if args.json:
            _print_json(listing)
        else:
            print("toy MDPs:")
            for name, text in listing["mdps"].items():
                print(f"  {name:<18} {text}")
            print("settings:")
            for name, text in listing["settings"].items():
                print(f"  {name:<21} {text}")
        return 0
    if args.controls:
        return _run_controls(args)
    if not args.potential:
        raise BadInputError("--potential ID|module:attr is required (or --list, --controls)")
    for name in args.setting or []:
        if name not in PRESETS:
            raise UnknownIdError("setting", name, PRESETS)
    for name in args.mdp or []:
        if name not in toy_names():
            raise UnknownIdError("toy MDP", name, toy_names(), hint="--list shows them")
    from planshape.invariance.check import check_potential

    report = check_potential(
        args.potential,
        mdps=args.mdp,
        settings=args.setting,
        potential_kwargs=_kwargs(args.arg),
    )
    if args.json:
        _print_json(report.to_dict())
    else:
        print(render(report))
    return 0 if report.preserved else 1


def _refusal(build: Any, expected: str) -> str:
    """The message with which a refused control is refused ("" if it is not)."""
    from planshape.invariance.check import check_potential

    try:
        check_potential(build(), mdps=["reach"], settings=["discounted"])
    except BadInputError as err:
        return str(err) if expected in str(err) else ""
    return ""


def _run_controls(args: argparse.Namespace) -> int:
    from planshape.invariance.controls import CONTROLS, REFUSED, run_control

    results = [(control, run_control(control)) for control in CONTROLS]
    refused = [(name, _refusal(build, expected)) for name, build, expected in REFUSED]
    caught = all(not verdict.preserved for _, verdict in results) and all(m for _, m in refused)
    if args.json:
        _print_json(
            {
                "caught": caught,
                "refused": [{"control": n, "refused": bool(m), "message": m} for n, m in refused],
                "controls": [
                    {
                        "control": c.name,
                        "mistake": c.mistake,
                        "argument": c.argument,
                        "caught": not v.preserved,
                        **v.to_dict(),
                    }
                    for c, v in results
                ],
            }
        )
    else:
        for control, verdict in results:
            flag = "caught" if not verdict.preserved else "MISSED"
            print(f"{flag}: {control.mistake} — on {control.toy}, {verdict.setting.label}")
            print(f"  why: {control.argument}")
            if verdict.counterexample is not None:
                print(f"  counterexample: {verdict.counterexample.describe()}")
            if verdict.not_a_potential:
                print(f"  counterexample: {verdict.not_a_potential}")
        for name, message in refused:
            print(f"{'refused' if message else 'MISSED'}: {name} — {message or 'accepted'}")
        print(
            f"{sum(not v.preserved for _, v in results)} of {len(results)} controls caught, "
            f"{sum(bool(m) for _, m in refused)} of {len(refused)} refused (exit 2 for a user)"
        )
    return 0 if caught else 1


def render(report: InvarianceReport) -> str:
    """The text report: one line per toy and setting, then counterexamples."""
    lines = []
    header = f"{'mdp':<18} {'setting':<34} {'verdict':<16} {'checked':>8} {'differ':>7} {'s':>6}"
    lines.append(header)
    for v in report.verdicts:
        lines.append(
            f"{v.mdp:<18} {v.setting.label:<34} {v.status:<16} {v.checked:>8} "
            f"{v.mismatches:>7} {v.seconds:>6.2f}"
        )
    for v in report.verdicts:
        if v.counterexample is not None:
            lines.append(f"counterexample on {v.mdp}, {v.setting.label}:")
            lines.append(f"  {v.counterexample.describe()}")
    lines.insert(
        0,
        f"potential {report.potential}: {report.summary()}\n"
        f"ties: actions within {report.tolerance:g}·max(1, max|Q|) of the best are tied",
    )
    return "\n".join(lines)


def _print_json(data: Any) -> None:
    json.dump(data, sys.stdout)
    sys.stdout.write("\n")
