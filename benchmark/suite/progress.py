"""How far a benchmark session has got: a line per finished run and, on a terminal, a bar.

The time left is weighted by each run's estimated cost
(:func:`planshape.harness.estimate.run_seconds`), never by the count of runs: a run found in
the store takes no time, so counting it would make the rest look fast, and a 100k-step SAC run
costs ten times a PPO run of the same budget. :class:`TimeLeft` holds that arithmetic;
:class:`BenchProgress` prints it (the lines go to any log; the tqdm bar only to a terminal).

>>> left = TimeLeft({"a": 10.0, "b": 30.0, "c": 0.0}, workers=2)
>>> left.before_any_run()      # nothing trained yet: the estimate itself, over two workers
20.0
>>> left.finished("c", elapsed=1.0, stored=True)    # stored: says nothing about the rest
20.0
>>> left.finished("a", elapsed=20.0, stored=False)  # 10 s of estimate took 20 s: 30 s -> 60 s
60.0
"""

from __future__ import annotations

import sys
from collections.abc import Mapping
from typing import IO, Any


class TimeLeft:
    """The time a session has left, from the estimated cost of its runs (item id → seconds;
    0 for a run already stored) and the wall time the trained ones took."""

    def __init__(self, cost: Mapping[str, float], workers: int = 1):
        self.cost = dict(cost)
        self.workers = max(int(workers), 1)
        self.finished_cost = 0.0
        self.trained_cost = 0.0

    def before_any_run(self) -> float:
        return self.remaining_cost() / self.workers

    def remaining_cost(self) -> float:
        return max(sum(self.cost.values()) - self.finished_cost, 0.0)

    def finished(self, name: str, *, elapsed: float, stored: bool) -> float:
        """Record that run ``name`` ended (``stored``: found in the store, not trained) after
        ``elapsed`` seconds of the session; return the seconds left."""
        cost = self.cost.get(name, 0.0)
        self.finished_cost += cost
        if not stored:
            self.trained_cost += cost
        if not self.trained_cost:
            return self.before_any_run()
        return elapsed / self.trained_cost * self.remaining_cost()


def clock(seconds: float) -> str:
    """``75`` → ``1m15s``; ``3700`` → ``1h01m``."""
    minutes, secs = divmod(int(seconds), 60)
    hours, minutes = divmod(minutes, 60)
    return f"{hours}h{minutes:02d}m" if hours else f"{minutes}m{secs:02d}s"


class BenchProgress:
    """The session's progress: :meth:`finished` returns the line to print for a run that
    ended and moves the bar (shown only when ``file`` is a terminal, unless ``bar`` says).

    >>> import io
    >>> progress = BenchProgress({"Reach-v1|sparse|PPO|seed0": 5.0}, workers=1, file=io.StringIO())
    >>> progress.finished("Reach-v1|sparse|PPO|seed0", "done", elapsed=4.0, stored=False)
    '[1/1] done    Reach-v1|sparse|PPO|seed0  elapsed 0m04s, about 0m00s left'
    >>> progress.close()
    """

    def __init__(
        self,
        cost: Mapping[str, float],
        *,
        workers: int = 1,
        file: IO[str] | None = None,
        bar: bool | None = None,
        started_at: float | None = None,
    ):
        """``cost``: item id → estimated seconds (0 for a stored run); ``started_at``: when the
        session began (``time.time()``), so that the bar's elapsed time is the session's."""
        from tqdm import tqdm

        self.total = len(cost)
        self.done = 0
        self.left = TimeLeft(cost, workers)
        self.bar = tqdm(
            total=self.total,
            desc="planshape bench",
            unit="run",
            file=file if file is not None else sys.stderr,
            disable=None if bar is None else not bar,  # None: only on a terminal
            dynamic_ncols=True,
            position=0,
            bar_format="{desc} {n_fmt}/{total_fmt} runs |{bar}| {elapsed} elapsed{postfix}",
            postfix=f"about {clock(self.left.before_any_run())} left",
        )
        if started_at is not None:
            self.bar.start_t = started_at

    def finished(self, name: str, outcome: str, *, elapsed: float, stored: bool) -> str:
        self.done += 1
        left = self.left.finished(name, elapsed=elapsed, stored=stored)
        self.bar.set_postfix_str(f"about {clock(left)} left", refresh=False)
        self.bar.update(1)
        return (
            f"[{self.done}/{self.total}] {outcome:7s} {name}  "
            f"elapsed {clock(elapsed)}, about {clock(left)} left"
        )

    def write(self, write_line: Any, line: str) -> None:
        """Print ``line`` with ``write_line`` (the terminal reporter's) above the bar."""
        self.bar.clear()
        write_line(line)
        self.bar.refresh()

    def close(self) -> None:
        self.bar.close()
