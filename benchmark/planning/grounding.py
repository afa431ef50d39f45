"""Ground a :class:`PddlTask` into STRIPS operators over numbered fluent atoms.

Heuristics and state-space searches work on ground operators, and so does a potential that
evaluates them on an observation's abstract state. :func:`ground_task` instantiates every
action schema whose *static* preconditions can hold: static positive preconditions are joined
against the static atoms of ``:init`` (a relation per predicate, indexed on the arguments bound
so far), so a schema such as push's five-parameter ``push`` costs as many candidates as its
``push_line`` relation has tuples instead of ``|places|⁴``. Parameters that no static atom binds
range over the objects of their type; (in)equalities and static negative preconditions filter
the result. The fluent preconditions are left open: the operators are those applicable in *some*
state, not only in states reachable from ``:init``, because an observation's abstract state
need not be one of those.

Fluent atoms are numbered in first-seen order (goal atoms, then operator atoms in operator
order), so a state is a set of numbers or an ``int`` bit mask (:meth:`GroundTask.mask`). Atoms
of a state that no operator and no goal mentions are irrelevant to every heuristic and are
dropped when a state is converted.

Example:
    >>> from planshape.planning.grid import grid_pddl
    >>> from planshape.planning.parse import parse_task
    >>> task = parse_task(*grid_pddl(1, 3, start=(0, 0), goal=(0, 2)).texts)
    >>> ground = ground_task(task)
    >>> len(ground.operators), [str(op.action) for op in ground.operators[:2]]
    (4, ['(move cell_0_0 cell_0_1)', '(move cell_0_1 cell_0_0)'])
    >>> ground.is_goal(ground.mask({("robot_at", "cell_0_2")}))
    True
"""

from __future__ import annotations

import itertools
import threading
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass

from planshape.errors import BadInputError
from planshape.planning.model import ActionSchema, Atom, GroundAction, PddlTask

__all__ = ["GroundOperator", "GroundTask", "ground_task"]


@dataclass(frozen=True)
class GroundOperator:
    """A ground STRIPS operator on numbered fluent atoms.

    ``pre`` and ``neg`` are the positive and negative fluent preconditions (static ones hold by
    construction), ``add`` and ``delete`` the effects; delete effects apply before add effects.
    """

    action: GroundAction
    pre: tuple[int, ...]
    neg: tuple[int, ...]
    add: tuple[int, ...]
    delete: tuple[int, ...]


class GroundTask:
    """A grounded task: fluent atoms, operators and goal, with bit-mask states.

    Built by :func:`ground_task`; treat it as read-only (it is shared per task).

    Attributes:
        task: the parsed task.
        atoms: the fluent atoms, numbered by position.
        index: atom -> number.
        operators: every operator whose static preconditions hold.
        goal: the numbers of the goal's fluent atoms.
        goal_possible: ``False`` when a static goal atom is false in ``:init`` (no state is a
            goal state then).
    """

    def __init__(
        self,
        task: PddlTask,
        atoms: Sequence[Atom],
        operators: Sequence[GroundOperator],
        goal: Sequence[int],
        goal_possible: bool,
    ):
        self.task = task
        self.atoms: tuple[Atom, ...] = tuple(atoms)
        self.index: dict[Atom, int] = {atom: i for i, atom in enumerate(self.atoms)}
        self.operators: tuple[GroundOperator, ...] = tuple(operators)
        self.goal: tuple[int, ...] = tuple(goal)
        self.goal_possible = goal_possible
        self.goal_mask = _mask(self.goal)
        self._pre_mask = [_mask(op.pre) for op in self.operators]
        self._neg_mask = [_mask(op.neg) for op in self.operators]
        self._del_mask = [_mask(op.delete) for op in self.operators]
        self._add_mask = [_mask(op.add) for op in self.operators]
        # operators indexed by their first positive precondition: a state's candidates are
        # those of its atoms (plus the few without positive preconditions)
        self._by_first: list[list[int]] = [[] for _ in self.atoms]
        self._unconditional: list[int] = []
        for k, op in enumerate(self.operators):
            (self._by_first[op.pre[0]] if op.pre else self._unconditional).append(k)

    def __repr__(self) -> str:
        return (
            f"GroundTask({self.task.domain_name}/{self.task.problem_name}: "
            f"{len(self.atoms)} fluent atoms, {len(self.operators)} operators)"
        )

    # ---- states

    def ids(self, state: Iterable[Atom]) -> list[int]:
        """The numbers of the relevant fluent atoms of ``state`` (others are dropped)."""
        index = self.index
        return [index[a] for a in state if a in index]

    def mask(self, state: Iterable[Atom]) -> int:
        """``state`` as a bit mask over :attr:`atoms`."""
        return _mask(self.ids(state))

    def atoms_of(self, mask: int) -> frozenset[Atom]:
        """The fluent atoms of a bit mask (the inverse of :meth:`mask` on relevant atoms)."""
        return frozenset(self.atoms[i] for i in _bits(mask))

    def is_goal(self, mask: int) -> bool:
        return self.goal_possible and mask & self.goal_mask == self.goal_mask

    # ---- successors

    def applicable(self, mask: int) -> Iterator[int]:
        """The numbers of the operators applicable in ``mask`` (negative preconditions too)."""
        pre, neg = self._pre_mask, self._neg_mask
        for i in _bits(mask):
            for k in self._by_first[i]:
                if mask & pre[k] == pre[k] and not mask & neg[k]:
                    yield k
        for k in self._unconditional:
            if mask & pre[k] == pre[k] and not mask & neg[k]:
                yield k

    def successor(self, mask: int, operator: int) -> int:
        """The state after applying ``operator`` (assumed applicable) in ``mask``."""
        return (mask & ~self._del_mask[operator]) | self._add_mask[operator]

    def successors(self, mask: int) -> list[tuple[int, int]]:
        """``(operator, next state)`` for every applicable operator."""
        return [(k, self.successor(mask, k)) for k in self.applicable(mask)]


def _mask(ids: Iterable[int]) -> int:
    mask = 0
    for i in ids:
        mask |= 1 << i
    return mask


def _bits(mask: int) -> Iterator[int]:
    while mask:
        low = mask & -mask
        yield low.bit_length() - 1
        mask ^= low


# ---- grounding --------------------------------------------------------------------------------

_CACHE: dict[int, tuple[PddlTask, GroundTask]] = {}
_LOCK = threading.Lock()


def ground_task(task: PddlTask) -> GroundTask:
    """The grounded task, built once per task object (tasks from :func:`load_task` are shared).

    Raises :class:`BadInputError` when the task has no action schemas (a task built by hand
    rather than parsed from PDDL).
    """
    with _LOCK:
        hit = _CACHE.get(id(task))
        if hit is not None and hit[0] is task:
            return hit[1]
    if not task.actions:
        raise BadInputError(
            f"task {task.domain_name}/{task.problem_name} has no action schemas to ground; "
            "parse it from PDDL (planshape.planning.parse_task or load_task)"
        )
    ground = _Grounder(task).ground()
    with _LOCK:
        _CACHE[id(task)] = (task, ground)  # the task is kept alive, so its id stays unique
    return ground


class _Grounder:
    def __init__(self, task: PddlTask):
        self.task = task
        self.static = task.static_predicates
        self.relations: dict[str, list[tuple[str, ...]]] = {}
        for atom in task.static_atoms():
            self.relations.setdefault(atom[0], []).append(atom[1:])
        for rows in self.relations.values():
            rows.sort()
        self.static_set = task.static_atoms()
        self._indexes: dict[tuple[str, tuple[int, ...]], dict[tuple[str, ...], list]] = {}
        self.atoms: dict[Atom, int] = {}

    def number(self, atom: Atom) -> int:
        if atom not in self.atoms:
            self.atoms[atom] = len(self.atoms)
        return self.atoms[atom]

    def ground(self) -> GroundTask:
        goal_static = [a for a in self.task.goal if a[0] in self.static]
        goal_possible = all(a in self.static_set for a in goal_static)
        goal = [self.number(a) for a in sorted(self.task.goal) if a[0] not in self.static]
        operators = []
        for name in sorted(self.task.actions):
            operators.extend(self.schema(self.task.actions[name]))
        atoms = sorted(self.atoms, key=self.atoms.__getitem__)
        return GroundTask(self.task, atoms, operators, goal, goal_possible)

    def index(self, predicate: str, positions: tuple[int, ...]) -> dict[tuple[str, ...], list]:
        """The static relation of ``predicate`` keyed on the arguments at ``positions``."""
        key = (predicate, positions)
        if key not in self._indexes:
            table: dict[tuple[str, ...], list] = {}
            for row in self.relations.get(predicate, ()):
                table.setdefault(tuple(row[p] for p in positions), []).append(row)
            self._indexes[key] = table
        return self._indexes[key]

    def schema(self, schema: ActionSchema) -> Iterator[GroundOperator]:
        variables = [v for v, _ in schema.parameters]
        domains = {v: frozenset(self.task.objects_of_type(t)) for v, t in schema.parameters}
        static_pos = [a for a in schema.positive if a[0] in self.static]
        for binding in self.join(static_pos, domains):
            for rest in itertools.product(
                *(sorted(domains[v]) for v in variables if v not in binding)
            ):
                full = dict(binding)
                full.update(zip((v for v in variables if v not in binding), rest, strict=True))
                operator = self.instantiate(schema, variables, full)
                if operator is not None:
                    yield operator

    def join(self, atoms: list[Atom], domains: dict[str, frozenset[str]]) -> list[dict]:
        """Bindings of the variables of ``atoms`` under which every one is a static fact."""
        bindings: list[dict[str, str]] = [{}]
        remaining = list(atoms)
        while remaining and bindings:
            # next: the atom with the most arguments already bound, then the smallest relation
            bound = bindings[0].keys()
            atom = min(
                remaining,
                key=lambda a: (
                    -sum(1 for t in a[1:] if t in bound or not t.startswith("?")),
                    len(self.relations.get(a[0], ())),
                ),
            )
            remaining.remove(atom)
            terms = atom[1:]
            fixed = tuple(i for i, t in enumerate(terms) if t in bound or not t.startswith("?"))
            table = self.index(atom[0], fixed)
            extended = []
            for binding in bindings:
                key = tuple(binding.get(terms[i], terms[i]) for i in fixed)
                for row in table.get(key, ()):
                    new = dict(binding)
                    if all(self.bind(new, t, o, domains) for t, o in zip(terms, row, strict=True)):
                        extended.append(new)
            bindings = extended
        return bindings

    @staticmethod
    def bind(binding: dict[str, str], term: str, obj: str, domains: dict) -> bool:
        if not term.startswith("?"):
            return term == obj
        if term in binding:
            return binding[term] == obj
        if obj not in domains[term]:
            return False
        binding[term] = obj
        return True

    def instantiate(
        self, schema: ActionSchema, variables: list[str], binding: dict[str, str]
    ) -> GroundOperator | None:
        def bind(atom: Atom) -> Atom:
            return (atom[0], *(binding.get(t, t) for t in atom[1:]))

        for left, right in schema.equal:
            if binding.get(left, left) != binding.get(right, right):
                return None
        for left, right in schema.not_equal:
            if binding.get(left, left) == binding.get(right, right):
                return None
        pre, neg = [], []
        for atom in map(bind, schema.positive):
            if atom[0] in self.static:
                if atom not in self.static_set:
                    return None
            else:
                pre.append(atom)
        for atom in map(bind, schema.negative):
            if atom[0] in self.static:
                if atom in self.static_set:
                    return None
            else:
                neg.append(atom)
        number = self.number
        return GroundOperator(
            GroundAction(schema.name, tuple(binding[v] for v in variables)),
            pre=tuple(dict.fromkeys(map(number, pre))),
            neg=tuple(dict.fromkeys(map(number, neg))),
            add=tuple(dict.fromkeys(number(bind(a)) for a in schema.add)),
            delete=tuple(dict.fromkeys(number(bind(a)) for a in schema.delete)),
        )
