"""Every runnable example in a docstring of the package, run as a test.

The modules are found by walking the installed packages (the import names, not the source
folders, which are mapped: ``planshape`` is ``benchmark/``), so a new module's examples run
without being listed anywhere.
"""

from __future__ import annotations

import doctest
import importlib
import pkgutil

import pytest

import planshape
import planshape.baselines
import planshape.tasks

#: pytest's own files inside the package (the shipped suite), not modules with examples
NOT_MODULES = ("planshape.suite.conftest", "planshape.suite.test_runs")


def package_modules() -> list[str]:
    roots = (planshape, planshape.tasks, planshape.baselines)
    found = {
        info.name
        for root in roots
        for info in pkgutil.walk_packages(root.__path__, root.__name__ + ".")
    }
    return sorted(found - set(NOT_MODULES) | {"planshape"})


MODULES = package_modules()


def test_the_walk_finds_the_whole_package():
    assert len(MODULES) >= 90
    for name in (
        "planshape.shaping.potentials",
        "planshape.tasks.planar.render",
        "planshape.baselines.paper",
    ):
        assert name in MODULES


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples_run(name: str) -> None:
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0
