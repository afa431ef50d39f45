"""The results store: append-only tidy rows, one JSON Lines file per finished run.

``<out>/runs/<run_id>.jsonl`` holds every evaluation row of one training run. It is written
once, atomically (a temporary file renamed into place), when the run has finished, so a killed
benchmark leaves either a whole run or nothing, and a resumed benchmark skips exactly the runs
whose file exists.

Example:
    >>> import tempfile
    >>> store = ResultStore(tempfile.mkdtemp())
    >>> store.has("abc")
    False
    >>> _ = store.write("abc", [{"task": "t", "step": 0}])
    >>> store.has("abc")
    True

Reading the rows back, with checks, is :func:`planshape.scoring.load_rows`.
"""

from __future__ import annotations

import json
import os
import tempfile
from collections.abc import Iterable
from pathlib import Path
from typing import Any


class ResultStore:
    """Rows of finished runs under ``<out>/runs``."""

    def __init__(self, out: str | Path):
        self.out = Path(out)
        self.runs = self.out / "runs"

    def path(self, run_id: str) -> Path:
        return self.runs / f"{run_id}.jsonl"

    def has(self, run_id: str) -> bool:
        return self.path(run_id).is_file()

    def write(self, run_id: str, rows: Iterable[dict[str, Any]]) -> Path:
        """Write a finished run's rows atomically; an existing run is left as it is."""
        self.runs.mkdir(parents=True, exist_ok=True)
        target = self.path(run_id)
        text = "".join(json.dumps(row, sort_keys=True) + "\n" for row in rows)
        with tempfile.NamedTemporaryFile(
            "w", dir=self.runs, prefix=f".{run_id}.", suffix=".tmp", delete=False
        ) as handle:
            handle.write(text)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(handle.name, target)
        return target

    def clean_partial(self) -> int:
        """Remove temporary files left by runs that were killed while writing."""
        stale = list(self.runs.glob(".*.tmp")) if self.runs.is_dir() else []
        for path in stale:
            path.unlink(missing_ok=True)
        return len(stale)
