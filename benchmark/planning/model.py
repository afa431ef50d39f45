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

from dataclasses import dataclass, field

Atom = tuple[str, ...]
AbstractState = frozenset[Atom]


def format_atom(atom: Atom) -> str:
    """``("at", "a")`` -> ``"(at a)"``."""
    return "(" + " ".join(atom) + ")"


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


@dataclass(frozen=True)
class Plan:
    """A validated plan and the subgoal sequence it induces.

    ``subgoals[0]`` is the initial abstract state and ``subgoals[i]`` the state after the i-th
    action, so ``len(subgoals) == len(actions) + 1``. States hold fluent and static atoms alike.
    """

    actions: tuple[GroundAction, ...]
    subgoals: tuple[AbstractState, ...]
    cost: int
    search: str
    #: provenance: how long the planner took (0.0 for a cache hit) and whether the cache answered
    planner_seconds: float = field(default=0.0, compare=False)
    from_cache: bool = field(default=False, compare=False)

    @property
    def length(self) -> int:
        return len(self.actions)
