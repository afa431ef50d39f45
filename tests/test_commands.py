"""The CLI's subcommands come from one explicit list of modules, none of which imports the CLI
back (no import loop)."""

from __future__ import annotations

import importlib

from planshape.cli import build_parser
from planshape.commands import MODULES, registered


def test_every_listed_module_registers_and_none_imports_the_cli():
    for name in MODULES[1:]:
        source = importlib.util.find_spec(name).origin
        with open(source, encoding="utf-8") as handle:
            code = [line for line in handle if not line.lstrip().startswith(">>>")]
        assert not any(line.startswith("from planshape.cli import") for line in code), name
    names = set(registered())
    assert {"plan", "bench", "adopt", "leaderboard", "tasks", "probe", "export", "render"} <= names
    assert "check-invariance" in names
    help_text = build_parser().format_help()
    assert all(name in help_text for name in names)
