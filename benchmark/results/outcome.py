"""Shaping outcomes: whether a planning-derived potential reaches the hand-crafted dense reward
in one (task, algorithm) cell.

The question the benchmark exists to answer, asked of every cell the same way: does some
potential derived from a plan reach the dense reward's mean final success at the same budget,
and if not, does it learn faster (a larger area under its success curve)? Controls — the dense
reward's own distance made a potential, :data:`CONTROL_POTENTIALS` — are shaped entries but not
planning-derived, so they never answer it. :func:`shaping_outcome` reads a cell's summary rows
(one per entry, as :func:`~planshape.results.cells.summarize` makes them); what the answer is
worth is the budget check's to say (:mod:`planshape.results.verdict`): only a cell that
*decides* can show that shaping helps or does not.

Example:
    >>> rows = [
    ...     {"entry": "dense", "potential": None, "success_mean": 0.90, "curve_area_mean": 0.36},
    ...     {"entry": "plan-distance/stages", "potential": "plan-distance",
    ...      "success_mean": 0.64, "curve_area_mean": 0.47},
    ...     {"entry": "goal-distance/grid", "potential": "goal-distance",
    ...      "success_mean": 1.0, "curve_area_mean": 0.9},
    ... ]
    >>> outcome = shaping_outcome(rows)
    >>> outcome.status, outcome.entry
    ('faster', 'plan-distance/stages')
    >>> print(outcome.text)
    learns faster, ends lower: no planning-derived entry reaches dense's mean success at this \
budget (best plan-distance/stages 0.64, dense 0.90), but plan-distance/stages has the larger \
curve area (0.47 against dense's 0.36)
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any, Literal, NamedTuple

from planshape.results.cells import DENSE, REFERENCE_ENTRIES
from planshape.results.tables import short_task

__all__ = [
    "CONTROL_POTENTIALS",
    "ShapingOutcome",
    "planning_derived",
    "shaping_outcome",
    "tally",
]

#: shaped entries that are not planning-derived: the dense reward's distance as a potential
CONTROL_POTENTIALS: tuple[str, ...] = ("goal-distance",)

#: ``at-least-dense``: a planning-derived entry reaches dense's mean success at equal budget;
#: ``faster``: none does, but one has the larger curve area; ``below-dense``: neither;
#: ``none``: no dense or no planning-derived entry to compare
Status = Literal["at-least-dense", "faster", "below-dense", "none"]
#: the tolerance of "reaches": means over seeds of rates over episodes are sums of fractions
_TIE = 1e-9


class ShapingOutcome(NamedTuple):
    """One cell's answer: ``status`` (one of :data:`Status`), the planning-derived
    ``entry`` that gives it (None with ``"none"``), the sentence that says why (``text``) and
    that entry's probability of ending with a higher success rate than a dense run, with its
    interval (``p_improve_dense``: value, low, high; NaN where unknown): how much 5 seeds say
    about the difference."""

    status: Status
    entry: str | None
    text: str
    p_improve_dense: tuple[float, float, float] = (math.nan, math.nan, math.nan)


def planning_derived(row: Mapping[str, Any]) -> bool:
    """Whether a summary row's entry is shaped by a planning-derived potential: not sparse or
    dense, and not a control (:data:`CONTROL_POTENTIALS`).

    Example:
        >>> planning_derived({"entry": "plan-based/grid", "potential": "plan-based"})
        True
        >>> planning_derived({"entry": "goal-distance/grid", "potential": "goal-distance"})
        False
        >>> planning_derived({"entry": "dense", "potential": None})
        False
    """
    if row["entry"] in REFERENCE_ENTRIES:
        return False
    potential = row.get("potential") or str(row["entry"]).split("/", 1)[0]
    return potential not in CONTROL_POTENTIALS


def _value(row: Mapping[str, Any], column: str) -> float:
    value = row.get(column)
    return math.nan if value is None else float(value)


def _best(rows: Sequence[Mapping[str, Any]], column: str) -> Mapping[str, Any] | None:
    """The row with the largest ``column`` (NaN counts as lowest; first in order on ties)."""
    known = [r for r in rows if not math.isnan(_value(r, column))]
    return max(known, key=lambda r: _value(r, column)) if known else None


def shaping_outcome(rows: Sequence[Mapping[str, Any]]) -> ShapingOutcome:
    """The outcome of one (task, algorithm) cell from its summary rows (each with ``entry``,
    ``potential``, ``success_mean`` and ``curve_area_mean``; where they carry
    ``p_improve_dense`` and its bounds, the sentence ends with the entry's).

    ``at-least-dense``: the planning-derived entry with the highest mean final success reaches
    dense's. ``faster``: none does, but one has a larger curve area than dense (it learns
    faster over the budget and ends lower). ``below-dense``: neither. ``none``: the cell has no
    dense entry or no planning-derived one.

    Example:
        >>> shaping_outcome([
        ...     {"entry": "dense", "success_mean": 0.94, "curve_area_mean": 0.85},
        ...     {"entry": "plan-distance/stages", "success_mean": 0.94, "curve_area_mean": 0.63},
        ... ]).text
        "reaches dense: plan-distance/stages's mean success 0.94 against dense's 0.94 at \
equal budget"
    """
    status, entry, text = _judged(rows)
    row = next((r for r in rows if r["entry"] == entry), None)
    if row is None:
        return ShapingOutcome(status, entry, text)
    p = (
        _value(row, "p_improve_dense"),
        _value(row, "p_improve_dense_low"),
        _value(row, "p_improve_dense_high"),
    )
    if not math.isnan(p[0]):
        text += f"; P({entry} > dense) {p[0]:.2f}"
        text += "" if math.isnan(p[1]) else f" [{p[1]:.2f}, {p[2]:.2f}]"
    return ShapingOutcome(status, entry, text, p)


def _judged(rows: Sequence[Mapping[str, Any]]) -> tuple[Status, str | None, str]:
    """:func:`shaping_outcome`'s status, entry and sentence, before the probability."""
    dense = next((r for r in rows if r["entry"] == DENSE), None)
    planned = [r for r in rows if planning_derived(r)]
    if dense is None or not planned:
        missing = "dense" if dense is None else "planning-derived"
        return "none", None, f"no {missing} entry to compare"
    success, area = _value(dense, "success_mean"), _value(dense, "curve_area_mean")
    final = _best(planned, "success_mean")
    if final is not None and _value(final, "success_mean") >= success - _TIE:
        return (
            "at-least-dense",
            str(final["entry"]),
            f"reaches dense: {final['entry']}'s mean success "
            f"{_value(final, 'success_mean'):.2f} against dense's {success:.2f} at equal budget",
        )
    levels = (
        f"best {final['entry']} {_value(final, 'success_mean'):.2f}, dense {success:.2f}"
        if final is not None
        else f"dense {success:.2f}"
    )
    faster = _best(planned, "curve_area_mean")
    if faster is not None and _value(faster, "curve_area_mean") > area + _TIE:
        return (
            "faster",
            str(faster["entry"]),
            "learns faster, ends lower: no planning-derived entry reaches dense's mean success "
            f"at this budget ({levels}), but {faster['entry']} has the larger curve area "
            f"({_value(faster, 'curve_area_mean'):.2f} against dense's {area:.2f})",
        )
    best_area = (
        "best n/a"
        if faster is None
        else f"best {faster['entry']} {_value(faster, 'curve_area_mean'):.2f}"
    )
    return (
        "below-dense",
        None if final is None else str(final["entry"]),
        "below dense: no planning-derived entry reaches dense's mean success at this budget "
        f"({levels}) or its curve area ({best_area}, dense {area:.2f})",
    )


def tally(checks: Sequence[Mapping[str, Any]]) -> str:
    """The outcomes of the cells whose budget check *decides*, counted in one sentence, from
    :func:`planshape.results.verdict.budget_checks` (each with ``task``, ``algo``, ``status``
    and ``outcome``). Only those cells can show whether shaping helps.

    Example:
        >>> print(tally([
        ...     {"task": "planshape/Push-v1", "algo": "PPO", "status": "decides",
        ...      "outcome": "below-dense"},
        ...     {"task": "planshape/Push-v1", "algo": "SAC", "status": "decides",
        ...      "outcome": "at-least-dense"},
        ...     {"task": "planshape/Reach-v1", "algo": "PPO", "status": "no-verdict",
        ...      "outcome": "at-least-dense"},
        ... ]))
        Of the 2 cells whose budget check decides, a planning-derived potential reaches dense's \
mean success at equal budget in 1 (Push-v1 SAC), learns faster but ends lower in 0, and stays \
below dense in 1 (Push-v1 PPO). The 1 other cell cannot show whether shaping helps.
    """
    deciding = [c for c in checks if c["status"] == "decides"]
    others = len(checks) - len(deciding)
    rest = (
        f" The {others} other cell{'' if others == 1 else 's'} cannot show whether shaping helps."
        if others
        else ""
    )
    if not deciding:
        return f"No cell's budget check decides: no outcome here shows whether shaping helps.{rest}"

    def counted(status: str) -> str:
        names = [f"{short_task(c['task'])} {c['algo']}" for c in deciding if c["outcome"] == status]
        return f"{len(names)} ({', '.join(names)})" if names else "0"

    cells = f"{len(deciding)} cell{'' if len(deciding) == 1 else 's'}"
    unmatched = counted("none")
    without = "" if unmatched == "0" else f"; {unmatched} have nothing to compare"
    return (
        f"Of the {cells} whose budget check decides, a planning-derived potential reaches "
        f"dense's mean success at equal budget in {counted('at-least-dense')}, learns faster but "
        f"ends lower in {counted('faster')}, and stays below dense in {counted('below-dense')}"
        f"{without}.{rest}"
    )
