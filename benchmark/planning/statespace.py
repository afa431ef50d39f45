"""Exact goal distances h* on the explicit abstract state space of a :class:`GroundTask`.

:class:`GoalDistances` explores the state space forward from ``:init`` once (breadth first,
with negative preconditions and delete effects, i.e. the real semantics), then labels every
explored state with its distance to the nearest goal state by one search over the reversed
edges. Every operator costs 1, so h*(s) is the length of an optimal plan from s — what
Fast Downward's optimal searches return for a problem whose ``:init`` is s.

A state the first exploration did not reach (an observation's abstract state need not be
reachable from ``:init``) is explored on demand: the new part of its forward closure is added to
the graph and labelled by a backward search among the new states, seeded by their edges into
states labelled before; those keep their distances, because their forward closures were already
complete. States from which no goal state is reachable get ``math.inf``.

The planar grid models have small spaces (reach and maze-reach: one state per cell, about 150;
push: one per (end effector, box) pair, about 23 500, explored in about half a second). A space
larger than ``max_states`` raises :class:`BadInputError`.

Example:
    >>> from planshape.planning.grid import grid_pddl
    >>> from planshape.planning.parse import parse_task
    >>> from planshape.planning.grounding import ground_task
    >>> grid = grid_pddl(3, 3, start=(0, 0), goal=(0, 2), blocked_edges=[((0, 1), (0, 2)),
    ...                                                                  ((1, 1), (1, 2))])
    >>> distances = GoalDistances(ground_task(parse_task(*grid.texts)))
    >>> distances.of_atoms({("robot_at", "cell_0_0")}), distances.n_states
    (6, 9)
"""

from __future__ import annotations

import heapq
import math
from collections import deque
from collections.abc import Iterable

from planshape.errors import BadInputError
from planshape.planning.grounding import GroundTask
from planshape.planning.model import Atom

__all__ = ["DEFAULT_MAX_STATES", "GoalDistances"]

#: the largest state space :class:`GoalDistances` explores (states, not bytes): about ten
#: seconds of exploration, ten times the push grid's space.
DEFAULT_MAX_STATES = 250_000


class GoalDistances:
    """h*(s) for every state of the explored space, explored from ``:init`` and on demand.

    Args:
        ground: the grounded task.
        max_states: refuse (with :class:`BadInputError`) to explore more states than this.
    """

    def __init__(self, ground: GroundTask, max_states: int = DEFAULT_MAX_STATES):
        self.ground = ground
        self.max_states = max_states
        #: state -> its successors (states), for every explored state
        self._successors: dict[int, tuple[int, ...]] = {}
        #: state -> h* (inf for dead ends); complete for every explored state
        self._distance: dict[int, float] = {}
        self.initial = ground.mask(ground.task.init)
        self._explore(self.initial)

    @property
    def n_states(self) -> int:
        """The number of states explored so far."""
        return len(self._successors)

    def __call__(self, state: int) -> float:
        """h*(state) for a bit-mask state (``math.inf`` when no goal state is reachable)."""
        distance = self._distance.get(state)
        if distance is None:
            self._explore(state)
            distance = self._distance[state]
        return distance

    def of_atoms(self, atoms: Iterable[Atom]) -> float:
        """h* of a state given as atoms (static and irrelevant atoms are ignored)."""
        return self(self.ground.mask(atoms))

    def successors(self, state: int) -> tuple[int, ...]:
        """The distinct successor states of an explored (or new) state."""
        if state not in self._successors:
            self._explore(state)
        return self._successors[state]

    def max_finite(self) -> float:
        """The largest finite h* among the explored states (0 if there is none)."""
        return max((d for d in self._distance.values() if not math.isinf(d)), default=0)

    def _explore(self, start: int) -> None:
        ground, successors = self.ground, self._successors
        if start in successors:
            return
        queue = deque([start])
        successors[start] = ()
        new = [start]
        while queue:
            state = queue.popleft()
            after = tuple(
                dict.fromkeys(ground.successor(state, k) for k in ground.applicable(state))
            )
            successors[state] = after
            for other in after:
                if other not in successors:
                    if len(successors) >= self.max_states:
                        for state in new:  # leave the graph as it was
                            del successors[state]
                        raise BadInputError(
                            f"the state space of {ground.task.domain_name}/"
                            f"{ground.task.problem_name} has more than {self.max_states} "
                            f"states (exploring from {sorted(ground.atoms_of(start))[:4]}); exact "
                            "goal distances (h*) are out of reach here: raise max_states or "
                            "use a relaxed heuristic (h-add, h-ff)"
                        )
                    successors[other] = ()
                    new.append(other)
                    queue.append(other)
        self._label(new)

    def _label(self, new: list[int]) -> None:
        """Distances of the ``new`` states: a Dijkstra search backwards from the goal states
        among them and from their edges into states labelled before (whose distances are
        final, because their forward closures were complete)."""
        ground, successors, known = self.ground, self._successors, self._distance
        fresh = set(new)
        predecessors: dict[int, list[int]] = {}
        distance: dict[int, float] = {}
        for state in new:
            best = 0.0 if ground.is_goal(state) else math.inf
            for other in successors[state]:
                if other in fresh:
                    predecessors.setdefault(other, []).append(state)
                elif known[other] + 1 < best:
                    best = known[other] + 1
            if best < math.inf:
                distance[state] = best
        heap = [(d, s) for s, d in distance.items()]
        heapq.heapify(heap)
        while heap:
            d, state = heapq.heappop(heap)
            if d > distance[state]:
                continue
            for before in predecessors.get(state, ()):
                if d + 1 < distance.get(before, math.inf):
                    distance[before] = d + 1
                    heapq.heappush(heap, (d + 1, before))
        for state in new:
            d = distance.get(state, math.inf)
            known[state] = d if math.isinf(d) else int(d)
