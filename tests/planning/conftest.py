"""Fixtures of the planning tests: the delivery model and a helper for broken variants of it."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

DATA = Path(__file__).parent / "data"


@pytest.fixture
def domain() -> Path:
    return DATA / "delivery-domain.pddl"


@pytest.fixture
def problem() -> Path:
    return DATA / "delivery-problem.pddl"


@pytest.fixture
def variant(tmp_path: Path) -> Callable[..., Path]:
    """``variant("delivery-domain.pddl", old, new, ...)``: a copy of a data file with edits."""

    def make(name: str, *edits: str) -> Path:
        text = (DATA / name).read_text()
        for old, new in zip(edits[::2], edits[1::2], strict=True):
            assert old in text, f"{old!r} is not in {name}"
            text = text.replace(old, new, 1)
        path = tmp_path / name
        path.write_text(text)
        return path

    return make


def line_of(path: Path, snippet: str) -> int:
    """The 1-based line of the first occurrence of ``snippet`` in a file."""
    text = path.read_text()
    return text[: text.index(snippet)].count("\n") + 1
