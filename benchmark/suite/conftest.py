"""The benchmark suite as a pytest plugin: one test item per training run.

Items are parametrized over task × reward entry × algorithm × seed from a profile, so the usual
pytest selection works (``-k "Reach and plan-based"``, ``-m PPO``). Each item looks its run up
in the results store, trains and evaluates it if it is missing, and stores its rows; a run that
crashes fails its item and the others go on. At the end the leaderboard is rendered from every
stored row and a summary table is printed.

Options: ``--profile``, ``--out``, ``--potential`` (repeatable: a submission), ``--tasks``,
``--seeds``, ``--executor`` (``local`` or ``ray``) and ``--address`` (a Ray cluster).
Run it through ``planshape bench`` (which adds a process pool) or directly with
``pytest benchmark/suite --profile smoke``.
"""

from __future__ import annotations

import time

import pytest

from planshape.suite.progress import BenchProgress
from planshape.suite.session import BUSY, BenchSession, end_with_parent


def pytest_addoption(parser: pytest.Parser) -> None:
    group = parser.getgroup("planshape", "planshape benchmark")
    group.addoption("--profile", default="default", help="benchmark profile (default: default)")
    group.addoption("--out", default="leaderboard", help="results and leaderboard folder")
    group.addoption(
        "--potential",
        action="append",
        default=[],
        help="extra potential to rank (id or module:attr); repeatable",
    )
    group.addoption("--tasks", default=None, help="comma-separated task ids or names to keep")
    group.addoption("--seeds", default=None, help="comma-separated seeds to keep")
    group.addoption(
        "--executor", default="local", choices=("local", "ray"), help="where runs execute"
    )
    group.addoption("--address", default=None, help="Ray cluster address (with --executor ray)")
    group.addoption("--no-render", action="store_true", help="do not render the leaderboard")
    group.addoption("--tensorboard", default=None, help="also log each trained run to this folder")


def pytest_configure(config: pytest.Config) -> None:
    session = BenchSession.from_options(config)
    config.stash[BenchSession.KEY] = session
    for marker in sorted(session.markers()):
        config.addinivalue_line("markers", f"{marker}: planshape benchmark selection")
    if hasattr(config, "workerinput"):  # an xdist worker of the process pool
        end_with_parent()
    else:  # the controller
        config.pluginmanager.register(ProgressLines(config), "planshape-progress")


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    if "run_key" in metafunc.fixturenames:
        session: BenchSession = metafunc.config.stash[BenchSession.KEY]
        keys = session.keys()
        params = [
            pytest.param(k, marks=[getattr(pytest.mark, m) for m in session.marks(k)]) for k in keys
        ]
        metafunc.parametrize("run_key", params, ids=[session.item_id(k) for k in keys])


@pytest.fixture(scope="session")
def bench(request: pytest.FixtureRequest) -> BenchSession:
    return request.config.stash[BenchSession.KEY]


class ProgressLines:
    """After each run a line: how many are done, the time spent and an estimate of the time
    left (:class:`planshape.suite.progress.TimeLeft`: weighted by each run's estimated cost, so
    neither runs found in the store nor the order of cheap and dear runs distort it); on a
    terminal, a progress bar for the session as a whole below the lines."""

    def __init__(self, config: pytest.Config):
        self.config = config
        self.started = time.monotonic()
        self.started_at = time.time()  # the bar's clock (tqdm's) starts with the session too
        self.cost: dict[str, float] = {}
        self.progress: BenchProgress | None = None

    def pytest_sessionstart(self, session: pytest.Session) -> None:
        bench: BenchSession = self.config.stash[BenchSession.KEY]
        bench.prepare()
        self.cost = bench.estimated_seconds()

    @pytest.hookimpl(trylast=True)
    def pytest_collection_modifyitems(self, items: list[pytest.Item]) -> None:
        self._selected([item.nodeid for item in items])

    @pytest.hookimpl(optionalhook=True)
    def pytest_xdist_node_collection_finished(self, node, ids: list[str]) -> None:
        self._selected(ids)  # with a process pool the controller collects nothing itself

    def _selected(self, nodeids: list[str]) -> None:
        """Count and cost only the runs selected (``-k`` deselects some of the profile's)."""
        if self.progress is not None:  # every worker of a pool reports the same collection
            return
        names = {_run_name(nodeid) for nodeid in nodeids}
        workers = getattr(self.config.option, "numprocesses", None) or 1
        self.progress = BenchProgress(
            {name: self.cost.get(name, 0.0) for name in names},
            workers=int(workers),
            started_at=self.started_at,
        )

    @pytest.hookimpl(tryfirst=True)
    def pytest_report_teststatus(self, report: pytest.TestReport, config: pytest.Config):
        """No progress letter per run ("." or "s"): the run's own line says how it ended."""
        if report.when == "call" or (report.when == "setup" and not report.passed):
            return report.outcome, "", report.outcome.upper()
        return None

    def pytest_runtest_logreport(self, report: pytest.TestReport) -> None:
        finished = report.when == "call" or (report.when == "setup" and not report.passed)
        if not finished or self.progress is None:
            return
        outcome = "done" if report.passed else "stored" if report.skipped else report.outcome
        if report.skipped and any(tuple(p) == BUSY for p in report.user_properties):
            outcome = "busy"  # another benchmark on this folder is training it
        line = self.progress.finished(
            _run_name(report.nodeid),
            outcome,
            elapsed=time.monotonic() - self.started,
            stored=report.skipped,  # already stored: takes no time, says nothing of the rest
        )
        reporter = self.config.pluginmanager.get_plugin("terminalreporter")
        if reporter is not None:
            self.progress.write(reporter.write_line, line)

    def pytest_terminal_summary(self, terminalreporter) -> None:
        if self.progress is None or not self.progress.total:
            return  # the selection matched no run: nothing is rendered
        self.progress.close()
        text = self.config.stash[BenchSession.KEY].finish()
        if text:
            terminalreporter.write_sep("=", "planshape leaderboard")
            terminalreporter.write_line(text)


def _run_name(nodeid: str) -> str:
    """The run's item id (``Reach-v1|sparse|PPO|seed0``) of a test node id."""
    return nodeid.split("[", 1)[-1].rstrip("]")
