"""Plan a PDDL model once, validate it, and remember it: the planning stage's entry point.

Example:
    >>> from planshape.planning.grid import grid_pddl
    >>> grid = grid_pddl(2, 3, start=(0, 0), goal=(1, 2))
    >>> plan = solve_text(grid.domain, grid.problem, cache_dir=False)  # doctest: +SKIP
    >>> plan.length, plan.cost, sorted(plan.subgoals.fluents[-1])  # doctest: +SKIP
    (3, 3, [('robot_at', 'cell_1_2')])
"""

from __future__ import annotations

import logging
from pathlib import Path
from typing import Literal

from planshape.planning.cache import PlanCache, cache_key, default_cache_dir
from planshape.planning.fast_downward import DEFAULT_SEARCH, plan_text, search_arguments
from planshape.planning.model import Plan, SubgoalStates
from planshape.planning.parse import decode_pddl, parse_task, read_pddl_bytes
from planshape.planning.subgoals import subgoal_sequence

__all__ = ["CacheDir", "solve", "solve_text"]

log = logging.getLogger("planshape.planning")

#: ``None``: the default directory (``$PLANSHAPE_CACHE_DIR`` or ``~/.cache/planshape/plans``);
#: ``False``: no cache; a path: that directory.
CacheDir = str | Path | None | Literal[False]


def solve(
    domain: str | Path,
    problem: str | Path,
    *,
    search: str = DEFAULT_SEARCH,
    timeout: float = 60.0,
    cache_dir: CacheDir = None,
) -> Plan:
    """Plan ``problem`` with Fast Downward, validate the plan and return it with its subgoals.

    A cached plan for the same domain text, problem text and search is returned without
    parsing or planning (``plan.from_cache`` is then true and ``plan.planner_seconds`` 0).
    ``timeout`` bounds Fast Downward's wall-clock time; ``search`` names an entry of
    :data:`SEARCHES`; ``cache_dir`` is a directory, ``None`` for the default one
    (``$PLANSHAPE_CACHE_DIR`` or ``~/.cache/planshape/plans``) or ``False`` for no cache.

    Raises :class:`PDDLError` (bad or missing file), :class:`UnknownIdError` (search name),
    :class:`UnsolvableError`, :class:`PlannerTimeoutError`, :class:`PlannerMissingError`,
    :class:`PlannerError` and :class:`PlanValidationError` (the plan does not execute on the
    model: a bug to report).

    Example:
        >>> plan = solve("pddl/maze/domain.pddl", "pddl/maze/grid.pddl")  # doctest: +SKIP
        >>> [str(a) for a in plan.actions[:2]]  # doctest: +SKIP
        ['(move cell_0_0 cell_0_1)', '(move cell_0_1 cell_0_2)']
    """
    search_arguments(search)  # an unknown name fails before any file is read
    return _solve(
        read_pddl_bytes(domain),
        read_pddl_bytes(problem),
        search=search,
        timeout=timeout,
        cache_dir=cache_dir,
        domain_file=str(domain),
        problem_file=str(problem),
    )


def solve_text(
    domain_text: str,
    problem_text: str,
    *,
    search: str = DEFAULT_SEARCH,
    timeout: float = 60.0,
    cache_dir: CacheDir = None,
    domain_file: str = "<domain>",
    problem_file: str = "<problem>",
) -> Plan:
    """:func:`solve` on PDDL text (e.g. from :func:`planshape.planning.grid.grid_pddl`)."""
    search_arguments(search)
    return _solve(
        domain_text.encode("utf-8"),
        problem_text.encode("utf-8"),
        search=search,
        timeout=timeout,
        cache_dir=cache_dir,
        domain_file=domain_file,
        problem_file=problem_file,
    )


def _solve(
    domain: bytes,
    problem: bytes,
    *,
    search: str,
    timeout: float,
    cache_dir: CacheDir,
    domain_file: str,
    problem_file: str,
) -> Plan:
    cache = None
    if cache_dir is not False:  # the cache is keyed by bytes: a hit decodes nothing
        cache = PlanCache(default_cache_dir() if cache_dir is None else Path(cache_dir))
        key = cache_key(domain, problem, search)
        hit = cache.load(key)
        if hit is not None:
            return hit
    domain_text = decode_pddl(domain, domain_file)
    problem_text = decode_pddl(problem, problem_file)
    task = parse_task(domain_text, problem_text, domain_file, problem_file)
    result = plan_text(
        domain_text,
        problem_text,
        search=search,
        timeout=timeout,
        domain_file=domain_file,
        problem_file=problem_file,
    )
    states = subgoal_sequence(task, result.actions)
    plan = Plan(
        result.actions,
        SubgoalStates.from_states(states, task.static_predicates),
        result.cost,
        search,
        planner_seconds=result.seconds,
    )
    if cache is not None:
        try:
            cache.store(key, plan, domain_file=domain_file, problem_file=problem_file)
        except OSError as err:
            log.warning("could not write the plan cache in %s (%s)", cache.directory, err)
    return plan
