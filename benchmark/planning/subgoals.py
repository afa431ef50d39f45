"""Execute a plan on the abstract model: Ŝ = [ŝ0 … ŝn], each step checked.

ŝ0 is the problem's ``:init``; ŝi = (ŝ(i-1) − del(ai)) ∪ add(ai) once every precondition of the
ground action ai holds in ŝ(i-1). The last state must satisfy the goal. Any failure is a
:class:`PlanValidationError` that names the step, the action and the atom.

Example:
    >>> from planshape.planning.grid import grid_pddl
    >>> from planshape.planning.parse import parse_task
    >>> grid = grid_pddl(1, 3, start=(0, 0), goal=(0, 2))
    >>> task = parse_task(grid.domain, grid.problem)
    >>> states = subgoal_sequence(task, ["(move cell_0_0 cell_0_1)", "(move cell_0_1 cell_0_2)"])
    >>> [sorted(s - task.static_atoms()) for s in states]
    [[('robot_at', 'cell_0_0')], [('robot_at', 'cell_0_1')], [('robot_at', 'cell_0_2')]]
"""

from __future__ import annotations

from collections.abc import Iterable

from planshape.errors import PlanValidationError
from planshape.planning.model import (
    AbstractState,
    ActionSchema,
    Atom,
    GroundAction,
    PddlTask,
    format_atom,
    parse_atom,
)

__all__ = ["apply_action", "subgoal_sequence"]


def subgoal_sequence(
    task: PddlTask, actions: Iterable[GroundAction | str]
) -> tuple[AbstractState, ...]:
    """The abstract states a plan visits, from ``task.init`` to a state satisfying the goal.

    ``actions`` are ground actions or their text, e.g. ``"(move cell_0_0 cell_0_1)"``. The result
    has one state more than there are actions.

    Example:
        >>> from planshape.planning.grid import grid_pddl
        >>> from planshape.planning.parse import parse_task
        >>> task = parse_task(*grid_pddl(1, 2, start=(0, 0), goal=(0, 1)).texts)
        >>> subgoal_sequence(task, ["(move cell_0_0 cell_0_0)"])  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        planshape.errors.PlanValidationError: step 1 (move cell_0_0 cell_0_0): precondition (neig...
    """
    state = task.init
    states = [state]
    for step, action in enumerate(actions, start=1):
        state = apply_action(task, state, action, step=step)
        states.append(state)
    missing = task.goal - state
    if missing:
        atoms = " ".join(format_atom(a) for a in sorted(missing))
        raise PlanValidationError(
            f"the plan ends after {len(states) - 1} step(s) in a state that misses the goal "
            f"atom(s) {atoms}{_source(task)}"
        )
    return tuple(states)


def apply_action(
    task: PddlTask, state: AbstractState, action: GroundAction | str, *, step: int | None = None
) -> AbstractState:
    """The successor of ``state`` under ``action``, after checking its preconditions.

    Example:
        >>> from planshape.planning.grid import grid_pddl
        >>> from planshape.planning.parse import parse_task
        >>> task = parse_task(*grid_pddl(1, 2, start=(0, 0), goal=(0, 1)).texts)
        >>> after = apply_action(task, task.init, "(move cell_0_0 cell_0_1)")
        >>> ("robot_at", "cell_0_1") in after, ("robot_at", "cell_0_0") in after
        (True, False)
    """
    ground = _as_ground(action)
    where = f"step {step} {ground}" if step is not None else str(ground)
    schema = _schema(task, ground, where)
    binding = dict(zip((var for var, _ in schema.parameters), ground.args, strict=True))
    for (var, expected), obj in zip(schema.parameters, ground.args, strict=True):
        actual = task.objects.get(obj)
        if actual is None:
            raise PlanValidationError(f"{where}: unknown object {obj!r}{_source(task)}")
        if not task.is_subtype(actual, expected):
            raise PlanValidationError(
                f"{where}: {obj!r} has type {actual}, but parameter {var} of {schema.name!r} "
                f"expects type {expected}{_source(task)}"
            )

    def bind(atom: Atom) -> Atom:
        return (atom[0], *(binding.get(t, t) for t in atom[1:]))

    for atom in map(bind, schema.positive):
        if atom not in state:
            _fail(where, f"precondition {format_atom(atom)} does not hold", task)
    for atom in map(bind, schema.negative):
        if atom in state:
            _fail(where, f"precondition (not {format_atom(atom)}) fails: the atom holds", task)
    for left, right in schema.equal:
        a, b = binding.get(left, left), binding.get(right, right)
        if a != b:
            _fail(where, f"precondition (= {a} {b}) does not hold", task)
    for left, right in schema.not_equal:
        a, b = binding.get(left, left), binding.get(right, right)
        if a == b:
            _fail(where, f"precondition (not (= {a} {b})) fails", task)
    return (state - frozenset(map(bind, schema.delete))) | frozenset(map(bind, schema.add))


def _as_ground(action: GroundAction | str) -> GroundAction:
    if isinstance(action, GroundAction):
        return action
    name, *args = parse_atom(action)
    return GroundAction(name, tuple(args))


def _schema(task: PddlTask, ground: GroundAction, where: str) -> ActionSchema:
    schema = task.actions.get(ground.name)
    if schema is None:
        known = ", ".join(sorted(task.actions)) or "none (the task was not parsed from PDDL)"
        raise PlanValidationError(
            f"{where}: unknown action {ground.name!r}; the domain defines: {known}"
        )
    if schema.arity != len(ground.args):
        raise PlanValidationError(
            f"{where}: action {ground.name!r} takes {schema.arity} argument(s), "
            f"{len(ground.args)} given"
        )
    return schema


def _fail(where: str, what: str, task: PddlTask) -> None:
    raise PlanValidationError(f"{where}: {what}{_source(task)}")


def _source(task: PddlTask) -> str:
    if task.domain_file and task.problem_file:
        return f" ({task.domain_file}, {task.problem_file})"
    return ""
