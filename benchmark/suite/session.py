"""State of one benchmark session: the selected runs, the store, the executor, the verdicts.

The pytest plugin in ``conftest.py`` is a thin layer over this class, so the same selection and
the same run function serve ``pytest benchmark/suite``, ``planshape bench`` and the tests.
"""

from __future__ import annotations

import json
import os
import re
import tempfile
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pytest

from planshape.errors import BadInputError, UnknownIdError
from planshape.profiles import Profile, RunKey, get_profile
from planshape.registration import task_ids
from planshape.runner import RunSpec, code_version, execute
from planshape.store import ResultStore

SHAPED_ENTRY = re.compile(r"^(?P<potential>.+)/(?P<model>[^/]+)$")


def _short(task_id: str) -> str:
    """``planshape/MazeReach-v0`` -> ``mazereach``: the comparable part of a task name."""
    name = re.sub(r"-v\d+$", "", task_id.split("/", 1)[-1])
    return re.sub(r"[-_]", "", name).lower()


def _version(task_id: str) -> int:
    found = re.search(r"-v(\d+)$", task_id)
    return int(found.group(1)) if found else -1


def resolve_tasks(names: str | None) -> list[str] | None:
    """``"reach,planshape/Push-v0"`` -> task ids. A short name matches a task's name without
    namespace, version, dashes or case, and means its newest version (``maze-reach`` ->
    ``planshape/MazeReach-v1``)."""
    if not names:
        return None
    known = task_ids()
    by_short = {_short(t): t for t in sorted(known, key=_version)}
    chosen = []
    for name in (n.strip() for n in names.split(",") if n.strip()):
        task = name if name in known else by_short.get(_short(name))
        if task is None:
            raise UnknownIdError("task", name, known, hint="`planshape tasks` lists them")
        chosen.append(task)
    return chosen


def parse_seeds(text: str | None) -> list[int] | None:
    if not text:
        return None
    try:
        return [int(s) for s in text.split(",") if s.strip()]
    except ValueError:
        raise BadInputError(f"--seeds takes comma-separated integers, not {text!r}") from None


@dataclass
class BenchSession:
    """The runs a benchmark session selected and how it executes and stores them."""

    profile: Profile
    out: Path
    potentials: Sequence[str] = ()
    tasks: Sequence[str] | None = None
    seeds: Sequence[int] | None = None
    executor: str = "local"
    address: str | None = None
    render: bool = True
    command: str = ""
    collected: int = 0
    store: ResultStore = field(init=False)

    KEY = pytest.StashKey["BenchSession"]()

    def __post_init__(self) -> None:
        self.store = ResultStore(self.out)

    @classmethod
    def from_options(cls, config: pytest.Config) -> BenchSession:
        option = config.getoption
        return cls(
            profile=get_profile(option("--profile")),
            out=Path(option("--out")),
            potentials=tuple(option("--potential")),
            tasks=resolve_tasks(option("--tasks")),
            seeds=parse_seeds(option("--seeds")),
            executor=option("--executor"),
            address=option("--address"),
            render=not option("--no-render"),
            command=os.environ.get("PLANSHAPE_BENCH_COMMAND", "pytest benchmark/suite"),
        )

    # ---- selection ---------------------------------------------------------------------------

    def keys(self) -> list[RunKey]:
        return list(
            self.profile.runs(tasks=self.tasks, seeds=self.seeds, extra_potentials=self.potentials)
        )

    @staticmethod
    def item_id(key: RunKey) -> str:
        name = key.task.split("/", 1)[-1]
        return f"{name}|{key.entry}|{key.algo}|seed{key.seed}"

    @staticmethod
    def marks(key: RunKey) -> list[str]:
        """Markers of an item: its algorithm, its task family and its reward kind."""
        from planshape.hyperparams import family

        return [_marker(key.algo), _marker(family(key.task)), _marker(key.reward)]

    def markers(self) -> set[str]:
        return {m for key in self.keys() for m in self.marks(key)}

    # ---- invariance verdicts -------------------------------------------------------------------

    @property
    def verdict_file(self) -> Path:
        return self.out / "invariance.json"

    def verdict(self, potential: str | None) -> str:
        """The invariance checker's verdict on ``potential`` (cached in ``<out>``)."""
        if potential is None:
            return "not-applicable"
        cached = self._verdicts()
        entry = cached.get(potential)
        if entry and entry.get("code_version") == code_version():
            return entry["verdict"]
        verdict = check_invariance(potential)
        cached = self._verdicts()
        cached[potential] = {"verdict": verdict, "code_version": code_version()}
        _write_json(self.verdict_file, cached)
        return verdict

    def _verdicts(self) -> dict[str, Any]:
        try:
            return json.loads(self.verdict_file.read_text())
        except (FileNotFoundError, json.JSONDecodeError):
            return {}

    # ---- running -------------------------------------------------------------------------------

    def prepare(self) -> None:
        """Controller-side start: drop half-written files, check every potential once."""
        self.store.clean_partial()
        for potential in sorted({k.potential for k in self.keys() if k.potential}):
            self.verdict(potential)

    def spec(self, key: RunKey) -> RunSpec:
        return RunSpec.create(
            key,
            self.profile.name,
            self.profile.eval_every,
            self.profile.eval_episodes,
            invariance=self.verdict(key.potential),
        )

    def is_done(self, key: RunKey) -> bool:
        return self.store.has(self.spec(key).run_id)

    def run(self, key: RunKey) -> list[dict[str, Any]]:
        spec = self.spec(key)
        run_id = spec.run_id  # before running: the identity of what was asked for
        rows = execute(spec) if self.executor == "local" else _execute_on_ray(spec, self.address)
        self.store.write(run_id, rows)
        return rows

    def finish(self) -> str:
        """Render the leaderboard from every stored row; return the terminal summary."""
        from planshape.leaderboard import render_leaderboard, summary_table
        from planshape.scoring import load_rows

        rows = load_rows(self.out) if self.store.runs.is_dir() else []
        if not rows:
            return ""
        if self.render:
            render_leaderboard(rows, self.out, self.header())
        return summary_table(rows)

    def header(self) -> dict[str, Any]:
        return {
            "profile": self.profile.name,
            "description": self.profile.description,
            "command": self.command,
            "caveats": list(self.profile.caveats),
            "eval_every": self.profile.eval_every,
            "eval_episodes": self.profile.eval_episodes,
            "rendered": time.strftime("%Y-%m-%d", time.gmtime()),
        }


def check_invariance(potential: str) -> str:
    """``"preserved"`` or ``"violated"`` from the invariance checker on every toy MDP."""
    from planshape.invariance import check_potential

    report = check_potential(potential)
    return "preserved" if report.preserved else "violated"


def _execute_on_ray(spec: RunSpec, address: str | None) -> list[dict[str, Any]]:
    """Run ``execute(spec)`` as a Ray task (one CPU): the same function, so the same numbers."""
    try:
        import ray
    except ImportError:
        raise BadInputError("--executor ray needs Ray: pip install 'planshape[ray]'") from None
    if not ray.is_initialized():
        ray.init(address=address, log_to_driver=False, include_dashboard=False)
    remote = ray.remote(num_cpus=1)(execute)
    return ray.get(remote.remote(spec))


def _marker(name: str) -> str:
    return re.sub(r"\W", "_", name)


def _write_json(path: Path, data: Any) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.NamedTemporaryFile("w", dir=path.parent, delete=False, suffix=".tmp") as f:
        json.dump(data, f, indent=2, sort_keys=True)
    os.replace(f.name, path)
