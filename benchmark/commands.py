"""The registry of ``planshape`` subcommands, apart from the command line that runs them.

A subcommand is one function decorated with :func:`subcommand` in the module that owns its
job; :data:`MODULES` lists those modules explicitly, and :func:`registered` imports them when
the parser is built, so no subcommand module imports :mod:`planshape.cli` (no import loop)
and ``planshape --help`` lists them in this order.

Example:
    >>> sorted(registered())[:3]
    ['adopt', 'bench', 'check-invariance']
"""

from __future__ import annotations

import argparse
import importlib
from collections.abc import Callable

__all__ = ["MODULES", "Handler", "registered", "subcommand"]

Handler = Callable[[argparse.Namespace], int]
Setup = Callable[[argparse.ArgumentParser], Handler]

#: every module that defines subcommands, in the order ``planshape --help`` lists them
MODULES = (
    "planshape.cli",
    "planshape.harness.bench",
    "planshape.harness.adopt",
    "planshape.harness.catalog",
    "planshape.harness.probe",
    "planshape.results.frame",
    "planshape.results.evidence",
    "planshape.results.videos",
    "planshape.invariance.command",
)

#: name -> (one-line help, setup function); filled by :func:`subcommand`, in definition order.
_SUBCOMMANDS: dict[str, tuple[str, Setup]] = {}


def subcommand(name: str, help: str) -> Callable[[Setup], Setup]:
    """Register ``planshape NAME``: the decorated function adds arguments to its parser and
    returns the handler that runs it (see :func:`planshape.cli.main` for exit statuses)."""

    def register(setup: Setup) -> Setup:
        _SUBCOMMANDS[name] = (help, setup)
        return setup

    return register


def registered() -> dict[str, tuple[str, Setup]]:
    """Every subcommand of :data:`MODULES` (imported on first use)."""
    for module in MODULES:
        importlib.import_module(module)
    return _SUBCOMMANDS
