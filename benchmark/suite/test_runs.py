"""One item per training run of the selected profile (see ``conftest.py``)."""

from __future__ import annotations

import pytest

from planshape.harness.profiles import RunKey
from planshape.suite.session import BUSY, BenchSession


def test_run(run_key: RunKey, bench: BenchSession, request: pytest.FixtureRequest) -> None:
    if bench.is_done(run_key):
        pytest.skip("already in the results store")
    with bench.claim(run_key) as mine:
        if not mine:
            request.node.user_properties.append(BUSY)  # the progress line says "busy"
            pytest.skip("being trained by another planshape bench on this folder")
        if bench.is_done(run_key):  # the benchmark that held the claim finished it
            pytest.skip("already in the results store")
        bench.run(run_key)
