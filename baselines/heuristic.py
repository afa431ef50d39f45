"""Planner-heuristic potentials: φ(ŝ) = −h(ŝ), with h a classical planning heuristic evaluated
on the observation's abstract state ŝ.

Gehring et al. (2022) shaped rewards with classical heuristics this way. Such a potential needs
no single fixed plan: whatever abstract state the agent is in, on or off the plan, h says how far
the goal still is, so an agent that left the plan still gets a gradient towards the goal. On the
grid model of maze-reach every h here follows the walls: a cell just behind the U's bottom wall
is as far from the goal as the detour around the wall, not as the straight line.

Heuristics (``heuristic=``), computed on the task's own ground operators
(:mod:`planshape.planning.grounding`) from the fluent part of ŝ plus the static atoms:

* ``"h-add"``, ``"h-max"``: Bonet & Geffner's additive and max heuristics (delete relaxation,
  negative preconditions dropped, unit costs), :mod:`planshape.planning.relaxed`;
* ``"h-ff"``: the length of Hoffmann & Nebel's relaxed plan (the same relaxation);
* ``"h-star"``: the exact remaining plan length h*(ŝ), by breadth-first search over the explicit
  abstract state space (:class:`planshape.planning.statespace.GoalDistances`; ~150 states on
  the reach and maze-reach grids, 23 562 on the push grid, explored once per process in about
  half a second).

Values are cached per abstract state (its fluent atoms) for the life of the process, so each
distinct ŝ costs one heuristic evaluation; afterwards a step costs one classification.

Definitions (``scale`` multiplies all of them; h0 = h(ŝ0), ŝ0 the plan's initial state):

* linear (``gamma=None``): φ = −h(ŝ)/h0, so φ(ŝ0) = −1 and φ = 0 exactly on goal states;
  ``normalize=False`` gives φ = −h(ŝ).
* discount-aware (``gamma`` = the learner's γ, from the shaping wrapper): φ = −(1 − γ^h)/(1 − γ),
  the discounted cost of h unit-cost steps, divided (``normalize=True``) by its value at ŝ0:
  φ = −(1 − γ^h)/(1 − γ^h0). Before normalizing, a step that lowers h by one gets
  F = γ·φ' − φ = 1 at every distance from the goal, and standing still 1 − γ^h < 1; with the
  linear φ = −h the step gets γ + (1 − γ)·h and standing still (1 − γ)·h, both growing with the
  distance. γ must be the learner's for that reading; any γ keeps the optimal policy (φ is a
  function of the state whatever γ is).
* dead ends: where the goal is unreachable from ŝ (h = ∞: a box pushed against the grid's
  border, an observation outside every place) φ must stay finite. The discount-aware φ takes
  its limit γ^∞ = 0, i.e. −1/(1 − γ^h0). The linear φ uses h_dead = h0 · (1 + H*)/h*(ŝ0),
  where H* is the largest finite h* among the abstract states reachable from ŝ0: a dead end is
  worth one step less than the farthest solvable state, measured in plan lengths (φ = −2.44 on
  the push grid, −1.16 on maze-reach). When the state space is too large to enumerate
  (``max_states``), h_dead = 2·h0 + 1. Pass ``dead_end=`` to set h_dead yourself.

Registered: ``h-add``, ``h-ff``, ``h-star`` (linear), ``h-add-discounted``, ``h-ff-discounted``,
``h-star-discounted`` (with the learner's γ, which the shaping wrapper gives them:
:meth:`HeuristicPotential.for_discount`) and ``h-star-geodesic`` (:class:`HStarGeodesic`).
``"h-max"`` is available through ``HeuristicPotential("h-max")``.

These potentials suit models whose places tile the space (the ``grid`` models): with waypoint
models (``single``, ``multi``) an observation between places abstracts to a state with no
position, which is a dead end.

Example:
    >>> import gymnasium, planshape  # doctest: +SKIP
    >>> env = gymnasium.make("planshape/MazeReach-v0", reward="shaped", potential="h-star",
    ...                      model="grid", gamma=0.99)  # doctest: +SKIP
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from planshape.baselines.common import IdentityCache, point_distance
from planshape.errors import BadInputError, PotentialError
from planshape.planning.grounding import ground_task
from planshape.planning.relaxed import h_add, h_ff, h_max
from planshape.planning.statespace import DEFAULT_MAX_STATES, GoalDistances
from planshape.shaping.abstraction import Abstraction, AtomEvaluator
from planshape.shaping.potentials import Potential, ShapingContext, StepPotential

__all__ = ["HEURISTICS", "HStarGeodesic", "HeuristicPotential", "ModelBinding"]


def _h_add(binding: ModelBinding, mask: int) -> float:
    return h_add(binding.ground, _ids(mask))


def _h_max(binding: ModelBinding, mask: int) -> float:
    return h_max(binding.ground, _ids(mask))


def _h_ff(binding: ModelBinding, mask: int) -> float:
    return h_ff(binding.ground, _ids(mask))


def _exact(binding: ModelBinding, mask: int) -> float:
    return binding.distances()(mask)


#: heuristic name -> evaluator of a bit-mask state of a bound model
HEURISTICS: dict[str, Callable[[ModelBinding, int], float]] = {
    "h-add": _h_add,
    "h-max": _h_max,
    "h-ff": _h_ff,
    "h-star": _exact,
}


def _ids(mask: int) -> list[int]:
    ids = []
    while mask:
        low = mask & -mask
        ids.append(low.bit_length() - 1)
        mask ^= low
    return ids


#: ``gamma`` of a discount-aware potential that takes the learner's discount from the wrapper
LEARNER = "learner"


class ModelBinding:
    """One abstract model prepared for heuristic evaluation, shared by the potentials of a
    process: the grounded task, a bit per classified fluent atom, the plan's initial state and
    (built on first use) the exact goal distances."""

    def __init__(
        self, abstraction: Abstraction, subgoals: Any, max_states: int = DEFAULT_MAX_STATES
    ):
        self.abstraction = abstraction
        self.ground = ground_task(abstraction.task)
        index = self.ground.index
        # only the atoms some operator or the goal mentions matter
        atoms = [a for a in abstraction.fluent_atoms if a in index]
        self._classify = AtomEvaluator(atoms, abstraction.classifiers) if atoms else None
        self.column_bits = [1 << index[a] for a in atoms]
        initial = getattr(subgoals, "fluents", None)
        self.initial = self.ground.mask(initial[0] if initial else subgoals[0])
        self.max_states = max_states
        self._distances: GoalDistances | None = None
        self._reachable_max: float | None = None

    def distances(self) -> GoalDistances:
        """h* over the explicit state space (explored from the task's ``:init`` on first use)."""
        if self._distances is None:
            self._distances = GoalDistances(self.ground, self.max_states)
            self._reachable_max = self._distances.max_finite()
        return self._distances

    def reachable_max(self) -> float:
        """H*: the largest finite h* among the states reachable from ``:init``."""
        self.distances()
        assert self._reachable_max is not None
        return self._reachable_max

    def state_key(self, ctx: ShapingContext) -> tuple[Any, Callable[[], int]]:
        """A cheap cache key for ŝ of ``ctx`` and a function that builds its bit mask."""
        if ctx.atoms is not None or self._classify is None:
            mask = self.ground.mask(ctx.abstract_state)
            return mask, lambda: mask
        columns = frozenset(self._classify.holding(ctx.obs))
        bits = self.column_bits

        def mask() -> int:
            out = 0
            for c in columns:
                out |= bits[c]
            return out

        return columns, mask


_BINDINGS: dict[tuple[int, int, int], tuple[Any, Any, ModelBinding]] = {}


def bind_model(ctx: ShapingContext, max_states: int = DEFAULT_MAX_STATES) -> ModelBinding:
    """The :class:`ModelBinding` of ``ctx``'s abstraction and plan (made once per process)."""
    abstraction = ctx.abstraction
    if abstraction is None:
        raise PotentialError(
            "heuristic potentials evaluate h on the abstract state and need the context's "
            "abstraction (its PDDL task and classifiers); the shaping wrapper and the "
            "invariance checker provide it"
        )
    key = (id(abstraction), id(ctx.subgoals), max_states)
    hit = _BINDINGS.get(key)
    if hit is None or hit[0] is not abstraction or hit[1] is not ctx.subgoals:
        binding = ModelBinding(abstraction, ctx.subgoals, max_states)
        _BINDINGS[key] = (abstraction, ctx.subgoals, binding)  # keeps both alive: ids stay unique
        return binding
    return hit[2]


class _PerModel:
    """What a potential derives from one bound model: its φ per abstract state."""

    __slots__ = ("binding", "by_key", "by_mask", "extra", "normalizer")

    def __init__(self, binding: ModelBinding):
        self.binding = binding
        self.by_key: dict[Any, float] = {}
        self.by_mask: dict[int, float] = {}
        self.normalizer = 1.0
        self.extra: dict[Any, Any] = {}


class _BoundPotential(Potential):
    """Shared machinery: per-model state, and φ cached per abstract state."""

    def __init__(self, scale: float = 1.0, max_states: int = DEFAULT_MAX_STATES):
        super().__init__(scale)
        self.max_states = int(max_states)
        self._models: IdentityCache[_PerModel] = IdentityCache()

    def _model(self, ctx: ShapingContext) -> _PerModel:
        binding = bind_model(ctx, self.max_states)
        return self._models.get(binding, lambda: self._prepared(_PerModel(binding)))

    def _prepared(self, model: _PerModel) -> _PerModel:
        self._prepare(model)
        return model

    def _prepare(self, model: _PerModel) -> None:
        """Fill in the per-model constants (normalizer, dead-end value, ...)."""

    def _value(self, model: _PerModel, mask: int) -> float:
        raise NotImplementedError

    def _cached(self, model: _PerModel, ctx: ShapingContext) -> float:
        key, mask = model.binding.state_key(ctx)
        value = model.by_key.get(key)
        if value is None:
            bits = mask()
            value = model.by_mask.get(bits)
            if value is None:
                value = model.by_mask[bits] = float(self._value(model, bits))
            model.by_key[key] = value
        return value


class HeuristicPotential(_BoundPotential):
    """φ(ŝ) = −h(ŝ)/h(ŝ0) (linear) or −(1 − γ^h)/(1 − γ^h(ŝ0)) (discount-aware).

    Args:
        heuristic: ``"h-add"``, ``"h-ff"``, ``"h-max"`` or ``"h-star"`` (see the module
            docstring).
        gamma: ``None`` for the linear potential; for the discount-aware one the learner's
            discount, or ``"learner"`` to take it from the shaping wrapper
            (:meth:`for_discount`; the registered ``h-*-discounted`` do).
        scale: multiplies φ.
        normalize: divide by the value at the plan's initial state ŝ0 (φ(ŝ0) = −1).
        dead_end: h assigned where the goal is unreachable (linear potential only); default
            h0 · (1 + H*)/h*(ŝ0) (see the module docstring).
        max_states: the largest state space enumerated for h* (and for the default
            ``dead_end``).

    Example:
        >>> from planshape.shaping.potentials import ShapingContext
        >>> from planshape.planning import grid_pddl, parse_task
        >>> from planshape.shaping.abstraction import Abstraction
        >>> task = parse_task(*grid_pddl(1, 4, start=(0, 0), goal=(0, 3)).texts)
        >>> cells = {f"cell_0_{j}": float(j) for j in range(4)}
        >>> at = lambda obs, c: abs(obs[..., 0] - cells[c]) < 0.5
        >>> abstraction = Abstraction(task, {"robot_at": at})
        >>> ctx = ShapingContext(obs=np.array([1.0]), progress=0, t=0, abstraction=abstraction,
        ...                      subgoals=[task.init])
        >>> HeuristicPotential("h-ff")(ctx), HeuristicPotential("h-star", gamma=0.5)(ctx)
        (-0.6666666666666666, -0.8571428571428571)
    """

    def __init__(
        self,
        heuristic: str = "h-ff",
        *,
        gamma: float | None = None,
        scale: float = 1.0,
        normalize: bool = True,
        dead_end: float | None = None,
        max_states: int = DEFAULT_MAX_STATES,
    ):
        super().__init__(scale, max_states)
        if heuristic not in HEURISTICS:
            raise BadInputError(
                f"unknown heuristic {heuristic!r}; known: {', '.join(sorted(HEURISTICS))}"
            )
        if (
            gamma is not None
            and gamma != LEARNER
            and (isinstance(gamma, bool) or not isinstance(gamma, int | float) or not 0 < gamma < 1)
        ):
            raise BadInputError(
                f"gamma must be a discount in (0, 1), {LEARNER!r} (the learner's, set by the "
                f"shaping wrapper) or None, not {gamma!r}"
            )
        if dead_end is not None and not (math.isfinite(dead_end) and dead_end >= 0):
            raise BadInputError(f"dead_end must be a finite h value ≥ 0, not {dead_end!r}")
        self.heuristic = heuristic
        self.gamma = gamma
        self.normalize = normalize
        self.dead_end = dead_end
        self._evaluate = HEURISTICS[heuristic]

    def __repr__(self) -> str:
        return (
            f"HeuristicPotential({self.heuristic!r}, gamma={self.gamma}, scale={self.scale}, "
            f"normalize={self.normalize})"
        )

    def for_discount(self, gamma: float) -> Potential:
        """With ``gamma="learner"``, a copy discounting with the learner's ``gamma``; with a
        fixed or no ``gamma``, ``self``."""
        if self.gamma != LEARNER:
            return self
        if not 0 < gamma < 1:
            raise BadInputError(
                f"potential {self.name!r} is −(1 − γ^h)/(1 − γ^h0) with the learner's γ, which "
                f"must be below 1 (got {gamma}); use {self.heuristic!r}, its undiscounted form"
            )
        copied = copy.copy(self)
        copied.gamma = float(gamma)
        copied._models = IdentityCache()
        return copied

    def h(self, ctx: ShapingContext) -> float:
        """h(ŝ) of the context's abstract state, unscaled (``math.inf`` at a dead end)."""
        model = self._model(ctx)
        _, mask = model.binding.state_key(ctx)
        return self._evaluate(model.binding, mask())

    def _prepare(self, model: _PerModel) -> None:
        if self.gamma == LEARNER:
            raise PotentialError(
                f"potential {self.name!r} discounts with the learner's γ, which the shaping "
                "wrapper and the invariance checker give it; to evaluate it directly, take "
                "potential.for_discount(gamma) first"
            )
        binding = model.binding
        h0 = self._evaluate(binding, binding.initial)
        model.extra["h0"] = h0
        if self.gamma is not None:
            if self.normalize and 0 < h0 < math.inf:
                model.normalizer = 1.0 / (1.0 - self.gamma**h0)
            else:
                model.normalizer = 1.0 / (1.0 - self.gamma)
            return
        if self.normalize and 0 < h0 < math.inf:
            model.normalizer = 1.0 / h0
        model.extra["dead"] = (
            self.dead_end if self.dead_end is not None else self._dead(binding, h0)
        )

    @staticmethod
    def _dead(binding: ModelBinding, h0: float) -> float:
        finite_h0 = h0 if 0 < h0 < math.inf else 1.0
        try:
            distances = binding.distances()
        except BadInputError:
            return 2.0 * finite_h0 + 1.0
        exact0 = distances(binding.initial)
        if not 0 < exact0 < math.inf:
            return 1.0 + binding.reachable_max()
        return finite_h0 * (1.0 + binding.reachable_max()) / exact0

    def _value(self, model: _PerModel, mask: int) -> float:
        h = self._evaluate(model.binding, mask)
        if self.gamma is not None:
            discounted = 0.0 if math.isinf(h) else self.gamma**h
            return -(1.0 - discounted) * model.normalizer
        if math.isinf(h):
            h = model.extra["dead"]
        return -h * model.normalizer

    def potential(self, ctx: ShapingContext) -> float:
        return self._cached(self._model(ctx), ctx)

    def specialize(self, ctx: ShapingContext) -> StepPotential | None:
        """φ remembered per key of the classifiers (φ is a function of ŝ, and ŝ of the key)."""
        return _per_key(self, ctx, self.potential)


class HStarGeodesic(_BoundPotential):
    """h* with sub-place resolution: the distance to the goal along the abstract state space,
    in moves, measured continuously inside a place.

    For an abstract state ŝ with h = h*(ŝ) > 0, each *optimal move* ŝ → ŝ' (h*(ŝ') = h − 1)
    moves one entity e (the first, in the ``locate`` hook's order, whose place changes) from
    place a to place b, a move of length u = |b − a| (one cell on a grid model). With p the
    entity's position,

        φ = −min over optimal moves of  min(h + |p − a|/u,  h − 1 + |p − b|/u)  / h*(ŝ0),

    so φ = −h/h*(ŝ0) at the centre of a place, as h-star, and between centres it rises
    continuously as the entity approaches the next place of a shortest path, instead of being
    flat over a whole cell (2.5 steps of the end effector). Entering the next place never lowers
    φ (its own first term continues the second); at a turn of the path it rises by up to 0.4 of
    a move. φ = 0 on goal states; dead ends as the linear :class:`HeuristicPotential`
    (h = h_dead); without ``locate``/``positions`` hooks, or where no located entity moves,
    φ = −h/h*(ŝ0). Like h*, it is a function of the observation alone and needs no plan: off
    the plan it still points along the shortest path around the walls.

    Args:
        scale: multiplies φ.
        dead_end: h* assigned where the goal is unreachable (see :class:`HeuristicPotential`).
        max_states: the largest state space enumerated for h*.
    """

    def __init__(
        self,
        scale: float = 1.0,
        dead_end: float | None = None,
        max_states: int = DEFAULT_MAX_STATES,
    ):
        super().__init__(scale, max_states)
        self.dead_end = dead_end

    def _prepare(self, model: _PerModel) -> None:
        binding = model.binding
        h0 = binding.distances()(binding.initial)
        model.normalizer = 1.0 / h0 if 0 < h0 < math.inf else 1.0
        model.extra["dead"] = (
            self.dead_end if self.dead_end is not None else HeuristicPotential._dead(binding, h0)
        )

    def _moves(self, model: _PerModel, ctx: ShapingContext, mask: int):
        """(h*, [(entity, place a, place b, length u)] of the optimal moves) of a state."""
        binding = model.binding
        distances = binding.distances()
        h = distances(mask)
        moves: list[tuple[str, list[float], list[float], float]] = []
        if 0 < h < math.inf and ctx.geometry is not None:
            here = _located(ctx.geometry, binding.ground.atoms_of(mask))
            for after in distances.successors(mask):
                if distances(after) != h - 1:
                    continue
                there = _located(ctx.geometry, binding.ground.atoms_of(after))
                for entity, b in there.items():
                    a = here.get(entity)
                    if a is not None:
                        length = math.dist(a, b)
                        if length > 0:
                            moves.append((entity, a, b, length))
                            break
        return h, moves

    def _entry(self, ctx: ShapingContext) -> tuple[_PerModel, tuple[float, list]]:
        model = self._model(ctx)
        key, mask = model.binding.state_key(ctx)
        entry = model.by_key.get(key)
        if entry is None:
            entry = model.by_key[key] = self._moves(model, ctx, mask())
        return model, entry

    @staticmethod
    def _along(model: _PerModel, entry: tuple[float, list], geometry: Any, obs: Any) -> float:
        """φ of ``obs`` in the abstract state whose (h*, optimal moves) are ``entry``."""
        h, moves = entry
        if h == 0:
            return 0.0
        if math.isinf(h):
            return -model.extra["dead"] * model.normalizer
        left = float(h)
        if moves:
            positions = geometry.positions(obs)
            left = math.inf
            for entity, a, b, length in moves:
                p = positions[entity]
                left = min(
                    left, h + point_distance(p, a) / length, h - 1 + point_distance(p, b) / length
                )
        return -left * model.normalizer

    def potential(self, ctx: ShapingContext) -> float:
        model, entry = self._entry(ctx)
        return self._along(model, entry, ctx.geometry, ctx.obs)

    def specialize(self, ctx: ShapingContext) -> StepPotential | None:
        """The abstract state's (h*, optimal moves) remembered per key of the classifiers, with
        φ itself where it is constant in the cell; the continuous part measured on every step
        by :meth:`_along`'s arithmetic in the same order (so the same floats), without its
        per-step tests and conversions."""
        model, geometry = self._model(ctx), ctx.geometry

        def remember(here: ShapingContext) -> Any:
            h, moves = self._entry(here)[1]
            if h == 0 or math.isinf(h) or not moves:  # φ does not depend on where in the cell
                return self._along(model, (h, moves), geometry, here.obs)
            return h, h - 1, model.normalizer, _measured(moves)

        of_values = getattr(geometry, "positions_of_values", None)
        dist, inf = math.dist, math.inf

        def measure(remembered: Any, obs: Any, values: list[Any] | None) -> float:
            if type(remembered) is float:
                return remembered
            h, h_next, normalizer, groups = remembered
            if values is not None and of_values is not None:  # obs.tolist() made once
                positions = of_values(values)
            else:
                positions = geometry.positions(obs)
            left = inf
            for entity, starts, ends in groups:
                p = positions[entity]
                for a, length in starts:
                    via = h + dist(p, a) / length
                    if via < left:
                        left = via
                for b, length in ends:
                    via = h_next + dist(p, b) / length  # h - 1 + …, added as _along adds
                    if via < left:
                        left = via
            return -left * normalizer

        return _per_key(self, ctx, remember, measure)


def _measured(moves: list[tuple[str, Any, Any, float]]) -> tuple[Any, ...]:
    """The optimal moves of a cell as :class:`HStarGeodesic`'s step measures them: per entity,
    its distinct (start, length) and its (end, length) pairs. The moves of one entity leave from
    one place, so a step measures the way back to it once, not once per move; the least of
    the terms is the same float in any order and without repeats.

    Example:
        >>> _measured([("ee", [0, 0], [0, 1], 1.0), ("ee", [0, 0], [1, 0], 1.0)])
        (('ee', (([0, 0], 1.0),), (([0, 1], 1.0), ([1, 0], 1.0))),)
    """
    starts: dict[str, list[tuple[Any, float]]] = {}
    ends: dict[str, list[tuple[Any, float]]] = {}
    for entity, a, b, length in moves:
        if (a, length) not in starts.setdefault(entity, []):
            starts[entity].append((a, length))
        ends.setdefault(entity, []).append((b, length))
    return tuple((e, tuple(starts[e]), tuple(ends[e])) for e in starts)


def _per_key(
    potential: _BoundPotential,
    ctx: ShapingContext,
    remember: Callable[[ShapingContext], Any],
    measure: Callable[[Any, Any, list[Any] | None], float] | None = None,
) -> StepPotential | None:
    """A step function that remembers, per key of the model's classifiers, what
    ``remember(context)`` gives for the first observation seen with that key (observations
    with one key have one abstract state), and returns it, or ``measure(remembered, obs,
    values)``, where ``values`` is ``obs.tolist()`` when the key was read from it (a flat
    observation whose classifiers can key values), else None. None when the classifiers have
    no keys (the model's places are neither one grid nor regions)."""
    classify = potential._model(ctx).binding._classify
    if classify is None or not classify.keyed:
        return None
    subgoals, geometry, abstraction = ctx.subgoals, ctx.geometry, ctx.abstraction
    remembered: dict[tuple[Any, ...], Any] = {}
    key_of_values = classify.values_key(ctx.obs)

    def phi(obs: Any, progress: int) -> float:
        if key_of_values is not None and type(obs) is np.ndarray and obs.ndim == 1:
            values = obs.tolist()
            key = key_of_values(values)
        else:
            values, key = None, classify.key(obs)
        value = remembered.get(key)
        if value is None:
            if len(remembered) >= 1 << 16:
                remembered.clear()
            here = ShapingContext(obs, progress, 0, subgoals, geometry, abstraction)
            value = remembered[key] = remember(here)
        return value if measure is None else measure(value, obs, values)

    return phi


def _located(geometry: Any, atoms: frozenset) -> Mapping[str, list[float]]:
    return {e: np.asarray(v, float).tolist() for e, v in geometry.locate(atoms).items()}
