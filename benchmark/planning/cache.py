"""The on-disk plan cache: validated plans keyed by the content hash of what produced them.

An entry is one JSON file ``<key>.json``::

    {"format": 1, "key": "<sha256>", "checksum": "<sha256 of the payload text>",
     "payload": {"search": ..., "arguments": [...], "actions": ["(move a b)", ...], "cost": 2,
                 "static": ["(neighbors a b)", ...], "fluents": [["(robot_at a)"], ...], ...}}

The subgoal states are stored as the static atoms once plus each state's fluent atoms, so that
a hit neither parses PDDL nor builds large sets (:class:`SubgoalStates` builds full states on
use). Entries are written atomically (a temporary file, then :func:`os.replace`). An entry
that cannot be read, has another format or key, or whose checksum does not match is ignored
with a warning; the caller plans again and overwrites it.

Example:
    >>> key = cache_key("(define (domain d))", "(define (problem p))", "astar-lmcut")
    >>> len(key)
    64
"""

from __future__ import annotations

import functools
import hashlib
import importlib.metadata
import json
import logging
import os
import tempfile
from pathlib import Path
from typing import Any

from planshape.planning.fast_downward import DRIVER_ENV, SEARCHES, search_arguments
from planshape.planning.model import GroundAction, Plan, SubgoalStates, format_atom

__all__ = ["CACHE_DIR_ENV", "CACHE_FORMAT", "PlanCache", "cache_key", "default_cache_dir"]

log = logging.getLogger("planshape.planning")

#: Bump when the entry layout or the meaning of its fields changes: old entries are then unused.
CACHE_FORMAT = 1
#: Environment variable naming the cache directory (default ``~/.cache/planshape/plans``).
CACHE_DIR_ENV = "PLANSHAPE_CACHE_DIR"

_PAYLOAD = '"payload":'
_PAYLOAD_BYTES = _PAYLOAD.encode()


def default_cache_dir() -> Path:
    """``$PLANSHAPE_CACHE_DIR`` if set, else ``~/.cache/planshape/plans``."""
    configured = os.environ.get(CACHE_DIR_ENV)
    if configured:
        return Path(configured).expanduser()
    return Path.home() / ".cache" / "planshape" / "plans"


@functools.cache
def _planner_version() -> str:
    try:
        return importlib.metadata.version("up-fast-downward")
    except importlib.metadata.PackageNotFoundError:
        return "unknown"


def cache_key(domain: str | bytes, problem: str | bytes, search: str) -> str:
    """sha256 over the cache format, planner, search name and arguments, domain and problem.

    ``domain`` and ``problem`` are PDDL texts (or their UTF-8 bytes: the same key). Each field
    is length-prefixed, so no two different inputs share a key by concatenation.
    """
    planner = os.environ.get(DRIVER_ENV) or f"up-fast-downward {_planner_version()}"
    fields = (
        f"planshape-plan-cache {CACHE_FORMAT}",
        planner,
        search,
        json.dumps(search_arguments(search)),
        domain,
        problem,
    )
    digest = hashlib.sha256()
    for field in fields:
        data = field if isinstance(field, bytes) else field.encode("utf-8")
        digest.update(b"%d:" % len(data))
        digest.update(data)
    return digest.hexdigest()


class PlanCache:
    """A directory of plan entries.

    Example:
        >>> import tempfile
        >>> from planshape.planning.model import GroundAction, Plan
        >>> cache = PlanCache(tempfile.mkdtemp())
        >>> plan = Plan((GroundAction("go", ("a", "b")),),
        ...             (frozenset({("at", "a")}), frozenset({("at", "b")})), 1, "astar-lmcut")
        >>> _ = cache.store("0" * 64, plan)
        >>> hit = cache.load("0" * 64)
        >>> hit == plan, hit.from_cache
        (True, True)
    """

    def __init__(self, directory: str | Path):
        self.directory = Path(directory)

    def path(self, key: str) -> Path:
        return self.directory / f"{key}.json"

    def load(self, key: str) -> Plan | None:
        """The cached plan for ``key``, or ``None`` when there is no usable entry."""
        path = self.path(key)
        try:
            text = path.read_bytes()
        except FileNotFoundError:
            return None
        except OSError as err:
            log.warning("ignoring unreadable plan cache entry %s (%s); planning again", path, err)
            return None
        try:
            return _decode(text, key)
        except _CorruptEntry as err:
            log.warning("ignoring plan cache entry %s: %s; planning again", path, err)
            return None

    def store(self, key: str, plan: Plan, **provenance: Any) -> Path:
        """Write ``plan`` under ``key`` atomically; extra keywords are kept in the payload."""
        text = _encode(key, plan, provenance)
        self.directory.mkdir(parents=True, exist_ok=True)
        handle, temporary = tempfile.mkstemp(dir=self.directory, prefix=".tmp-", suffix=".json")
        try:
            with os.fdopen(handle, "w", encoding="utf-8", newline="\n") as stream:
                stream.write(text)
            os.replace(temporary, self.path(key))
        except BaseException:
            Path(temporary).unlink(missing_ok=True)
            raise
        return self.path(key)


class _CorruptEntry(Exception):
    pass


def _encode(key: str, plan: Plan, provenance: dict[str, Any]) -> str:
    subgoals = plan.subgoals
    if not isinstance(subgoals, SubgoalStates):
        common = frozenset.intersection(*map(frozenset, subgoals)) if subgoals else frozenset()
        subgoals = SubgoalStates(common, [s - common for s in subgoals])
    payload = {
        "search": plan.search,
        "arguments": SEARCHES.get(plan.search),
        "actions": [str(a) for a in plan.actions],
        "cost": plan.cost,
        "planner_seconds": plan.planner_seconds,
        "static": sorted(map(format_atom, subgoals.static)),
        "fluents": [sorted(map(format_atom, f)) for f in subgoals.fluents],
        **provenance,
    }
    body = json.dumps(payload, separators=(",", ":"))
    checksum = hashlib.sha256(body.encode("utf-8")).hexdigest()
    head = json.dumps({"format": CACHE_FORMAT, "key": key, "checksum": checksum})
    return head[:-1] + ", " + _PAYLOAD + body + "}\n"


def _atom(text: str) -> tuple[str, ...]:
    """``"(at a)"`` -> ``("at", "a")`` for text this module wrote (lower case, one space)."""
    if text[0] != "(" or text[-1] != ")":
        raise ValueError(f"not an atom: {text!r}")
    return tuple(text[1:-1].split(" "))


def _decode(text: bytes, key: str) -> Plan:
    try:
        entry = json.loads(text)
    except ValueError as err:
        raise _CorruptEntry(f"not valid JSON ({err})") from None
    if not isinstance(entry, dict):
        raise _CorruptEntry("not a JSON object")
    if entry.get("format") != CACHE_FORMAT:
        raise _CorruptEntry(f"cache format {entry.get('format')!r}, expected {CACHE_FORMAT}")
    if entry.get("key") != key:
        raise _CorruptEntry("the entry's key does not match its inputs")
    start, end = text.find(_PAYLOAD_BYTES), text.rstrip().rfind(b"}")
    body = text[start + len(_PAYLOAD_BYTES) : end] if 0 <= start < end else b""
    if hashlib.sha256(body).hexdigest() != entry.get("checksum"):
        raise _CorruptEntry("checksum mismatch (the entry was truncated or edited)")
    try:
        payload = entry["payload"]
        actions = tuple(GroundAction(a[0], a[1:]) for a in map(_atom, payload["actions"]))
        fluents = [map(_atom, state) for state in payload["fluents"]]
        static = payload["static"]
        if not isinstance(static, list) or len(fluents) != len(actions) + 1:
            raise _CorruptEntry("the subgoals do not match the actions")
        return Plan(
            actions,
            SubgoalStates(functools.partial(map, _atom, static), fluents),
            int(payload["cost"]),
            str(payload["search"]),
            planner_seconds=0.0,
            from_cache=True,
        )
    except (KeyError, TypeError, ValueError, AttributeError, IndexError) as err:
        raise _CorruptEntry(f"malformed payload ({type(err).__name__}: {err})") from None
