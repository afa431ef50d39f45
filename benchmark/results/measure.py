"""Success measures: which episodes a profile counts as solved.

Every evaluation point records two success rates of the deterministic policy (stored rows,
:class:`~planshape.results.rows.StoredRow`): ``success_rate``, the task's success flag on the
episode's **last** step, and ``success_any_rate``, the flag on **any** step. No task ends its
episode on success, so a policy that reaches the goal and drifts off it before the horizon is
solved by the second and unsolved by the first. The planar tasks are defined by the first (the
task is to reach the goal and stay there). MetaWorld's benchmark counts an episode as solved
when the flag is set at any point of its 500 steps ("Evaluation" in MetaWorld's
documentation).

A profile names its measure (:attr:`planshape.harness.profiles.Profile.success_measure`) and
:func:`measured` rewrites its stored rows once, before anything is scored, so that every
statistic, table, plot and budget check of the leaderboard counts success the same way:

* ``"end"`` — rows unchanged;
* ``"any-step"`` — ``success_rate`` becomes the any-step rate and the end-of-episode rate moves
  to ``success_end_rate`` (shown beside it). Runs stored before the any-step rate was recorded
  cannot be counted so: a (task, algorithm) cell with one such run keeps the end-of-episode
  rate for all of its runs, so that no comparison mixes the two, and is reported until its runs
  are trained again.

Example:
    >>> row = {"run_id": "a", "task": "t", "algo": "SAC", "success_rate": 0.2,
    ...        "success_any_rate": 0.9, "evaluation": "10 deterministic episodes"}
    >>> old = {"run_id": "b", "task": "u", "algo": "SAC", "success_rate": 0.5}
    >>> rows, at_end = measured([row, old], "any-step")
    >>> [r["success_rate"] for r in rows], rows[0]["success_end_rate"], at_end
    ([0.9, 0.5], 0.2, {('u', 'SAC'): ['b']})
    >>> measured([row, old], "end") == ([row, old], {})
    True
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Mapping, Sequence
from typing import Any, Literal, get_args

__all__ = ["SUCCESS_MEASURES", "SuccessMeasure", "describe", "measured"]

SuccessMeasure = Literal["end", "any-step"]
#: the measures a profile may name
SUCCESS_MEASURES: tuple[str, ...] = get_args(SuccessMeasure)

_DESCRIPTIONS = {
    "end": "success counts an episode whose success flag is set on its last step",
    "any-step": (
        "success counts an episode whose success flag is set at any step (MetaWorld's own "
        "protocol); the end-of-episode rate is shown beside it"
    ),
}


def describe(measure: str) -> str:
    """The measure in words, as the leaderboard states it.

    Example:
        >>> describe("end")
        'success counts an episode whose success flag is set on its last step'
    """
    if measure not in _DESCRIPTIONS:
        raise ValueError(
            f"unknown success measure {measure!r}; use one of {', '.join(SUCCESS_MEASURES)}"
        )
    return _DESCRIPTIONS[measure]


def _any_step(row: Mapping[str, Any]) -> dict[str, Any]:
    out = {k: v for k, v in row.items() if k != "success_any_rate"}
    out["success_end_rate"] = row["success_rate"]
    out["success_rate"] = row["success_any_rate"]
    if "evaluation" in row:
        out["evaluation"] = f"{row['evaluation']}; {describe('any-step')}"
    return out


Cell = tuple[str, str]


def measured(
    rows: Sequence[Mapping[str, Any]], measure: str
) -> tuple[list[Mapping[str, Any]], dict[Cell, list[str]]]:
    """``rows`` with ``success_rate`` counted by ``measure``, and the (task, algorithm) cells
    left counted at the episode's end, each with the ids (sorted) of its runs that lack the
    any-step rate.

    Example:
        >>> rows = [{"run_id": "a", "task": "t", "algo": "SAC", "success_rate": 1.0},
        ...         {"run_id": "c", "task": "t", "algo": "SAC", "success_rate": 0.0,
        ...          "success_any_rate": 1.0}]
        >>> shown, at_end = measured(rows, "any-step")
        >>> [r["success_rate"] for r in shown], at_end
        ([1.0, 0.0], {('t', 'SAC'): ['a']})
    """
    describe(measure)  # rejects an unknown measure
    if measure == "end":
        return list(rows), {}
    lacking: dict[Cell, set[str]] = defaultdict(set)
    for r in rows:
        if "success_any_rate" not in r:
            lacking[(str(r["task"]), str(r["algo"]))].add(str(r["run_id"]))
    out = [r if (r["task"], r["algo"]) in lacking else _any_step(r) for r in rows]
    return out, {cell: sorted(ids) for cell, ids in sorted(lacking.items())}
