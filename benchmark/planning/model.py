"""The value types that flow out of the planning stage.

A ground atom is a tuple ``(predicate, obj1, ..., objm)`` in lower case, e.g.
``("robot_at", "cell_2_3")``; an abstract state is a frozenset of ground atoms (Definition 1 of
the source paper). A :class:`Plan` carries the ground operators Fast Downward returned and the
subgoal sequence Ŝ = [ŝ0 … ŝn] obtained by applying them from the initial state.

Example:
    >>> a = GroundAction("move", ("a", "b"))
    >>> str(a)
    '(move a b)'
    >>> plan = Plan((a,), (frozenset({("at", "a")}), frozenset({("at", "b")})), 1, "astar-lmcut")
    >>> plan.length
    1
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, overload

Atom = tuple[str, ...]
AbstractState = frozenset[Atom]


def format_atom(atom: Atom) -> str:
    """``("at", "a")`` -> ``"(at a)"``."""
    return "(" + " ".join(atom) + ")"


def parse_atom(text: str) -> Atom:
    """``"(at a)"`` -> ``("at", "a")``: the inverse of :func:`format_atom` (names are lowered).

    Example:
        >>> parse_atom("(Move A b)")
        ('move', 'a', 'b')
    """
    inner = text.strip()
    if not (inner.startswith("(") and inner.endswith(")")):
        raise ValueError(f"not a ground atom: {text!r} (expected e.g. '(at a)')")
    return tuple(inner[1:-1].lower().split())


@dataclass(frozen=True)
class GroundAction:
    """A ground operator: an action schema name and the objects substituted for its parameters."""

    name: str
    args: tuple[str, ...]

    def __str__(self) -> str:
        return format_atom((self.name, *self.args))


@dataclass(frozen=True)
class PredicateSignature:
    """A predicate's name and the types of its parameters, in order."""

    name: str
    parameter_types: tuple[str, ...]

    @property
    def arity(self) -> int:
        return len(self.parameter_types)


@dataclass(frozen=True)
class ActionSchema:
    """A STRIPS action schema with typed parameters, as the planning stage applies it.

    Atoms are lower-case tuples whose arguments are either parameters (``"?from"``) or constants.
    Equalities are pairs of such terms. Delete effects are applied before add effects, so an atom
    both deleted and added holds afterwards (PDDL semantics, as in Fast Downward).

    Example:
        >>> move = ActionSchema("move", (("?from", "cell"), ("?to", "cell")),
        ...     positive=(("at", "?from"),), add=(("at", "?to"),), delete=(("at", "?from"),))
        >>> move.arity
        2
    """

    name: str
    #: (variable, type) in declaration order, variables with their leading ``?``.
    parameters: tuple[tuple[str, str], ...]
    positive: tuple[Atom, ...] = ()
    negative: tuple[Atom, ...] = ()
    equal: tuple[tuple[str, str], ...] = ()
    not_equal: tuple[tuple[str, str], ...] = ()
    add: tuple[Atom, ...] = ()
    delete: tuple[Atom, ...] = ()

    @property
    def arity(self) -> int:
        return len(self.parameters)


@dataclass(frozen=True)
class PddlTask:
    """What the abstraction layer needs to know about a parsed (domain, problem) pair.

    ``objects`` includes the domain's constants. ``static_predicates`` are the predicates that no
    action adds or deletes: their truth is fixed by the problem's ``:init`` and they are never
    classified. Every other predicate is *fluent* and needs a classifier.
    """

    domain_name: str
    problem_name: str
    predicates: dict[str, PredicateSignature]
    #: type -> parent type (``None`` for the root ``object``).
    types: dict[str, str | None]
    #: object or constant -> its declared type.
    objects: dict[str, str]
    init: AbstractState
    goal: AbstractState
    static_predicates: frozenset[str]
    domain_file: str | None = None
    problem_file: str | None = None
    #: action name -> schema; what :func:`planshape.planning.subgoal_sequence` applies. Tasks
    #: built by hand (tests, toy MDPs) may leave it empty.
    actions: Mapping[str, ActionSchema] = field(default_factory=dict, compare=False, repr=False)

    @property
    def fluent_predicates(self) -> frozenset[str]:
        return frozenset(self.predicates) - self.static_predicates

    def is_subtype(self, child: str, ancestor: str) -> bool:
        """Whether ``child`` equals ``ancestor`` or descends from it (``object`` is the root)."""
        seen: str | None = child
        while seen is not None:
            if seen == ancestor:
                return True
            seen = self.types.get(seen)
        return ancestor == "object"

    def objects_of_type(self, type_name: str) -> tuple[str, ...]:
        """Objects (and constants) of ``type_name`` or one of its subtypes, in sorted order."""
        return tuple(sorted(o for o, t in self.objects.items() if self.is_subtype(t, type_name)))

    def static_atoms(self) -> AbstractState:
        """The atoms of ``:init`` whose predicate is static."""
        return frozenset(a for a in self.init if a[0] in self.static_predicates)


class SubgoalStates(Sequence[AbstractState]):
    """The subgoal sequence Ŝ, stored as the static atoms once plus each state's fluent atoms.

    It behaves like a tuple of full abstract states (static ∪ fluent atoms): indexing,
    iteration, ``len``, ``==`` with a tuple of frozensets. A full state is built the first time it
    is asked for and kept; a plan loaded from the cache therefore costs no set building until
    its states are used. ``static`` and ``fluents`` are the cheap views for code that only
    compares fluent atoms. ``static`` may be given as a zero-argument callable, evaluated once.

    Example:
        >>> states = SubgoalStates({("link", "a", "b")}, [{("at", "a")}, {("at", "b")}])
        >>> len(states), sorted(states[1])
        (2, [('at', 'b'), ('link', 'a', 'b')])
        >>> states == (states[0], states[1])
        True
        >>> states.fluents[1]
        frozenset({('at', 'b')})
    """

    __slots__ = ("_states", "_static", "fluents")

    def __init__(
        self,
        static: Iterable[Atom] | Callable[[], Iterable[Atom]],
        fluents: Iterable[Iterable[Atom]],
    ):
        self._static: AbstractState | Callable[[], Iterable[Atom]] = (
            static if callable(static) else frozenset(static)
        )
        self.fluents: tuple[AbstractState, ...] = tuple(frozenset(f) for f in fluents)
        self._states: list[AbstractState | None] = [None] * len(self.fluents)

    @classmethod
    def from_states(
        cls, states: Sequence[AbstractState], static_predicates: Iterable[str]
    ) -> SubgoalStates:
        """Split full states by predicate; the states given are kept, not rebuilt."""
        names = frozenset(static_predicates)
        static = frozenset(a for a in states[0] if a[0] in names) if states else frozenset()
        result = cls(static, [s - static for s in states])
        result._states = list(states)
        return result

    @property
    def static(self) -> AbstractState:
        """The atoms of static predicates, the same in every state."""
        if callable(self._static):
            self._static = frozenset(self._static())
        return self._static

    def _state(self, index: int) -> AbstractState:
        state = self._states[index]
        if state is None:
            state = self._states[index] = self.static | self.fluents[index]
        return state

    @overload
    def __getitem__(self, index: int) -> AbstractState: ...
    @overload
    def __getitem__(self, index: slice) -> tuple[AbstractState, ...]: ...
    def __getitem__(self, index: int | slice) -> AbstractState | tuple[AbstractState, ...]:
        if isinstance(index, slice):
            return tuple(self._state(i) for i in range(*index.indices(len(self))))
        return self._state(range(len(self))[index])

    def __len__(self) -> int:
        return len(self.fluents)

    def __iter__(self) -> Iterator[AbstractState]:
        return (self._state(i) for i in range(len(self)))

    def __eq__(self, other: object) -> bool:
        if isinstance(other, SubgoalStates):
            return self.fluents == other.fluents and self.static == other.static
        if isinstance(other, Sequence) and not isinstance(other, str):
            return len(self) == len(other) and all(a == b for a, b in zip(self, other, strict=True))
        return NotImplemented

    def __hash__(self) -> int:  # equal to the hash of the equal tuple
        return hash(tuple(self))

    def __reduce__(self) -> tuple[Any, ...]:  # picklable even with a lazy ``static``
        return (SubgoalStates, (self.static, self.fluents))

    def __repr__(self) -> str:
        return f"SubgoalStates({len(self.static)} static atoms, fluents={list(self.fluents)!r})"


@dataclass(frozen=True)
class Plan:
    """A validated plan and the subgoal sequence it induces.

    ``subgoals[0]`` is the initial abstract state and ``subgoals[i]`` the state after the i-th
    action, so ``len(subgoals) == len(actions) + 1``. States hold fluent and static atoms alike.
    :func:`planshape.planning.solve` gives a :class:`SubgoalStates` (a lazy tuple-like sequence
    with ``static`` and ``fluents`` views); a plain tuple of frozensets is accepted too.
    """

    actions: tuple[GroundAction, ...]
    subgoals: Sequence[AbstractState]
    cost: int
    search: str
    #: provenance: how long the planner took (0.0 for a cache hit) and whether the cache answered
    planner_seconds: float = field(default=0.0, compare=False)
    from_cache: bool = field(default=False, compare=False)

    @property
    def length(self) -> int:
        return len(self.actions)
