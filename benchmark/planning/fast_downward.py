"""Run Fast Downward on a PDDL domain and problem and read back its plan.

The planner is the compiled Fast Downward shipped in the ``up-fast-downward`` wheel; only its
driver script is used (the wheel's Python package needs unified-planning and is never imported).
Set ``PLANSHAPE_FAST_DOWNWARD`` to another ``fast-downward.py`` to use a different build.

Each run happens in a fresh temporary directory, in its own process group, under a wall-clock
limit; Fast Downward's exit code becomes a planshape error (see :func:`run_fast_downward`).

Example:
    >>> sorted(SEARCHES)
    ['astar-blind', 'astar-hmax', 'astar-lmcut', 'gbfs-ff', 'lama-first']
    >>> parse_plan("(move a b)\\n(move b c) ; done\\n; cost = 2 (unit cost)\\n")
    ((GroundAction(name='move', args=('a', 'b')), GroundAction(name='move', args=('b', 'c'))), 2)
"""

from __future__ import annotations

import contextlib
import importlib.util
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from planshape.errors import (
    PDDLError,
    PlannerError,
    PlannerMissingError,
    PlannerTimeoutError,
    UnknownIdError,
    UnsolvableError,
)
from planshape.planning.model import GroundAction

__all__ = [
    "DEFAULT_SEARCH",
    "DRIVER_ENV",
    "OPTIMAL_SEARCHES",
    "SEARCHES",
    "PlannerResult",
    "find_driver",
    "parse_plan",
    "plan_text",
    "run_fast_downward",
    "search_arguments",
]

#: Environment variable that overrides the path of Fast Downward's ``fast-downward.py``.
DRIVER_ENV = "PLANSHAPE_FAST_DOWNWARD"

#: Named search configurations: Fast Downward arguments. A list that starts with ``--alias`` is
#: passed before the input files (a driver option); any other list after them. Add an entry to
#: make a new name usable everywhere (``solve``, ``planshape plan --search``).
SEARCHES: dict[str, list[str]] = {
    "astar-lmcut": ["--search", "astar(lmcut())"],
    "astar-blind": ["--search", "astar(blind())"],
    "astar-hmax": ["--search", "astar(hmax())"],
    "lama-first": ["--alias", "lama-first"],
    "gbfs-ff": ["--search", "eager_greedy([ff()])"],
}
DEFAULT_SEARCH = "astar-lmcut"
#: The configurations that guarantee a cost-optimal plan.
OPTIMAL_SEARCHES = frozenset({"astar-lmcut", "astar-blind", "astar-hmax"})

_EXIT_MEANINGS = {
    1: "found a plan, then ran out of memory",
    2: "found a plan, then ran out of time",
    3: "found a plan, then ran out of memory and time",
    20: "the translator ran out of memory",
    21: "the translator ran out of time",
    22: "the search ran out of memory",
    23: "the search ran out of time",
    24: "the search ran out of memory and time",
    30: "the translator failed (critical error)",
    32: "the search failed (critical error)",
    33: "the search rejected its configuration (input error)",
    34: "the search configuration is not supported on this task",
    35: "the driver failed (critical error)",
    36: "the driver rejected its arguments (input error)",
    37: "the driver configuration is not supported",
}


@dataclass(frozen=True)
class PlannerResult:
    """What one Fast Downward run returned."""

    actions: tuple[GroundAction, ...]
    cost: int
    search: str
    seconds: float


def search_arguments(search: str) -> list[str]:
    """The Fast Downward arguments of a named search; unknown name -> :class:`UnknownIdError`.

    Example:
        >>> search_arguments("astar-blind")
        ['--search', 'astar(blind())']
    """
    try:
        return list(SEARCHES[search])
    except KeyError:
        hint = "To define another, add it to planshape.planning.SEARCHES"
        raise UnknownIdError("search", search, SEARCHES, hint=hint) from None


def find_driver() -> Path:
    """The path of ``fast-downward.py``: ``$PLANSHAPE_FAST_DOWNWARD`` or the up-fast-downward one.

    Example:
        >>> find_driver().name  # doctest: +SKIP
        'fast-downward.py'
    """
    override = os.environ.get(DRIVER_ENV)
    if override:
        driver = Path(override).expanduser()
        if not driver.is_file():
            raise PlannerMissingError(
                f"Fast Downward driver not found at {driver} (from ${DRIVER_ENV}); point "
                f"${DRIVER_ENV} at a fast-downward.py, or unset it to use up-fast-downward's"
            )
        return driver
    spec = importlib.util.find_spec("up_fast_downward")  # locates it without importing it
    for location in (spec.submodule_search_locations or []) if spec else []:
        driver = Path(location) / "downward" / "fast-downward.py"
        if driver.is_file():
            return driver
    raise PlannerMissingError(
        "Fast Downward is not installed: pip install 'up-fast-downward==1.0.0', "
        f"or set ${DRIVER_ENV} to a fast-downward.py"
    )


def run_fast_downward(
    domain: str | Path,
    problem: str | Path,
    *,
    search: str = DEFAULT_SEARCH,
    timeout: float = 60.0,
) -> PlannerResult:
    """Plan with Fast Downward on PDDL files.

    Raises :class:`UnsolvableError` when Fast Downward proves there is no plan (or an incomplete
    search gives up), :class:`PlannerTimeoutError` after ``timeout`` seconds of wall-clock time
    (the whole process group is killed), :class:`PlannerMissingError` when the driver is absent,
    :class:`PDDLError` when the translator rejects the input and :class:`PlannerError` for
    anything else, each with the end of Fast Downward's output.

    Example:
        >>> result = run_fast_downward("d.pddl", "p.pddl", search="lama-first")  # doctest: +SKIP
        >>> result.actions[0]  # doctest: +SKIP
        GroundAction(name='move', args=('cell_0_0', 'cell_0_1'))
    """
    from planshape.planning.parse import read_pddl

    return plan_text(
        read_pddl(domain),
        read_pddl(problem),
        search=search,
        timeout=timeout,
        domain_file=str(domain),
        problem_file=str(problem),
    )


def plan_text(
    domain_text: str,
    problem_text: str,
    *,
    search: str = DEFAULT_SEARCH,
    timeout: float = 60.0,
    domain_file: str = "domain.pddl",
    problem_file: str = "problem.pddl",
) -> PlannerResult:
    """:func:`run_fast_downward` on PDDL text; the file names only appear in messages."""
    arguments = search_arguments(search)
    driver = find_driver()
    before, after = (arguments, []) if arguments[:1] == ["--alias"] else ([], arguments)
    with tempfile.TemporaryDirectory(prefix="planshape-fd-") as tmp:
        work = Path(tmp)
        (work / "domain.pddl").write_text(domain_text, encoding="utf-8")
        (work / "problem.pddl").write_text(problem_text, encoding="utf-8")
        command = [
            sys.executable, str(driver), "--plan-file", "sas_plan", *before,
            "domain.pddl", "problem.pddl", *after,
        ]  # fmt: skip
        started = time.perf_counter()
        code, output = _run(command, work, timeout, f"{domain_file} and {problem_file}", search)
        seconds = time.perf_counter() - started
        where = f"{domain_file} and {problem_file} ({search})"
        if code in (0, 1, 2, 3):
            plan_file = _plan_file(work)
            if plan_file is None:
                raise PlannerError(
                    f"Fast Downward reported success on {where} but wrote no plan file; "
                    f"{_tail(output)}"
                )
            actions, cost = parse_plan(plan_file.read_text(encoding="utf-8"), str(plan_file))
            return PlannerResult(actions, len(actions) if cost is None else cost, search, seconds)
    raise _exit_error(code, output, search, domain_file, problem_file, timeout)


def _run(command: list[str], cwd: Path, timeout: float, files: str, search: str) -> tuple[int, str]:
    try:
        process = subprocess.Popen(
            command,
            cwd=cwd,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            start_new_session=True,  # its own process group, so a timeout kills the search too
        )
    except OSError as err:
        raise PlannerMissingError(f"cannot start Fast Downward ({command[1]}): {err}") from None
    try:
        output, _ = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        _kill_group(process)
        raise PlannerTimeoutError(
            f"Fast Downward ({search}) did not finish within {timeout:g} s on {files}; "
            "raise the time limit (--timeout) or choose a faster search, e.g. lama-first"
        ) from None
    except BaseException:
        _kill_group(process)
        raise
    return process.returncode, output


def _kill_group(process: subprocess.Popen[str]) -> None:
    with contextlib.suppress(ProcessLookupError):  # it may have exited meanwhile
        os.killpg(process.pid, signal.SIGKILL)
    process.communicate()


def _plan_file(work: Path) -> Path | None:
    """``sas_plan``, or the last of ``sas_plan.1``, ``sas_plan.2``... of an anytime search."""
    numbered = sorted(
        (p for p in work.glob("sas_plan.*") if p.suffix[1:].isdigit()),
        key=lambda p: int(p.suffix[1:]),
    )
    if numbered:
        return numbered[-1]
    plan = work / "sas_plan"
    return plan if plan.is_file() else None


def _exit_error(
    code: int, output: str, search: str, domain_file: str, problem_file: str, timeout: float
) -> Exception:
    where = f"{domain_file} and {problem_file}"
    tail = _tail(output)
    if code in (10, 11):
        phase = "the translator" if code == 10 else f"the search ({search})"
        return UnsolvableError(f"{problem_file} has no plan: {phase} proved it unsolvable")
    if code == 12:
        return UnsolvableError(
            f"the incomplete search {search} gave up on {problem_file} without a plan; the "
            "problem may still be solvable: try a complete search such as astar-blind"
        )
    if code == 13:
        return UnsolvableError(f"{problem_file} has no plan within the cost bound ({search})")
    if code == 31:
        return PDDLError(f"Fast Downward's translator rejected {where}: {tail}")
    meaning = _EXIT_MEANINGS.get(code, f"exit status {code}")
    if code < 0:
        meaning = f"killed by signal {-code}"
    return PlannerError(f"Fast Downward on {where} ({search}): {meaning}: {tail}")


_PLAN_LINE = re.compile(r"^\(\s*([^\s()]+)((?:\s+[^\s()]+)*)\s*\)$")
_COST = re.compile(r";\s*cost\s*=\s*(\d+)")


def parse_plan(text: str, source: str = "plan file") -> tuple[tuple[GroundAction, ...], int | None]:
    """The actions of a Fast Downward plan file and its cost (``None`` if not stated).

    Lines look like ``(move a b)``; everything after ``;`` is a comment, except that the
    ``; cost = N`` comment gives the cost.
    """
    actions = []
    cost = None
    for number, raw in enumerate(text.splitlines(), start=1):
        comment = raw.find(";")
        if comment >= 0:
            found = _COST.search(raw[comment:])
            if found:
                cost = int(found.group(1))
        line = (raw if comment < 0 else raw[:comment]).strip()
        if not line:
            continue
        match = _PLAN_LINE.match(line)
        if match is None:
            raise PlannerError(f"{source}:{number}: cannot read plan step {line!r}")
        actions.append(GroundAction(match.group(1).lower(), tuple(match.group(2).lower().split())))
    return tuple(actions), cost


def _tail(output: str) -> str:
    """One line that says why Fast Downward stopped: the exception line of a Python traceback
    in its output, else its last line; the whole output is written to a log file, named."""
    kept = [line.strip() for line in output.splitlines() if line.strip()]
    if not kept:
        return "(no output)"
    errors = [line for line in kept if re.match(r"^[A-Za-z_][\w.]*(Error|Exception)\b", line)]
    reason = errors[-1] if errors else kept[-1]
    with tempfile.NamedTemporaryFile(
        "w", prefix="planshape-fast-downward-", suffix=".log", delete=False, encoding="utf-8"
    ) as log:
        log.write(output)
    return f"{reason} (Fast Downward's whole output: {log.name})"
