"""The planning stage: PDDL in, a validated plan and its subgoal states out.

``domain.pddl + problem.pddl --Fast Downward--> plan --apply from :init--> Ŝ = [ŝ0 … ŝn]``,
cached on disk by content hash.

Example:
    >>> from planshape.planning import grid_pddl, parse_task, subgoal_sequence
    >>> grid = grid_pddl(1, 2, start=(0, 0), goal=(0, 1))
    >>> task = parse_task(grid.domain, grid.problem)
    >>> len(subgoal_sequence(task, ["(move cell_0_0 cell_0_1)"]))
    2
    >>> plan = solve("domain.pddl", "problem.pddl", search="lama-first")  # doctest: +SKIP
"""

from planshape.planning.cache import (
    CACHE_DIR_ENV,
    CACHE_FORMAT,
    PlanCache,
    cache_key,
    default_cache_dir,
)
from planshape.planning.fast_downward import (
    DEFAULT_SEARCH,
    DRIVER_ENV,
    OPTIMAL_SEARCHES,
    SEARCHES,
    PlannerResult,
    find_driver,
    parse_plan,
    plan_text,
    run_fast_downward,
    search_arguments,
)
from planshape.planning.grid import Cell, GridNames, GridPddl, cell_name, grid_domain, grid_pddl
from planshape.planning.grounding import GroundOperator, GroundTask, ground_task
from planshape.planning.model import (
    AbstractState,
    ActionSchema,
    Atom,
    GroundAction,
    PddlTask,
    Plan,
    PredicateSignature,
    SubgoalStates,
    format_atom,
    parse_atom,
)
from planshape.planning.parse import load_task, parse_task, read_pddl
from planshape.planning.relaxed import h_add, h_ff, h_max
from planshape.planning.solve import CacheDir, solve, solve_text
from planshape.planning.statespace import GoalDistances
from planshape.planning.subgoals import apply_action, subgoal_sequence

__all__ = [
    "CACHE_DIR_ENV",
    "CACHE_FORMAT",
    "DEFAULT_SEARCH",
    "DRIVER_ENV",
    "OPTIMAL_SEARCHES",
    "SEARCHES",
    "AbstractState",
    "ActionSchema",
    "Atom",
    "CacheDir",
    "Cell",
    "GoalDistances",
    "GridNames",
    "GridPddl",
    "GroundAction",
    "GroundOperator",
    "GroundTask",
    "PddlTask",
    "Plan",
    "PlanCache",
    "PlannerResult",
    "PredicateSignature",
    "SubgoalStates",
    "apply_action",
    "cache_key",
    "cell_name",
    "default_cache_dir",
    "find_driver",
    "format_atom",
    "grid_domain",
    "grid_pddl",
    "ground_task",
    "h_add",
    "h_ff",
    "h_max",
    "load_task",
    "parse_atom",
    "parse_plan",
    "parse_task",
    "plan_text",
    "read_pddl",
    "run_fast_downward",
    "search_arguments",
    "solve",
    "solve_text",
    "subgoal_sequence",
]
