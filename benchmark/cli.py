"""The ``planshape`` command.

Each subcommand is one function decorated with :func:`subcommand`: it receives its own
``argparse`` parser to fill and returns the function that runs it; the modules that define them
are listed in :data:`planshape.commands.MODULES`. :func:`main` maps errors to
exit statuses, the same for every subcommand:

* 0: success;
* 1: a negative verdict (e.g. the problem has no plan);
* 2: bad input (a malformed or missing file, an unknown id, no planner installed);
* 3: the tool failed for another reason (planner timeout or crash, an invalid plan).

Errors are printed as one line on stderr, without a traceback.

Example:
    >>> main(["plan", "domain.pddl", "problem.pddl", "--json"])  # doctest: +SKIP
    0
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import sys
from collections.abc import Callable, Sequence
from typing import Any

from planshape.commands import Handler, Setup, registered
from planshape.commands import subcommand as _subcommand
from planshape.errors import BadInputError, PlanshapeError, UnsolvableError

__all__ = ["Handler", "build_parser", "main", "subcommand"]


def subcommand(name: str, help: str) -> Callable[[Setup], Setup]:
    """Register ``planshape NAME`` (:func:`planshape.commands.subcommand`).

    Example:
        >>> @subcommand("hello", "say hello")
        ... def _hello(parser):
        ...     parser.add_argument("--name", default="world")
        ...     return lambda args: print(f"hello {args.name}") or 0
        >>> main(["hello", "--name", "planner"])
        hello planner
        0
        >>> from planshape.commands import _SUBCOMMANDS
        >>> del _SUBCOMMANDS["hello"]
    """
    return _subcommand(name, help)


def build_parser() -> argparse.ArgumentParser:
    """The ``planshape`` argument parser with every registered subcommand."""
    parser = argparse.ArgumentParser(
        prog="planshape",
        description="Benchmark suite for reward densification with classical planning.",
    )
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, (help_text, setup) in registered().items():
        sub = commands.add_parser(name, help=help_text, description=help_text)
        sub.set_defaults(handler=setup(sub))
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run ``planshape`` with ``argv`` (default: ``sys.argv[1:]``); return the exit status."""
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exit_:  # argparse reports usage errors itself, with status 2
        return exit_.code if isinstance(exit_.code, int) else 2
    if getattr(args, "handler", None) is None:
        parser.print_help(sys.stderr)
        return 2
    try:
        return args.handler(args)
    except KeyboardInterrupt:  # Ctrl-C: the shell's status for it, no traceback
        print(f"planshape {args.command}: interrupted", file=sys.stderr)
        return 128 + signal.SIGINT
    except BrokenPipeError:  # e.g. `planshape plan ... | head`: stop quietly
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 1
    except BadInputError as err:
        return _fail(args.command, err, 2)
    except UnsolvableError as err:
        return _fail(args.command, err, 1)
    except PlanshapeError as err:
        return _fail(args.command, err, 3)


def _fail(command: str, err: Exception, status: int) -> int:
    message = " ".join(str(err).split())
    print(f"planshape {command}: error: {message}", file=sys.stderr)
    return status


def _print_json(data: Any) -> None:
    json.dump(data, sys.stdout)
    sys.stdout.write("\n")


# --------------------------------------------------------------------------- planshape plan


@subcommand("plan", "plan a PDDL problem with Fast Downward and print its subgoal states")
def _plan_command(parser: argparse.ArgumentParser) -> Handler:
    from planshape.planning.fast_downward import DEFAULT_SEARCH, SEARCHES

    parser.add_argument("domain", help="the PDDL domain file")
    parser.add_argument("problem", help="the PDDL problem file")
    parser.add_argument(
        "--search",
        default=DEFAULT_SEARCH,
        metavar="NAME",
        help=f"search configuration: {', '.join(SEARCHES)} (default: %(default)s)",
    )
    parser.add_argument(
        "--timeout", type=float, default=60.0, metavar="S", help="time limit in seconds"
    )
    parser.add_argument("--no-cache", action="store_true", help="plan again, ignore the cache")
    parser.add_argument("--json", action="store_true", help="print the plan as JSON")
    return _run_plan


def _run_plan(args: argparse.Namespace) -> int:
    from planshape.planning import format_atom, solve

    if args.timeout <= 0:
        raise BadInputError(f"--timeout must be positive, not {args.timeout:g}")
    try:
        plan = solve(
            args.domain,
            args.problem,
            search=args.search,
            timeout=args.timeout,
            cache_dir=False if args.no_cache else None,
        )
    except UnsolvableError as err:
        if args.json:
            _print_json({"solvable": False, "search": args.search, "message": str(err)})
        raise
    if args.json:
        _print_json(
            {
                "solvable": True,
                "actions": [str(a) for a in plan.actions],
                "subgoals": [sorted(map(format_atom, state)) for state in plan.subgoals],
                "cost": plan.cost,
                "search": plan.search,
                "from_cache": plan.from_cache,
                "planner_seconds": round(plan.planner_seconds, 4),
            }
        )
        return 0
    source = "from the cache" if plan.from_cache else f"planned in {plan.planner_seconds:.2f} s"
    print(f"plan: {plan.length} action(s), cost {plan.cost}, search {plan.search}, {source}")
    static, fluents = _split(plan.subgoals)
    if static:
        names = sorted({atom[0] for atom in static})
        print(f"static atoms (in every state, not shown): {len(static)} of {', '.join(names)}")
    print(f"  s0: {_atoms(fluents[0])}")
    for step, (action, state) in enumerate(zip(plan.actions, fluents[1:], strict=True), start=1):
        print(f"{step:3d}. {action}")
        print(f"  s{step}: {_atoms(state)}")
    return 0


def _split(subgoals: Sequence[frozenset]) -> tuple[frozenset, list[frozenset]]:
    from planshape.planning import SubgoalStates

    if isinstance(subgoals, SubgoalStates):
        return subgoals.static, list(subgoals.fluents)
    return frozenset(), list(subgoals)


def _atoms(state: frozenset) -> str:
    from planshape.planning import format_atom

    return " ".join(sorted(map(format_atom, state))) or "(no atoms)"


if __name__ == "__main__":  # python -m planshape.cli
    sys.exit(main())
