"""The runnable examples in the docstrings of the planar task versions, their models and
instance sets, the learners and evaluation protocol, and the results store, run as tests."""

from __future__ import annotations

import doctest
import importlib

import pytest

import planshape  # noqa: F401  (registers the tasks)

MODULES = [
    "planshape.tasks.planar.geometry",
    "planshape.tasks.planar.versions",
    "planshape.tasks.planar.paper_models",
    "planshape.tasks.planar.instances",
    "planshape.tasks.planar.abstract",
    "planshape.tasks.planar.oracle",
    "planshape.tasks.metaworld.observation",
    "planshape.tasks.metaworld.reach",
    "planshape.learners",
    "planshape.profiles",
    "planshape.runner",
    "planshape.estimate",
    "planshape.tasks.common",
    "planshape.store",
    "planshape.bench",
    "planshape.testing",
    "planshape.invariance.probes",
    "planshape.planning.prepass",
    "planshape.figures",
    "planshape.videos",
    "planshape.probe",
]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples_run(name: str) -> None:
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0 and result.attempted > 0
