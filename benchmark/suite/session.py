"""State of one benchmark session: the selected runs, the store, the executor, the verdicts.

The pytest plugin in ``conftest.py`` is a thin layer over this class, so the same selection and
the same run function serve ``pytest benchmark/suite``, ``planshape bench`` and the tests.
"""

from __future__ import annotations

import contextlib
import json
import os
import re
import signal
import sys
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pytest

from planshape.errors import BadInputError, UnknownIdError
from planshape.harness.profiles import Profile, RunKey, get_profile
from planshape.harness.runner import RunSpec, execute
from planshape.harness.store import ResultStore, write_atomic
from planshape.shaping.registration import task_ids

#: the user property of an item whose run another benchmark on the same folder is training
BUSY = ("planshape", "busy")
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
        seeds = [int(s) for s in text.split(",") if s.strip()]
    except ValueError:
        raise BadInputError(f"--seeds takes comma-separated integers, not {text!r}") from None
    negative = [s for s in seeds if s < 0]
    if negative:
        raise BadInputError(f"--seeds: a seed is a non-negative integer, not {negative[0]}")
    return seeds


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
    #: a folder to log every trained run to (planshape.training.tensorboard_logs), or None
    tensorboard: str | None = None
    #: draw a bar over each run's training steps (a single-worker session on a terminal)
    progress: bool = False
    collected: int = 0
    store: ResultStore = field(init=False)
    _checked: dict[str, str] = field(init=False, default_factory=dict)

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
            tensorboard=option("--tensorboard"),
            # in a process pool the workers' output is not shown: only the session's bar
            progress=not hasattr(config, "workerinput") and option("--executor") == "local",
        )

    # ---- selection ---------------------------------------------------------------------------

    def keys(self) -> list[RunKey]:
        return list(
            self.profile.runs(tasks=self.tasks, seeds=self.seeds, extra_potentials=self.potentials)
        )

    def estimated_seconds(self) -> dict[str, float]:
        """Item id -> the estimated wall time of its run
        (:func:`planshape.harness.estimate.run_seconds`;
        a run without a measured rate counts its budget at the slowest known rate); 0 for a
        run already stored, which takes no time."""
        from planshape.harness.estimate import TRAINING_RATE, run_seconds

        slowest = min(TRAINING_RATE.values())
        return {
            self.item_id(k): (
                0.0 if self.is_done(k) else run_seconds(k, self.profile) or k.budget / slowest
            )
            for k in self.keys()
        }

    @staticmethod
    def item_id(key: RunKey) -> str:
        name = key.task.split("/", 1)[-1]
        return f"{name}|{key.entry}|{key.algo}|seed{key.seed}"

    @staticmethod
    def marks(key: RunKey) -> list[str]:
        """Markers of an item: its algorithm, its task family and its reward kind."""
        from planshape.training.hyperparams import family

        return [_marker(key.algo), _marker(family(key.task)), _marker(key.reward)]

    def markers(self) -> set[str]:
        return {m for key in self.keys() for m in self.marks(key)}

    # ---- invariance verdicts -------------------------------------------------------------------

    @property
    def verdict_file(self) -> Path:
        return self.out / "invariance.json"

    def verdict(self, potential: str | None) -> str:
        """The invariance checker's verdict on ``potential``, computed once per session by the
        code that trains (so a changed potential or checker is checked again) and recorded in
        ``<out>/invariance.json``, which is rewritten only when a verdict changes."""
        if potential is None:
            return "not-applicable"
        if potential not in self._checked:
            self._checked[potential] = check_invariance(potential)
            recorded = self._verdicts()
            if recorded.get(potential) != self._checked[potential]:
                recorded[potential] = self._checked[potential]
                _write_json(self.verdict_file, recorded)
        return self._checked[potential]

    def _verdicts(self) -> dict[str, Any]:
        try:
            recorded = json.loads(self.verdict_file.read_text(encoding="utf-8"))
        except (FileNotFoundError, UnicodeDecodeError, json.JSONDecodeError):
            return {}
        return {p: v for p, v in recorded.items() if isinstance(v, str)}

    # ---- running -------------------------------------------------------------------------------

    def prepare(self) -> None:
        """Controller-side start: drop half-written files, check every potential once."""
        self.store.clean_partial()
        for potential in sorted({k.potential for k in self.keys() if k.potential}):
            self.verdict(potential)

    def spec(self, key: RunKey, *, with_verdict: bool = True) -> RunSpec:
        """The run's spec; its id does not depend on the verdict, which is only computed for
        a run that trains (``with_verdict``)."""
        return self.profile.spec(
            key, invariance=self.verdict(key.potential) if with_verdict else "not-checked"
        )

    def claim(self, key: RunKey) -> contextlib.AbstractContextManager[bool]:
        """The store's claim on training ``key``'s run (:meth:`ResultStore.claim`)."""
        return self.store.claim(self.spec(key, with_verdict=False).run_id)

    def is_done(self, key: RunKey) -> bool:
        return self.store.has(self.spec(key, with_verdict=False).run_id)

    def run(self, key: RunKey) -> list[dict[str, Any]]:
        spec = self.spec(key)
        run_id = spec.run_id  # before running: the identity of what was asked for
        if self.executor == "local":
            rows = execute(spec, self.tensorboard, progress=self.progress)
        else:
            rows = _execute_on_ray(spec, self.address, self.tensorboard)
        self.store.write(run_id, rows)
        return rows

    def finish(self) -> str:
        """Render the leaderboard from every stored row; return the terminal summary."""
        from planshape.results.leaderboard import render_leaderboard, summary_table
        from planshape.results.rows import load_rows

        rows = load_rows(self.out) if self.store.runs.is_dir() else []
        if not rows:
            return ""
        shown = self.profile.shown(rows)
        if self.render:
            render_leaderboard(shown, self.out, self.profile.header(rows))
        return summary_table(shown)


def check_invariance(potential: str) -> str:
    """``"preserved"`` or ``"violated"`` from the invariance checker on every toy MDP."""
    from planshape.invariance import check_potential

    report = check_potential(potential)
    return "preserved" if report.preserved else "violated"


def _execute_on_ray(
    spec: RunSpec, address: str | None, tensorboard: str | None = None
) -> list[dict[str, Any]]:
    """Run ``execute(spec)`` as a Ray task (one CPU): the same function, so the same numbers."""
    try:
        import ray
    except ImportError:
        raise BadInputError("--executor ray needs Ray: pip install 'planshape[ray]'") from None
    if not ray.is_initialized():
        ray.init(address=address, log_to_driver=False, include_dashboard=False)
    remote = ray.remote(num_cpus=1)(execute)
    return ray.get(remote.remote(spec, tensorboard))


def end_with_parent() -> bool:
    """Have the kernel end this process (SIGTERM) when its parent dies, so a pool worker never
    outlives a benchmark that was killed, even with SIGKILL. Linux only (``prctl``); returns
    whether it was set."""
    if not sys.platform.startswith("linux"):
        return False
    import ctypes

    pr_set_pdeathsig = 1
    libc = ctypes.CDLL(None, use_errno=True)
    if libc.prctl(pr_set_pdeathsig, signal.SIGTERM, 0, 0, 0) != 0:
        return False
    return os.getppid() != 1  # the parent may have died before the call


def _marker(name: str) -> str:
    return re.sub(r"\W", "_", name)


def _write_json(path: Path, data: Any) -> None:
    write_atomic(path, json.dumps(data, indent=2, sort_keys=True) + "\n")
