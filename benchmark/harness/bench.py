"""``planshape bench`` and ``planshape leaderboard``.

``planshape bench`` runs the benchmark suite (``benchmark/suite``, a pytest suite with one item
per training run) over a process pool, resuming from the results already stored in ``--out``,
then renders the leaderboard there. ``planshape leaderboard`` renders it again from the stored
rows without training.

Example:
    >>> main(["bench", "--profile", "smoke", "--out", "/tmp/planshape-smoke"])  # doctest: +SKIP
    0
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import signal
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any

from planshape.commands import Handler, subcommand
from planshape.errors import BadInputError
from planshape.harness.profiles import (
    PROFILES,
    RESULTS_ROOT,
    Profile,
    get_profile,
    profile_of_folder,
)

SUITE = Path(__file__).resolve().parents[1] / "suite"


def pytest_arguments(args: argparse.Namespace) -> list[str]:
    """The pytest command line that runs the selected part of the suite."""
    arguments = [
        str(SUITE),
        "--import-mode=importlib",
        "-p",
        "no:cacheprovider",
        "-o",
        "addopts=",
        "-o",
        "console_output_style=classic",
        "-q",
        "--profile",
        args.profile,
        "--out",
        str(args.out),
        "--executor",
        args.executor,
    ]
    for potential in args.potential:
        arguments += ["--potential", potential]
    for option in ("tasks", "seeds", "address", "tensorboard"):
        value = getattr(args, option)
        if value:
            arguments += [f"--{option}", value]
    if args.k:
        arguments += ["-k", args.k]
    if args.no_render:
        arguments.append("--no-render")
    workers = args.workers or os.cpu_count() or 1
    if workers > 1:
        arguments += ["-p", "xdist", "-n", str(workers)]
    else:  # the run trains in this process: let its progress bar reach the terminal
        arguments.append("--capture=no")
    return arguments


@subcommand("bench", "run the benchmark (train, evaluate, store) and render the leaderboard")
def _bench(parser: argparse.ArgumentParser) -> Handler:
    parser.description = (
        "Train every run of a profile that is not yet in the results store, evaluate it on the "
        "task's own metrics and render the leaderboard. Interrupted runs are redone; finished "
        "ones never are. Profiles: "
        + "; ".join(f"{p.name}: {p.description}" for p in PROFILES.values())
    )
    parser.add_argument("--profile", default="default", help="profile (default: %(default)s)")
    parser.add_argument(
        "--out",
        type=Path,
        default=None,
        help="results and leaderboard folder (default: the profile's own, leaderboard/ for the "
        "default profile and leaderboard/<profile>/ for any other)",
    )
    parser.add_argument(
        "--potential",
        action="append",
        default=[],
        metavar="REF",
        help="a potential to rank beside the references: a registered id or module:attr; it "
        "is checked for invariance first, then trained on every model of every task",
    )
    parser.add_argument("--tasks", help="comma-separated tasks to keep, e.g. reach,push")
    parser.add_argument("--seeds", help="comma-separated seeds to keep, e.g. 0,1")
    parser.add_argument(
        "--executor", choices=("local", "ray"), default="local", help="local process pool or Ray"
    )
    parser.add_argument("--address", help="Ray cluster address, with --executor ray")
    parser.add_argument(
        "--workers", type=int, default=None, help="parallel runs (default: one per CPU core)"
    )
    parser.add_argument("-k", help="pytest -k expression to select runs, e.g. 'PPO and grid'")
    parser.add_argument("--no-render", action="store_true", help="do not render the leaderboard")
    parser.add_argument(
        "--tensorboard",
        metavar="DIR",
        help="also log every run it trains to TensorBoard under DIR (stored results unchanged)",
    )
    parser.add_argument(
        "--dry-run",
        action="store_true",
        help="print the selected runs and their estimated wall time; train and write nothing",
    )
    return run_bench


def run_bench(args: argparse.Namespace) -> int:
    """``planshape bench``: check the selection and the results folder, run the benchmark suite
    (``planshape.suite``) under pytest, and render the leaderboard; returns the exit status."""
    import pytest

    from planshape.suite.session import parse_seeds, resolve_tasks

    # bad input is reported before anything starts
    profile = get_profile(args.profile)
    if profile.archived:
        raise BadInputError(f"--profile {profile.name} cannot be run: {profile.archived}")
    args.out = args.out if args.out is not None else Path(profile.folder)
    if args.workers is not None and args.workers < 1:
        raise BadInputError(
            f"--workers is the number of parallel runs, at least 1, not {args.workers}; leave it "
            "out for one per CPU core"
        )
    check_store(args.out, profile, args.potential)
    tasks, seeds = resolve_tasks(args.tasks), parse_seeds(args.seeds)
    if not any(profile.runs(tasks=tasks, seeds=seeds)):
        raise BadInputError(
            f"--tasks/--seeds select no run of profile {profile.name!r}; `planshape bench "
            f"--profile {profile.name} --dry-run` lists its runs"
        )
    if args.k and not any(
        selected_by(args.k, key)
        for key in profile.runs(tasks=tasks, seeds=seeds, extra_potentials=args.potential)
    ):
        raise BadInputError(
            f"the selection matches no run: -k {args.k!r} selects none of profile "
            f"{profile.name!r}'s runs (with the --tasks and --seeds given); `planshape bench "
            f"--profile {profile.name} --dry-run` lists them with their names"
        )
    if args.executor != "ray" and args.address:
        raise BadInputError("--address applies only with --executor ray")
    if args.tensorboard:
        from planshape.training.tensorboard_logs import require_tensorboard

        require_tensorboard()
    if args.dry_run:
        return _dry_run(args, profile)
    for reference in args.potential:
        _check_submission(reference)
    with _signals_interrupt() as received:
        status = pytest.main(pytest_arguments(args))
    if status == pytest.ExitCode.INTERRUPTED:
        # pytest has ended the pool's workers; finished runs are stored, the rest resume
        return 128 + (received[-1] if received else signal.SIGINT)
    if status == pytest.ExitCode.NO_TESTS_COLLECTED:
        raise BadInputError("the selection matches no run; check --tasks, --seeds and -k")
    if status == pytest.ExitCode.USAGE_ERROR:
        return 2
    return 0 if status == pytest.ExitCode.OK else 1


@contextlib.contextmanager
def _signals_interrupt() -> Iterator[list[int]]:
    """While the suite runs, SIGTERM (and SIGHUP) interrupt it as Ctrl-C does: pytest then
    tears the process pool down, so no worker is left training. Yields the signals received,
    for the exit status (128 + the signal's number, 130 for Ctrl-C)."""
    received: list[int] = []

    def interrupt(number: int, _frame: Any) -> None:
        received.append(number)
        raise KeyboardInterrupt(f"signal {signal.Signals(number).name}")

    previous = {s: signal.signal(s, interrupt) for s in (signal.SIGTERM, signal.SIGHUP)}
    try:
        yield received
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler)


def selected_by(expression: str, key: Any) -> bool:
    """Whether ``-k expression`` selects the suite's item of run ``key``: pytest's own keyword
    matching on the names the item carries (its id, its module and its markers).

    Example:
        >>> from planshape.harness.profiles import RunKey
        >>> key = RunKey("planshape/Reach-v1", "dense", "SAC-default", 0, 1000)
        >>> selected_by("Reach and dense and default", key), selected_by("PPO", key)
        (True, False)
    """
    from _pytest.mark import KeywordMatcher
    from _pytest.mark.expression import Expression

    from planshape.suite.session import BenchSession

    names = {f"test_run[{BenchSession.item_id(key)}]", "test_runs.py", *BenchSession.marks(key)}
    try:
        return Expression.compile(expression).evaluate(KeywordMatcher(names))
    except SyntaxError as exc:
        raise BadInputError(f"-k {expression!r} is not a pytest -k expression: {exc}") from None


def _dry_run(args: argparse.Namespace, profile: Any) -> int:
    """Print the runs the selection would train (not yet stored) and their estimated time."""
    from planshape.harness.estimate import estimate, render
    from planshape.harness.store import ResultStore
    from planshape.suite.session import parse_seeds, resolve_tasks

    store = ResultStore(args.out)
    keys = [
        key
        for key in profile.runs(
            tasks=resolve_tasks(args.tasks),
            seeds=parse_seeds(args.seeds),
            extra_potentials=args.potential,
        )
        if not store.has(profile.spec(key).run_id)
    ]
    if args.k:
        keys = [key for key in keys if selected_by(args.k, key)]
    workers = args.workers or os.cpu_count() or 1
    rows, total = estimate(keys, profile, workers)
    print(f"profile {profile.name}, results in {args.out} (nothing trains or is written)")
    print(render(rows, total, workers))
    return 0


def check_store(out: Path, profile: Profile, extra_potentials: Sequence[str] = ()) -> None:
    """Refuse, before anything trains, a results folder that cannot take this profile's runs:
    ``--out`` is not a folder, a stored run file is damaged or unfinished (it would count as a
    missing run, or be lost), or the folder holds runs of another profile or of another
    evaluation protocol (new runs would mix into them). Nothing is changed.

    A run stored by another profile whose id is one of this profile's runs is the same run
    (ids hash what determines the numbers, not the profile's name), so it is accepted: a
    larger profile's folder can start from a smaller one's runs (copy ``runs/*.jsonl``). So is
    one that neither its own profile nor this one shows any more (its budget or settings were
    replaced, :meth:`Profile.shows`): such a run was copied in when it was a run of both, and
    stays stored without entering a cell.

    Example:
        >>> import tempfile
        >>> check_store(Path(tempfile.mkdtemp()), get_profile("smoke"))  # an empty folder
    """
    from planshape.harness.runner import EVAL_PROTOCOL
    from planshape.harness.store import ResultStore

    for folder in (out, *out.parents):
        if folder.exists() and not folder.is_dir():
            raise BadInputError(
                f"--out {out}: {folder} is a file, not a folder; choose a folder for the results"
            )
    store = ResultStore(out)
    stored = store.stored()
    if not stored:
        return
    own = {profile.spec(k).run_id for k in profile.runs(extra_potentials=extra_potentials)}
    found: dict[tuple[str, int], str] = {}
    for path in stored:
        first = store.read(path)[0]
        key = (first["profile"], int(first.get("eval_protocol", 1)))
        if (
            key[0] != profile.name
            and key[1] == EVAL_PROTOCOL
            and (path.stem in own or _retired(first, profile))
        ):
            continue  # the same run, stored by another profile, or one no cell shows
        found.setdefault(key, path.name)
    foreign = {k: v for k, v in found.items() if k != (profile.name, EVAL_PROTOCOL)}
    if foreign:
        (other, protocol), example = min(foreign.items())
        raise BadInputError(
            f"{out}: holds runs of profile {other!r} evaluated with protocol {protocol} (e.g. "
            f"runs/{example}); new runs of profile {profile.name!r} (protocol {EVAL_PROTOCOL}) "
            "would mix into them. Choose another --out, or leave --out out to use the profile's "
            "own folder"
        )


def _retired(row: dict, profile: Profile) -> bool:
    """Whether a stored run of another profile is shown neither by that profile nor by
    ``profile`` (an unknown profile's runs are not retired: nothing says what it shows)."""
    own = PROFILES.get(row["profile"])
    return own is not None and not own.shows(row) and not profile.shows(row)


def _check_submission(reference: str) -> None:
    """Make the potential (import errors are bad input) and print its invariance verdict."""
    from planshape.invariance import check_potential
    from planshape.shaping.potentials import make_potential

    make_potential(reference)
    report = check_potential(reference)
    verdict = "preserves" if report.preserved else "DOES NOT preserve"
    print(f"invariance: {reference} {verdict} the optimal policy on every toy MDP", flush=True)


def _profile_of(out: Path, rows: list[dict]) -> str:
    """The profile whose folder ``out`` is, else the last profile the rows name."""
    profile = profile_of_folder(out)
    return profile.name if profile is not None else sorted({r["profile"] for r in rows})[-1]


@subcommand("leaderboard", "render the leaderboard again from the stored results")
def _leaderboard(parser: argparse.ArgumentParser) -> Handler:
    parser.add_argument(
        "--out", type=Path, default=Path(RESULTS_ROOT), help="results and leaderboard folder"
    )
    parser.add_argument("--profile", default=None, help="profile named in the header")
    parser.add_argument("--json", action="store_true", help="print the summary as JSON")
    return run_leaderboard


def run_leaderboard(args: argparse.Namespace) -> int:
    """``planshape leaderboard``: render the page, summary and plots of ``--out`` again from its
    stored rows and print the summary table (``--json``: the summary as JSON)."""
    from planshape.results.cells import summarize
    from planshape.results.leaderboard import render_leaderboard, summary_table
    from planshape.results.render import json_ready
    from planshape.results.rows import load_rows

    rows = load_rows(args.out)
    if not rows:
        raise BadInputError(f"{args.out}: no stored results (runs/*.jsonl); run planshape bench")
    profile = get_profile(args.profile or _profile_of(args.out, rows))
    shown = profile.shown(rows)
    render_leaderboard(shown, args.out, profile.header(rows))
    if args.json:
        print(json.dumps(json_ready(summarize(shown)), indent=2, sort_keys=True, allow_nan=False))
    else:
        print(summary_table(shown))
    return 0
