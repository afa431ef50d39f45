"""Delete-relaxation heuristics on a :class:`GroundTask`: h_max, h_add and h_FF.

The delete relaxation ignores delete effects and negative preconditions; every operator costs
1 (the planar models have unit costs). For a state s (its fluent atoms; static atoms hold by
grounding) the atom costs are the least fixed point of

    c(p) = 0 if p ∈ s,  else  min over operators o adding p of  1 + C(pre(o)),

with C = Σ for h_add and C = max for h_max (Bonet & Geffner 2001); h(s) = C(goal). Both are
computed by one generalized Dijkstra pass (Knuth 1977) that stops once every goal atom is
settled. h_FF (Hoffmann & Nebel 2001) is the number of operators in a relaxed plan extracted
backwards through the relaxed planning graph: the graph's layers are the h_max costs, a goal at
layer i is achieved by an operator of layer i − 1 of least *difficulty* (the sum of its
preconditions' layers, ties to the first operator in grounding order), the operator's
preconditions become goals at their own layers, and its add effects count as achieved at
layers i − 1 and i so that no second achiever is chosen for them. ``supporters="add"`` gives
instead the best-supporter variant of Fast Downward and pyperplan (Keyder & Geffner 2008): each
atom's achiever is the operator that set its h_add cost.

Every function returns ``math.inf`` when the goal is not relaxed-reachable (a dead end for sure)
and 0 exactly when the state satisfies the goal.

Example:
    >>> from planshape.planning.grid import grid_pddl
    >>> from planshape.planning.parse import parse_task
    >>> from planshape.planning.grounding import ground_task
    >>> ground = ground_task(parse_task(*grid_pddl(2, 3, start=(0, 0), goal=(1, 2)).texts))
    >>> state = ground.ids({("robot_at", "cell_0_0")})
    >>> h_max(ground, state), h_add(ground, state), h_ff(ground, state)
    (3, 3, 3)
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Iterable
from typing import Literal

from planshape.planning.grounding import GroundTask

__all__ = ["RelaxedCosts", "h_add", "h_ff", "h_max", "relaxed_costs", "relaxed_plan"]

Supporters = Literal["max", "add"]


class _Relaxation:
    """Per-task arrays of the relaxed operators, built once and kept on the GroundTask."""

    def __init__(self, ground: GroundTask):
        self.n_atoms = len(ground.atoms)
        self.pre = [op.pre for op in ground.operators]
        self.add = [op.add for op in ground.operators]
        self.n_pre = [len(p) for p in self.pre]
        self.precondition_of: list[list[int]] = [[] for _ in range(self.n_atoms)]
        self.achievers: list[list[int]] = [[] for _ in range(self.n_atoms)]
        for k, op in enumerate(ground.operators):
            for p in op.pre:
                self.precondition_of[p].append(k)
            for p in op.add:
                self.achievers[p].append(k)
        self.unconditional = [k for k, n in enumerate(self.n_pre) if n == 0]


def _relaxation(ground: GroundTask) -> _Relaxation:
    relaxation = getattr(ground, "_relaxation", None)
    if relaxation is None:
        relaxation = _Relaxation(ground)
        ground._relaxation = relaxation  # type: ignore[attr-defined]
    return relaxation


class RelaxedCosts:
    """The atom costs of one Dijkstra pass: ``cost[p]`` (``inf`` if unreached) and, for every
    reached atom not in the state, ``supporter[p]``, the operator that set its cost."""

    __slots__ = ("cost", "op_cost", "supporter")

    def __init__(self, cost: list[float], supporter: list[int], op_cost: list[float]):
        self.cost = cost
        self.supporter = supporter
        self.op_cost = op_cost


def relaxed_costs(
    ground: GroundTask,
    state: Iterable[int],
    combine: Literal["add", "max"],
    *,
    complete: bool = False,
) -> RelaxedCosts:
    """h_add (``combine="add"``) or h_max (``"max"``) costs of every atom from ``state``.

    The pass stops once all goal atoms are settled unless ``complete`` is set; atoms settled by
    then (all those no dearer than the dearest goal atom) have their final cost.
    """
    r = _relaxation(ground)
    inf = math.inf
    cost: list[float] = [inf] * r.n_atoms
    supporter = [-1] * r.n_atoms
    op_cost: list[float] = [inf] * len(r.pre)
    counter = list(r.n_pre)
    acc = [0.0] * len(r.pre)
    heap: list[tuple[float, int]] = []
    for p in state:
        if cost[p]:
            cost[p] = 0.0
            heap.append((0.0, p))
    heapq.heapify(heap)
    for k in r.unconditional:
        op_cost[k] = 1.0
        for q in r.add[k]:
            if cost[q] > 1.0:
                cost[q], supporter[q] = 1.0, k
                heapq.heappush(heap, (1.0, q))
    goal = set(ground.goal)
    pending = len(goal)
    settled = [False] * r.n_atoms
    is_add = combine == "add"
    while heap and (pending or complete):
        c, p = heapq.heappop(heap)
        if settled[p] or c > cost[p]:
            continue
        settled[p] = True
        if p in goal:
            pending -= 1
        for k in r.precondition_of[p]:
            counter[k] -= 1
            acc[k] = acc[k] + c if is_add else max(acc[k], c)
            if counter[k] == 0:
                through = op_cost[k] = 1.0 + acc[k]
                for q in r.add[k]:
                    if through < cost[q]:
                        cost[q], supporter[q] = through, k
                        heapq.heappush(heap, (through, q))
    return RelaxedCosts(cost, supporter, op_cost)


def _goal_value(ground: GroundTask, costs: RelaxedCosts, combine: str) -> float:
    if not ground.goal_possible:
        return math.inf
    values = [costs.cost[g] for g in ground.goal]
    if not values:
        return 0
    total = sum(values) if combine == "add" else max(values)
    return total if math.isinf(total) else int(total)


def h_max(ground: GroundTask, state: Iterable[int]) -> float:
    """h_max(s): the cost of the dearest goal atom, preconditions combined by max."""
    return _goal_value(ground, relaxed_costs(ground, state, "max"), "max")


def h_add(ground: GroundTask, state: Iterable[int]) -> float:
    """h_add(s): the sum of the goal atoms' costs, preconditions combined by sum."""
    return _goal_value(ground, relaxed_costs(ground, state, "add"), "add")


def h_ff(ground: GroundTask, state: Iterable[int], supporters: Supporters = "max") -> float:
    """h_FF(s): the length of a relaxed plan (see the module docstring for ``supporters``)."""
    plan = relaxed_plan(ground, state, supporters)
    return math.inf if plan is None else len(plan)


def relaxed_plan(
    ground: GroundTask, state: Iterable[int], supporters: Supporters = "max"
) -> frozenset[int] | None:
    """The operators (numbers) of h_FF's relaxed plan from ``state``; ``None`` at a dead end."""
    if supporters not in ("max", "add"):
        raise ValueError(f"supporters must be 'max' or 'add', not {supporters!r}")
    if not ground.goal_possible:
        return None
    costs = relaxed_costs(ground, state, supporters)
    if any(math.isinf(costs.cost[g]) for g in ground.goal):
        return None
    if supporters == "add":
        return _extract_by_supporters(ground, costs)
    return _extract_graphplan(ground, costs)


def _extract_by_supporters(ground: GroundTask, costs: RelaxedCosts) -> frozenset[int]:
    r = _relaxation(ground)
    plan: set[int] = set()
    seen: set[int] = set()
    stack = [g for g in ground.goal if costs.cost[g] > 0]
    while stack:
        p = stack.pop()
        if p in seen:
            continue
        seen.add(p)
        k = costs.supporter[p]
        if k not in plan:
            plan.add(k)
            stack.extend(q for q in r.pre[k] if costs.cost[q] > 0)
    return frozenset(plan)


def _extract_graphplan(ground: GroundTask, costs: RelaxedCosts) -> frozenset[int]:
    """Hoffmann & Nebel's extraction on the layers given by the h_max costs."""
    r = _relaxation(ground)
    level = costs.cost
    layers: dict[int, set[int]] = {}
    for g in ground.goal:
        if level[g] > 0:
            layers.setdefault(int(level[g]), set()).add(g)
    if not layers:
        return frozenset()
    true_at: set[tuple[int, int]] = set()  # (atom, layer) marked achieved
    plan: set[int] = set()
    for i in range(max(layers), 0, -1):
        for g in sorted(layers.get(i, ())):
            if (g, i) in true_at:
                continue
            best, best_difficulty = -1, math.inf
            for k in r.achievers[g]:
                # an operator of layer i − 1: applicable there (its preconditions' h_max < i)
                # and first applicable there (h_max(o) = i, so its cost is i)
                if costs.op_cost[k] == i:
                    difficulty = sum(level[q] for q in r.pre[k])
                    if difficulty < best_difficulty:
                        best, best_difficulty = k, difficulty
            plan.add(best)
            for q in r.pre[best]:
                lq = int(level[q])
                if lq and (q, i - 1) not in true_at:
                    layers.setdefault(lq, set()).add(q)
            for q in r.add[best]:
                true_at.add((q, i))
                true_at.add((q, i - 1))
    return frozenset(plan)
