"""One item per training run of the selected profile (see ``conftest.py``)."""

from __future__ import annotations

import pytest

from planshape.harness.profiles import RunKey
from planshape.suite.session import BenchSession


def test_run(run_key: RunKey, bench: BenchSession) -> None:
    if bench.is_done(run_key):
        pytest.skip("already in the results store")
    bench.run(run_key)
