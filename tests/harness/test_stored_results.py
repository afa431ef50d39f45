"""Stored results are never damaged: damaged run files are refused before anything trains, a
selection that matches nothing changes nothing, rendering is atomic and byte-stable, a live
writer's temporary file survives another benchmark's start, and signals end the pool."""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from planshape.cli import main
from planshape.harness.store import ResultStore, write_atomic
from tests.results.synthetic import store_run

SUBMISSION = "tests.submission.example:ProgressAndDistance"
ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def stored(tmp_path_factory) -> Path:
    """A results folder after one real smoke benchmark (with a submission)."""
    out = tmp_path_factory.mktemp("stored")
    command = ["bench", "--profile", "smoke", "--out", str(out), "--workers", "1"]
    assert main([*command, "--potential", SUBMISSION]) == 0
    return out


def snapshot(folder: Path) -> dict[str, tuple[bytes, int]]:
    """Every file under ``folder``: its bytes and modification time."""
    return {
        str(p.relative_to(folder)): (p.read_bytes(), p.stat().st_mtime_ns)
        for p in sorted(folder.rglob("*"))
        if p.is_file()
    }


@pytest.fixture
def copy_of(stored, tmp_path) -> Path:
    out = tmp_path / "copy"
    shutil.copytree(stored, out)
    return out


def test_rendering_again_leaves_every_file_as_it_was(stored, capsys):
    before = snapshot(stored)
    assert main(["leaderboard", "--out", str(stored)]) == 0
    command = ["bench", "--profile", "smoke", "--out", str(stored), "--workers", "1"]
    assert main([*command, "--potential", SUBMISSION]) == 0
    assert snapshot(stored) == before  # bytes and modification times
    board = (stored / "LEADERBOARD.md").read_text()
    # the header is the one command that reproduces the rows, whoever rendered it
    assert f"planshape bench --profile smoke --potential {SUBMISSION}" in board


@pytest.mark.parametrize(
    ("damage", "message"),
    [
        (lambda text: "", "empty: no result rows"),
        (lambda text: "".join(text.splitlines(True)[:-1]), "truncated: the last row (step"),
        (lambda text: text[: len(text) // 2], "not a JSON row"),
        (lambda text: b"\xff\xfe" + text.encode(), "not UTF-8 text (byte 0)"),
    ],
    ids=["empty", "truncated", "cut-mid-row", "not-utf8"],
)
def test_a_damaged_run_file_is_refused_before_anything_trains(copy_of, capsys, damage, message):
    victim = sorted((copy_of / "runs").glob("*.jsonl"))[0]
    damaged = damage(victim.read_text())
    if isinstance(damaged, bytes):
        victim.write_bytes(damaged)
    else:
        victim.write_text(damaged)
    before = snapshot(copy_of)
    for command in (
        ["bench", "--profile", "smoke", "--out", str(copy_of), "--workers", "1"],
        ["bench", "--profile", "smoke", "--out", str(copy_of), "--dry-run"],
        ["leaderboard", "--out", str(copy_of)],
    ):
        assert main(command) == 2
        err = capsys.readouterr().err
        assert victim.name in err and message in err, err
        assert "Traceback" not in err and "move the file out of runs/" in err
    assert snapshot(copy_of) == before


def test_a_file_holding_another_run_is_not_taken_for_its_name(copy_of, capsys):
    runs = sorted((copy_of / "runs").glob("*.jsonl"))
    shutil.copy(runs[1], runs[0])
    assert main(["bench", "--profile", "smoke", "--out", str(copy_of), "--workers", "1"]) == 2
    assert f"holds run {runs[1].stem!r}" in capsys.readouterr().err


def test_a_selection_that_matches_nothing_changes_nothing(copy_of, capsys):
    before = snapshot(copy_of)
    base = ["bench", "--profile", "smoke", "--out", str(copy_of), "--workers", "1"]
    for extra, message in (
        (["-k", "no_such_run"], "the selection matches no run"),
        (["--seeds", "99"], "select no run of profile 'smoke'"),
        (["--seeds", "-1"], "a seed is a non-negative integer, not -1"),
    ):
        assert main([*base, *extra]) == 2
        assert message in capsys.readouterr().err
    # a dry run tells a -k that matches nothing from a selection whose runs are all stored
    assert main([*base, "--dry-run", "-k", "no_such_run"]) == 2
    assert "-k 'no_such_run' selects none of profile 'smoke'" in capsys.readouterr().err
    assert main([*base, "--dry-run", "-k", "dense"]) == 0
    assert snapshot(copy_of) == before


def test_bad_output_folders_and_worker_counts_exit_2(tmp_path, capsys):
    a_file = tmp_path / "results.txt"
    a_file.write_text("not a folder")
    for out, extra, message in (
        (a_file, [], "is a file, not a folder"),
        (a_file / "below", [], "is a file, not a folder"),
        (tmp_path / "new", ["--workers", "0"], "at least 1, not 0"),
    ):
        assert main(["bench", "--profile", "smoke", "--out", str(out), *extra]) == 2
        err = capsys.readouterr().err
        assert message in err and "Traceback" not in err and "INTERNALERROR" not in err
    assert a_file.read_text() == "not a folder" and not (tmp_path / "new").exists()


def test_starting_benchmark_removes_only_the_temporary_files_of_dead_writers(tmp_path):
    store = ResultStore(tmp_path)
    store.runs.mkdir()
    finished = subprocess.run([sys.executable, "-c", "pass"], check=True)
    assert finished.returncode == 0
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    live = store.runs / f".abc.{os.getpid()}.x1.tmp"
    killed = store.runs / f".abc.{dead.pid}.x2.tmp"
    unnamed = store.runs / ".abc.x3.tmp"  # written before names carried the writer
    for path in (live, killed, unnamed):
        path.write_text("{")
    assert store.clean_partial() == 2
    assert live.exists() and not killed.exists() and not unnamed.exists()


def test_atomic_writes_name_their_writer_and_skip_unchanged_content(tmp_path):
    path = write_atomic(tmp_path / "board.md", "one")
    stamp = path.stat().st_mtime_ns
    time.sleep(0.01)
    write_atomic(path, "one")
    assert path.stat().st_mtime_ns == stamp
    write_atomic(path, "two")
    assert path.read_text() == "two" and not list(tmp_path.glob(".*.tmp"))


def _descendants(pid: int) -> set[int]:
    """Every live descendant of ``pid`` (from /proc)."""
    children: dict[int, list[int]] = {}
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue
        if fields[0] != "Z":  # zombies are gone, only not yet reaped
            children.setdefault(int(fields[1]), []).append(int(stat.parent.name))
    found, todo = set(), [pid]
    while todo:
        for child in children.get(todo.pop(), []):
            found.add(child)
            todo.append(child)
    return found


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
@pytest.mark.parametrize("number", [signal.SIGTERM, signal.SIGINT], ids=["SIGTERM", "SIGINT"])
def test_a_signal_ends_every_process_of_the_benchmark(tmp_path, number):
    out = tmp_path / "out"
    # as from a terminal: a process started by a pool worker inherits SIGINT ignored
    code = (
        "import signal, sys; signal.signal(signal.SIGINT, signal.default_int_handler); "
        "from planshape.cli import main; sys.exit(main())"
    )
    selection = ["--tasks", "reach", "--seeds", "0", "-k", "dense and PPO"]
    bench = subprocess.Popen(
        [sys.executable, "-c", code, "bench", *selection, "--out", str(out), "--workers", "2"],
        cwd=ROOT,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )
    deadline = time.monotonic() + 120
    while len(_workers(bench.pid)) < 2 and time.monotonic() < deadline:
        time.sleep(0.2)
    pool = _workers(bench.pid)
    assert len(pool) >= 2, "the process pool did not start"
    while not (out / "invariance.json").exists() and time.monotonic() < deadline:
        time.sleep(0.2)  # the controller has checked the potentials: the pool trains next
    time.sleep(3)  # into training
    bench.send_signal(number)
    output, _ = bench.communicate(timeout=120)
    assert bench.returncode == 128 + number, output
    assert "Traceback" not in output
    deadline = time.monotonic() + 30
    while _descendants_alive(pool) and time.monotonic() < deadline:
        time.sleep(0.2)
    assert not _descendants_alive(pool), output
    assert not list(out.glob("runs/*.jsonl"))  # the interrupted run is not stored


def _workers(pid: int) -> set[int]:
    """The pool's worker processes among ``pid``'s descendants (execnet's bootstrap line), not
    short-lived helpers such as ``git describe``."""
    found = set()
    for child in _descendants(pid):
        try:
            command = Path(f"/proc/{child}/cmdline").read_bytes()
        except OSError:
            continue
        if b"sys.stdin.readline" in command:
            found.add(child)
    return found


def _descendants_alive(pids: set[int]) -> set[int]:
    alive = set()
    for pid in pids:
        try:
            state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
        except OSError:
            continue
        if state != "Z":
            alive.add(pid)
    return alive


def test_a_larger_profile_starts_from_the_same_runs_of_a_smaller_one(tmp_path):
    """Run ids hash what determines the numbers, not the profile: the default profile's run of
    a key is the planar profile's run of it, and counts as stored there; a run the planar
    profile does not have is still refused."""
    from planshape.errors import BadInputError
    from planshape.harness.bench import check_store
    from planshape.harness.profiles import PROFILES, RunKey
    from planshape.harness.runner import RunSpec

    default, planar = PROFILES["default"], PROFILES["planar"]
    key = RunKey("planshape/Reach-v1", "sparse", "PPO", 0, 245_760)
    assert key in set(default.runs()) and key in set(planar.runs())
    store_run(tmp_path, key, PROFILES["default"])
    check_store(tmp_path, planar)  # the same run
    assert ResultStore(tmp_path).has(
        RunSpec.create(key, "planar", planar.eval_every, planar.eval_episodes).run_id
    )
    with pytest.raises(BadInputError, match="holds runs of profile 'default'"):
        check_store(tmp_path, PROFILES["smoke"])


def test_a_run_no_profile_shows_any_more_does_not_block_a_folder(tmp_path):
    """A run the default profile stored, copied into the planar profile's folder when it was
    a run of both, whose budget (or settings) both profiles have since replaced, mixes into no
    cell: the folder stays resumable. One the default profile still shows is refused."""
    from planshape.errors import BadInputError
    from planshape.harness.bench import check_store
    from planshape.harness.profiles import PROFILES, RunKey

    planar = PROFILES["planar"]
    store_run(
        tmp_path, RunKey("planshape/Push-v1", "dense", "SBX-SAC", 0, 100_000), PROFILES["default"]
    )
    check_store(tmp_path, planar)  # 100,000 steps: push's SAC budget before 150,000
    store_run(
        tmp_path, RunKey("planshape/Push-v1", "dense", "SBX-SAC", 0, 150_000), PROFILES["default"]
    )
    check_store(tmp_path, planar)  # one of planar's own runs
    store_run(
        tmp_path, RunKey("planshape/Reach-v1", "sparse", "PPO", 0, 245_760), PROFILES["default"]
    )
    with pytest.raises(BadInputError, match="holds runs of profile 'default'"):
        check_store(tmp_path, PROFILES["smoke"])  # shown by the default profile


def test_a_killed_benchmarks_claim_ends_with_it(tmp_path):
    """The claim on a run is the operating system's lock: a holder killed with SIGKILL (no
    cleanup runs) releases it, and a claim held by a live process is refused."""
    store = ResultStore(tmp_path)
    holder = subprocess.Popen(
        [
            sys.executable,
            "-c",
            "import sys, time; from planshape.harness.store import ResultStore\n"
            f"with ResultStore({str(tmp_path)!r}).claim('abc') as mine:\n"
            "    print(mine, flush=True); time.sleep(60)",
        ],
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        assert holder.stdout.readline().strip() == "True"
        with store.claim("abc") as mine:
            assert not mine  # a live process holds it
    finally:
        holder.send_signal(signal.SIGKILL)
        holder.wait()
    time.sleep(0.1)
    with store.claim("abc") as mine:
        assert mine
