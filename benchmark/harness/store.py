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
    >>> store.path("abc").name
    'abc.jsonl'

Two benchmarks may write into one folder at once (different ``-k`` selections, say): while a
run trains, its benchmark holds a claim on it (:meth:`ResultStore.claim`, a lock the operating
system releases when the process ends, however it ends), and another benchmark that reaches
the same run skips it instead of training it a second time.

A file counts as a finished run only if :func:`planshape.results.rows.read_run` reads it as a
whole run; reading every run back, with those checks, is
:func:`planshape.results.rows.load_rows`. A temporary file carries the id of the process writing
it, so a starting benchmark removes only those of processes that are gone, never another live
benchmark's.
"""

from __future__ import annotations

import contextlib
import json
import os
import tempfile
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any

from planshape.errors import ResultsError


class ResultStore:
    """Rows of finished runs under ``<out>/runs``."""

    def __init__(self, out: str | Path):
        self.out = Path(out)
        self.runs = self.out / "runs"

    def path(self, run_id: str) -> Path:
        return self.runs / f"{run_id}.jsonl"

    def has(self, run_id: str) -> bool:
        """Whether the run is stored and whole; a damaged or unfinished file raises
        :class:`planshape.errors.ResultsError` (it is neither trained over nor counted)."""
        path = self.path(run_id)
        if not path.exists():
            return False
        self.read(path)
        return True

    def read(self, path: Path) -> list[dict[str, Any]]:
        """The rows of a stored run file, checked to be one whole run of the id in its name
        (:func:`planshape.results.rows.read_run`), else
        :class:`planshape.errors.ResultsError`."""
        from planshape.results.rows import read_run

        rows = read_run(path)
        if rows[0]["run_id"] != path.stem:
            raise ResultsError(
                f"holds run {rows[0]['run_id']!r}, not the run {path.stem!r} of its name: move the "
                "file out of runs/ (or delete it) and run the benchmark again to retrain it",
                path,
            )
        return rows

    def stored(self) -> list[Path]:
        """The run files, by name."""
        return sorted(self.runs.glob("*.jsonl")) if self.runs.is_dir() else []

    def write(self, run_id: str, rows: Iterable[dict[str, Any]]) -> Path:
        """Write a finished run's rows atomically (a run written again is replaced whole)."""
        text = "".join(json.dumps(row, sort_keys=True) + "\n" for row in rows)
        return write_atomic(self.path(run_id), text)

    @contextlib.contextmanager
    def claim(self, run_id: str) -> Iterator[bool]:
        """While the block runs, hold the claim on training ``run_id``: yields True when this
        process holds it, False when another live process does. The claim is an exclusive
        ``flock`` on ``<out>/.claims/<run_id>.lock``, removed when released; the kernel drops a
        killed holder's lock with the process. A claimer should check :meth:`has` again once it
        holds the claim (the holder before it may have finished the run). Where ``fcntl`` is
        missing (Windows) every claim is granted.

        Example:
            >>> import tempfile
            >>> store = ResultStore(tempfile.mkdtemp())
            >>> with store.claim("abc") as mine, store.claim("abc") as again:
            ...     mine, again
            (True, False)
        """
        try:
            import fcntl
        except ImportError:  # pragma: no cover - not on POSIX
            yield True
            return
        folder = self.out / ".claims"
        folder.mkdir(parents=True, exist_ok=True)
        path = folder / f"{run_id}.lock"
        descriptor = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            try:
                fcntl.flock(descriptor, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                yield False
                return
            try:
                os.write(descriptor, f"{os.getpid()}\n".encode())
                yield True
            finally:
                path.unlink(missing_ok=True)
                fcntl.flock(descriptor, fcntl.LOCK_UN)
        finally:
            os.close(descriptor)

    def clean_partial(self) -> int:
        """Remove the temporary files of writers that were killed while writing (their process
        is gone); a live process's file is left alone. Returns how many were removed."""
        stale = [
            path
            for path in (self.runs.glob(".*.tmp") if self.runs.is_dir() else ())
            if not _alive(_writer(path))
        ]
        for path in stale:
            path.unlink(missing_ok=True)
        return len(stale)


def write_atomic(path: str | Path, content: str | bytes) -> Path:
    """Write ``content`` to ``path`` through a temporary file in the same folder, flushed to
    disk and renamed over ``path``: a reader sees the old file or the new one, never a part.
    A file that already holds ``content`` is left untouched. The temporary file is named
    ``.<name>.<pid>.<random>.tmp`` (see :meth:`ResultStore.clean_partial`) and removed if
    writing fails.

    Example:
        >>> import tempfile, pathlib
        >>> path = write_atomic(pathlib.Path(tempfile.mkdtemp()) / "a.txt", "text")
        >>> path.read_text()
        'text'
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    data = content.encode("utf-8") if isinstance(content, str) else content
    if path.is_file() and path.stat().st_size == len(data) and path.read_bytes() == data:
        return path  # unchanged: not even its modification time changes
    with tempfile.NamedTemporaryFile(
        "wb", dir=path.parent, prefix=f".{path.stem}.{os.getpid()}.", suffix=".tmp", delete=False
    ) as handle:
        try:
            handle.write(data)
            handle.flush()
            os.fsync(handle.fileno())
        except BaseException:
            handle.close()
            os.unlink(handle.name)
            raise
    os.replace(handle.name, path)
    return path


def _writer(path: Path) -> int | None:
    """The process id in a temporary file's name (``.<run_id>.<pid>.<random>.tmp``)."""
    parts = path.name.split(".")
    return int(parts[2]) if len(parts) >= 5 and parts[2].isdigit() else None


def _alive(pid: int | None) -> bool:
    """Whether process ``pid`` exists (None, from a name without one: treated as gone)."""
    if pid is None:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # it exists, under another user
        return True
    return True
