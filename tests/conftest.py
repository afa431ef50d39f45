"""Shared fixtures: every test plans into its own temporary plan cache."""

from __future__ import annotations

import pytest


@pytest.fixture(autouse=True)
def _isolated_plan_cache(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch):
    monkeypatch.setenv("PLANSHAPE_CACHE_DIR", str(tmp_path_factory.mktemp("plan-cache")))
