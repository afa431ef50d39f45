"""``planshape adopt``: bring finished runs from a scratch folder into a profile's stored results.

Long blocks are trained into a folder of their own (``planshape bench --out /scratch``), so that
an interrupted or failing block never touches the stored results; ``adopt`` then moves what
finished into the profile's folder, under rules that keep the store honest:

* a run the store lacks is added only if it is one of the store's profile's runs as the profile
  is now (task, entry, algorithm, seed, budget and settings), so nothing of another profile or
  an older budget is mixed in;
* a run the store has is replaced only by a re-execution that repeats it: the same rows with
  every stored field equal (floats exactly, NaN as NaN), except the provenance of the execution
  (:data:`EXECUTION_FIELDS`: wall time, throughput, code version, CPU); it may add fields, as a run
  re-trained after ``success_any_rate`` was recorded does. A re-execution whose numbers differ
  is refused, so stored evidence never changes silently;
* ``--whole-entries`` adds new runs only of entries whose every seed in the profile is then
  stored, so a committed cell never holds a partial entry.

Every run is checked before any file is written; a refusal exits with status 2 naming the file,
the row and the field, and changes nothing. Files are copied byte for byte.

Example:
    >>> stored = [{"run_id": "a", "step": 0, "success_rate": 0.5, "wall_time_s": 10.0}]
    >>> again = [{"run_id": "a", "step": 0, "success_rate": 0.5, "wall_time_s": 12.0,
    ...           "success_any_rate": 0.9}]
    >>> repeat_problem(stored, again) is None
    True
    >>> repeat_problem(stored, [{**again[0], "success_rate": 0.4}])
    'row 1 (step 0): success_rate 0.4, stored 0.5'
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from planshape.commands import Handler, subcommand
from planshape.errors import BadInputError
from planshape.harness.profiles import Profile, get_profile, profile_of_folder
from planshape.harness.store import ResultStore, write_atomic

__all__ = ["EXECUTION_FIELDS", "Adoption", "adopt", "plan_adoption", "repeat_problem"]

#: fields that describe one execution of a run, not its numbers: they may differ between a run
#: and its re-execution
EXECUTION_FIELDS = frozenset({"wall_time_s", "steps_per_s", "code_version", "cpu"})


def _same(a: Any, b: Any) -> bool:
    """Equal as stored values: of one type (rows are read with their schema's types) and
    equal, NaN equal to NaN."""
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return type(a) is type(b) and a == b


def repeat_problem(
    stored: Sequence[Mapping[str, Any]], again: Sequence[Mapping[str, Any]]
) -> str | None:
    """Why ``again`` does not repeat the ``stored`` run, or ``None`` if it does: as many rows,
    and in each every stored field but :data:`EXECUTION_FIELDS` equal (``again`` may have more
    fields)."""
    if len(stored) != len(again):
        return f"{len(again)} rows, stored {len(stored)}"
    for number, (old, new) in enumerate(zip(stored, again, strict=True), start=1):
        for name, value in old.items():
            if name in EXECUTION_FIELDS:
                continue
            if name not in new:
                return f"row {number} (step {old.get('step')}): no field {name!r}"
            if not _same(new[name], value):
                return (
                    f"row {number} (step {old.get('step')}): {name} {new[name]!r}, stored {value!r}"
                )
    return None


@dataclass
class Adoption:
    """What adopting a scratch folder does: files to add, files to replace, runs left."""

    added: list[Path] = field(default_factory=list)
    replaced: list[Path] = field(default_factory=list)
    unchanged: list[Path] = field(default_factory=list)
    held_back: list[Path] = field(default_factory=list)

    def summary(self) -> str:
        """One line per kind of change, for the terminal."""
        return "\n".join(
            f"{label}: {len(paths)} runs"
            for label, paths in (
                ("added", self.added),
                ("replaced by re-executions that repeat them", self.replaced),
                ("already stored as they are", self.unchanged),
                ("held back (their entries are not whole)", self.held_back),
            )
            if paths
        )


def _planned(profile: Profile) -> dict[tuple[str, str, str], set[int]]:
    """(task, algo, entry) -> the seeds the profile runs of it."""
    seeds: dict[tuple[str, str, str], set[int]] = {}
    for key in profile.runs():
        seeds.setdefault((key.task, key.algo, key.entry), set()).add(key.seed)
    return seeds


def _entry(rows: Sequence[Mapping[str, Any]]) -> tuple[str, str, str]:
    return str(rows[0]["task"]), str(rows[0]["algo"]), str(rows[0]["entry"])


def plan_adoption(
    source: Path, out: Path, profile: Profile, *, whole_entries: bool = False
) -> Adoption:
    """Check every run of ``source`` against the store in ``out``, which holds ``profile``'s
    runs, and say what adopting them would do; raise
    :class:`~planshape.errors.BadInputError` on the first run it must refuse."""
    scratch, store = ResultStore(source), ResultStore(out)
    if not scratch.stored():
        raise BadInputError(f"{source}: no finished runs (runs/*.jsonl) to adopt")
    new = {path: scratch.read(path) for path in scratch.stored()}
    stored = {path: store.read(path) for path in store.stored()}
    planned = _planned(profile)
    plan = Adoption()
    for path, rows in new.items():
        target = store.path(path.stem)
        if target in stored:
            problem = repeat_problem(stored[target], rows)
            if problem is not None:
                raise BadInputError(
                    f"{path}: does not repeat the stored run {target}: {problem}; its numbers "
                    "would change, so it is not adopted (train it into a folder of its own to "
                    "compare)"
                )
            same = target.read_bytes() == path.read_bytes()
            (plan.unchanged if same else plan.replaced).append(path)
        elif int(rows[0]["seed"]) in planned.get(_entry(rows), set()) and profile.shows(rows[0]):
            plan.added.append(path)
        else:
            task, algo, entry = _entry(rows)
            raise BadInputError(
                f"{path}: {entry} by {algo} on {task}, seed {rows[0]['seed']}, "
                f"{rows[0]['budget']:,} steps, is not a run of the {profile.name!r} profile as it "
                f"is now, whose results {out} holds; adopt it into its own profile's folder"
            )
    if whole_entries:
        have = {(*_entry(r), int(r[0]["seed"])) for r in (*new.values(), *stored.values())}
        whole = {e for e, seeds in planned.items() if all((*e, s) in have for s in seeds)}
        plan.held_back = [p for p in plan.added if _entry(new[p]) not in whole]
        plan.added = [p for p in plan.added if _entry(new[p]) in whole]
    return plan


def adopt(
    source: Path, out: Path, profile: Profile, *, whole_entries: bool = False, dry_run: bool = False
) -> Adoption:
    """Adopt the runs of ``source`` into ``out`` (module docstring); with ``dry_run`` only
    say what would change."""
    plan = plan_adoption(source, out, profile, whole_entries=whole_entries)
    if not dry_run:
        store = ResultStore(out)
        for path in (*plan.added, *plan.replaced):
            write_atomic(store.path(path.stem), path.read_bytes())
    return plan


@subcommand("adopt", "move finished runs from a scratch folder into a profile's stored results")
def _adopt(parser: argparse.ArgumentParser) -> Handler:
    parser.description = (
        "Add the finished runs of SOURCE (a folder planshape bench --out wrote) to the stored "
        "results in --out: runs not stored yet are added if they belong to the store's profile; "
        "a stored run is replaced only by a re-execution that repeats every stored number (it "
        "may add fields such as success_any_rate). Every run is checked before anything is "
        "written; a refusal changes nothing. Render the leaderboard afterwards with planshape "
        "leaderboard --out OUT."
    )
    parser.add_argument("source", type=Path, help="the scratch results folder")
    parser.add_argument("--out", type=Path, required=True, help="the profile's results folder")
    parser.add_argument(
        "--profile",
        default=None,
        help="the profile whose results --out holds (default: the profile whose folder it is)",
    )
    parser.add_argument(
        "--whole-entries",
        action="store_true",
        help="add new runs only of entries whose every seed in the profile is then stored",
    )
    parser.add_argument(
        "--dry-run", action="store_true", help="say what would change; write nothing"
    )
    return _run


def _profile_named(name: str | None, out: Path) -> Profile:
    """The ``--profile`` named, else the profile whose folder ``out`` is."""
    if name is not None:
        return get_profile(name)
    profile = profile_of_folder(out)
    if profile is not None:
        return profile
    raise BadInputError(
        f"{out}: not a profile's own folder; name the profile whose results it holds with --profile"
    )


def _run(args: argparse.Namespace) -> int:
    profile = _profile_named(args.profile, args.out)
    plan = adopt(
        args.source, args.out, profile, whole_entries=args.whole_entries, dry_run=args.dry_run
    )
    verb = "would change" if args.dry_run else "changed"
    print(f"{args.out}: {verb}:\n{plan.summary() or 'nothing'}")
    return 0
