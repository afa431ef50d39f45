"""Budget checks: whether one (task, algorithm) cell can carry a verdict on shaping.

A comparison of rewards says something only where the budget separates them. A cell in which
sparse and dense both fail cannot show that a potential helps (every entry may fail for want of
steps), and a cell in which sparse already succeeds leaves a potential little to win. The rule
planshape's profiles are held to: every entry has at least :data:`MIN_SEEDS` seeds, and the
hand-crafted dense reward reaches :data:`SOLVED` mean final success while sparse does not — or,
where dense fails by design (maze-reach's wall), some shaped entry does while sparse does not.

:func:`budget_check` applies that rule to a cell's summary rows (one per entry, as
:func:`~planshape.results.cells.summarize` makes them) and says in one sentence what the cell
can decide; the leaderboard prints it under each cell's heading.

Example:
    >>> rows = [
    ...     {"entry": "sparse", "n_seeds": 5, "success_mean": 0.4},
    ...     {"entry": "dense", "n_seeds": 5, "success_mean": 0.62},
    ...     {"entry": "plan-based/stages", "n_seeds": 5, "success_mean": 0.36},
    ... ]
    >>> check = budget_check(rows)
    >>> check.status
    'no-verdict'
    >>> print(check.text)
    no verdict: no entry reaches 0.8 mean success (dense 0.62, sparse 0.40, best shaped \
plan-based/stages 0.36); the budget is too small to show whether shaping helps
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any, Literal, NamedTuple

from planshape.results.cells import DENSE, REFERENCE_ENTRIES, SPARSE
from planshape.results.outcome import shaping_outcome
from planshape.results.tables import by_task_and_algo

__all__ = ["MIN_SEEDS", "SOLVED", "BudgetCheck", "budget_check", "budget_checks"]

#: mean final success at which an entry counts as solving the task at the budget
SOLVED = 0.8
#: the fewest seeds per entry from which a cell's comparison is reported as evidence
MIN_SEEDS = 5

Status = Literal["decides", "separates-little", "no-verdict"]


class BudgetCheck(NamedTuple):
    """What a cell can decide: ``status`` and the sentence that says why (``text``)."""

    status: Status
    text: str


def _success(rows: Sequence[Mapping[str, Any]], entry: str) -> float | None:
    return next((float(r["success_mean"]) for r in rows if r["entry"] == entry), None)


def _shaped_best(rows: Sequence[Mapping[str, Any]]) -> tuple[str, float] | None:
    shaped = [r for r in rows if r["entry"] not in REFERENCE_ENTRIES]
    if not shaped:
        return None
    best = max(shaped, key=lambda r: float(r["success_mean"]))
    return str(best["entry"]), float(best["success_mean"])


def _levels(dense: float | None, sparse: float | None, best: tuple[str, float] | None) -> str:
    references = ((DENSE, dense), (SPARSE, sparse))
    parts = [f"{name} {value:.2f}" for name, value in references if value is not None]
    if best is not None:
        parts.append(f"best shaped {best[0]} {best[1]:.2f}")
    return ", ".join(parts)


def _few_seeds(rows: Sequence[Mapping[str, Any]]) -> BudgetCheck | None:
    few = sorted({int(r["n_seeds"]) for r in rows if int(r["n_seeds"]) < MIN_SEEDS})
    if not few:
        return None
    seeds = str(few[0]) if len(few) == 1 else f"{few[0]} to {few[-1]}"
    return BudgetCheck(
        "no-verdict",
        f"no verdict: some entries have {seeds} seeds, fewer than {MIN_SEEDS}; "
        "their intervals say too little to rank them",
    )


def budget_check(rows: Sequence[Mapping[str, Any]]) -> BudgetCheck:
    """The budget check of one (task, algorithm) cell, from its summary rows (one per entry,
    each with ``entry``, ``n_seeds`` and ``success_mean``).

    ``decides``: dense reaches :data:`SOLVED` and sparse does not, or dense falls short and a
    shaped entry solves the task where sparse does not (the maze-reach case).
    ``separates-little``: sparse reaches :data:`SOLVED` too, so a potential can gain little.
    ``no-verdict``: an entry has fewer than :data:`MIN_SEEDS` seeds, there is no dense or no
    sparse entry (without sparse, nothing shows that the task is not solved without shaping),
    or no entry solves the task at this budget.

    Example:
        >>> check = budget_check([
        ...     {"entry": "sparse", "n_seeds": 5, "success_mean": 0.0},
        ...     {"entry": "dense", "n_seeds": 5, "success_mean": 0.0},
        ...     {"entry": "plan-distance/grid", "n_seeds": 5, "success_mean": 1.0},
        ... ])
        >>> check.status
        'decides'
        >>> print(check.text)
        decides: dense ends short of 0.8 (dense 0.00, sparse 0.00, best shaped ...), but a \
shaped entry solves the task where sparse does not
    """
    few = _few_seeds(rows)
    if few is not None:
        return few
    dense, sparse, best = _success(rows, DENSE), _success(rows, SPARSE), _shaped_best(rows)
    levels = _levels(dense, sparse, best)
    if dense is None:
        return BudgetCheck(
            "no-verdict", f"no verdict: no dense entry to check the budget against ({levels})"
        )
    if sparse is None:
        return BudgetCheck(
            "no-verdict",
            f"no verdict: no sparse entry to show whether the budget separates the rewards "
            f"({levels})",
        )
    if sparse is not None and sparse >= SOLVED:
        return BudgetCheck(
            "separates-little",
            f"separates little: sparse already reaches {SOLVED} mean success ({levels}), "
            "so a potential has little to gain at this budget",
        )
    if dense >= SOLVED:
        return BudgetCheck(
            "decides",
            f"decides: dense reaches {SOLVED} mean success and sparse does not ({levels})",
        )
    if best is not None and best[1] >= SOLVED:
        return BudgetCheck(
            "decides",
            f"decides: dense ends short of {SOLVED} ({levels}), but a shaped entry solves the "
            "task where sparse does not",
        )
    return BudgetCheck(
        "no-verdict",
        f"no verdict: no entry reaches {SOLVED} mean success ({levels}); the budget is too "
        "small to show whether shaping helps",
    )


def budget_checks(summary: Sequence[Mapping[str, Any]]) -> list[dict[str, Any]]:
    """The budget check of every (task, algorithm) cell in ``summary`` (rows of
    :func:`~planshape.results.cells.summarize`, grouped as the leaderboard groups them), sorted
    by task and algorithm: ``task``, ``algo``, ``budget``, ``status``, ``text``, and the cell's
    shaping outcome (:func:`~planshape.results.outcome.shaping_outcome`): ``outcome``,
    ``outcome_entry``, ``outcome_text`` and ``outcome_p_improve_dense`` (with ``_low`` and
    ``_high``).

    Example:
        >>> rows = [
        ...     {"task": "t", "algo": "PPO", "budget": 100, "entry": entry, "n_seeds": 5,
        ...      "success_mean": success, "success_iqm": success, "distance_iqm": 0.1}
        ...     for entry, success in (("dense", 0.9), ("sparse", 0.1))
        ... ]
        >>> [(c["task"], c["algo"], c["status"]) for c in budget_checks(rows)]
        [('t', 'PPO', 'decides')]
    """
    checks = []
    for task, by_algo in by_task_and_algo(summary).items():
        for algo, rows in by_algo.items():
            outcome = shaping_outcome(rows)
            p, low, high = outcome.p_improve_dense
            checks.append(
                {
                    "task": task,
                    "algo": algo,
                    "budget": rows[0].get("budget"),
                    **budget_check(rows)._asdict(),
                    "outcome": outcome.status,
                    "outcome_entry": outcome.entry,
                    "outcome_text": outcome.text,
                    "outcome_p_improve_dense": p,
                    "outcome_p_improve_dense_low": low,
                    "outcome_p_improve_dense_high": high,
                }
            )
    return checks
