"""One exception hierarchy for everything planshape reports to a user.

Every message names the thing that is wrong (a file and line, a predicate, a task, an option)
and says what to do about it. Command-line entry points map :class:`BadInputError` to exit
status 2 and a negative verdict to exit status 1.

Example:
    >>> from planshape.errors import PlanshapeError, UnknownIdError
    >>> err = UnknownIdError("potential", "plan-base", ["plan-based", "time-varying"])
    >>> isinstance(err, PlanshapeError)
    True
    >>> print(err)
    unknown potential 'plan-base'; did you mean 'plan-based'? Known: plan-based, time-varying
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable
from pathlib import Path


class PlanshapeError(Exception):
    """Base class of every error planshape raises on purpose."""


class BadInputError(PlanshapeError):
    """The user's input (a file, an option, an id) is wrong; CLI exit status 2."""


class FileError(BadInputError):
    """Bad input found in a file; the message starts with ``file:line:`` where they are known."""

    def __init__(self, message: str, file: str | Path | None = None, line: int | None = None):
        self.file = None if file is None else Path(file)
        self.line = line
        where = ""
        if file is not None:
            where = f"{file}:{line}: " if line is not None else f"{file}: "
        super().__init__(f"{where}{message}")


class PDDLError(FileError):
    """A PDDL file is malformed or names something its domain does not declare."""


class ResultsError(FileError):
    """A stored result file or row is malformed (the message names the file and line)."""


class PlannerError(PlanshapeError):
    """Fast Downward failed for a reason other than the problem being unsolvable."""


class PlannerMissingError(PlannerError, BadInputError):
    """The Fast Downward driver could not be found or started."""


class PlannerTimeoutError(PlannerError):
    """Fast Downward did not finish within the configured time limit."""


class UnsolvableError(PlanshapeError):
    """The planner proved that the problem has no plan (a negative verdict, exit status 1)."""


class PlanValidationError(PlanshapeError):
    """A plan does not apply from the initial state (a precondition fails) or misses the goal."""


class RegistrationError(BadInputError):
    """A task, model or potential was registered inconsistently (e.g. a predicate without a
    classifier)."""


class ClassifierError(PlanshapeError):
    """A predicate classifier raised or returned something that is not a truth value."""


class PotentialError(PlanshapeError):
    """A potential cannot be used as it is (it needs hooks the task lacks, it cannot chain
    its entities, ...)."""


class PotentialValueError(PotentialError, BadInputError):
    """A potential returned something that is not one finite number (``None``, a string, a
    vector, NaN, an infinity): the potential's code is wrong, CLI exit status 2."""


class CannotVerifyError(BadInputError):
    """The invariance checker cannot decide at this input's scale (e.g. a potential so large
    that ties are below the solvers' precision): exit status 2, with what to change."""


class GammaMismatchError(BadInputError):
    """The shaping discount and the learner's discount differ (correctness rule 1)."""


class UnknownIdError(BadInputError, KeyError):
    """An id (task, potential, model, reward variant, search, ...) is not registered."""

    def __init__(self, kind: str, name: str, known: Iterable[str], hint: str = ""):
        self.kind, self.name = kind, name
        self.known = sorted(known)
        close = difflib.get_close_matches(name, self.known, n=1)
        suggestion = f"; did you mean {close[0]!r}?" if close else ";"
        message = f"unknown {kind} {name!r}{suggestion} Known: {', '.join(self.known)}"
        if hint:
            message += f". {hint}"
        super().__init__(message)

    def __str__(self) -> str:  # KeyError would quote the message
        return str(self.args[0])
