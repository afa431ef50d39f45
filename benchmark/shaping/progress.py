"""When a subgoal counts as reached, and how plan progress (``max_idx``) moves.

Definitions (they are what the tests check):

* The *fluent part* of an abstract state is the set of its atoms whose predicate is fluent.
* With ``match="fluents"`` (the default) subgoal ŝ_i is **reached** in observation s when every
  fluent atom of ŝ_i holds in s. Atoms that ŝ_i does not contain may hold or not: overlapping
  regions or a box that is also touched never hide progress.
* With ``match="exact"`` subgoal ŝ_i is reached when the fluent part of Abstract(s) *equals* the
  fluent part of ŝ_i: this is ``Ŝ.index(ŝ)`` of the source paper's Algorithm 1, kept for
  fidelity experiments.
* Progress starts, on ``reset``, at the furthest subgoal reached in the initial observation, or
  0 if none is. After each step it becomes ``max(progress, furthest subgoal reached now)``: it
  only moves forward, it may skip subgoals, and it never drops when the agent leaves a subgoal.

Example:
    >>> import numpy as np
    >>> from planshape.shaping.abstraction import Abstraction
    >>> from planshape.planning.model import PddlTask, PredicateSignature
    >>> task = PddlTask("d", "p", {"at": PredicateSignature("at", ("place",))},
    ...     {"object": None, "place": "object"}, {"a": "place", "b": "place", "c": "place"},
    ...     frozenset({("at", "a")}), frozenset({("at", "c")}), frozenset())
    >>> centres = {"a": 0.0, "b": 1.0, "c": 2.0}
    >>> abstraction = Abstraction(task, {"at": lambda obs, p: abs(obs[..., 0] - centres[p]) < .3})
    >>> plan = [frozenset({("at", p)}) for p in "abc"]
    >>> tracker = PlanProgress(plan, abstraction)
    >>> progress = tracker.initial(np.array([0.0]))
    >>> progress = tracker.advance(progress, np.array([2.0]))  # skipped b: still counts
    >>> progress, tracker.advance(progress, np.array([0.0]))  # walking back keeps progress
    (2, 2)
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, Literal

import numpy as np

from planshape.errors import BadInputError
from planshape.planning.model import AbstractState
from planshape.shaping.abstraction import Abstraction, batch_shape

SubgoalMatch = Literal["fluents", "exact"]


class PlanProgress:
    """Tracks the furthest subgoal of a plan that an episode has reached.

    Args:
        subgoals: Ŝ = [ŝ0 … ŝn], the plan's abstract states (a ``Plan.subgoals``; its
            ``fluents`` view is used when it has one, so full states are never built here).
        abstraction: the classifiers that decide which atoms hold.
        match: the reached test, ``"fluents"`` or ``"exact"`` (see the module docstring).
    """

    def __init__(
        self,
        subgoals: Sequence[AbstractState],
        abstraction: Abstraction,
        match: SubgoalMatch = "fluents",
    ):
        if match not in ("fluents", "exact"):
            raise BadInputError(f"match must be 'fluents' or 'exact', not {match!r}")
        if not subgoals:
            raise BadInputError("a plan has at least one subgoal (its initial state)")
        self.subgoals = subgoals
        self.abstraction = abstraction
        self.match = match
        fluent_parts = getattr(subgoals, "fluents", None) or [
            frozenset(a for a in s if not abstraction.is_static(a)) for s in subgoals
        ]
        if match == "fluents":
            atoms = sorted(frozenset().union(*fluent_parts))
        else:
            atoms = list(abstraction.fluent_atoms)
        self._evaluate = abstraction.evaluator(atoms)
        column = {atom: j for j, atom in enumerate(atoms)}
        required = np.zeros((len(self.subgoals), len(atoms)), dtype=bool)
        for i, part in enumerate(fluent_parts):
            required[i, [column[a] for a in part]] = True
        # Subgoal i is reached when the number of its required atoms that hold equals its
        # size (fluents) or, for exact matching, when no atom disagrees with it: both are one
        # matrix product per observation.
        self._required_f = required.T.astype(np.float64)
        self._sizes = required.sum(axis=1).astype(np.float64)
        self._signed = np.where(required, 1.0, -1.0).T
        # The same test for one observation, on Python sets (see _furthest_one): per subgoal
        # its required atom columns; per atom the subgoals that require it, furthest first; per
        # exact fluent part the furthest subgoal that has it.
        self._needs = [frozenset(np.flatnonzero(row).tolist()) for row in required]
        self._by_atom: list[list[int]] = [[] for _ in atoms]
        for i in reversed(range(len(self._needs))):
            for j in self._needs[i]:
                self._by_atom[j].append(i)
        self._always = max((i for i, need in enumerate(self._needs) if not need), default=-1)
        self._exact = {need: i for i, need in enumerate(self._needs)}
        self._keyed = self.match == "fluents" and self._evaluate.keyed
        self._furthest_by_key: dict[tuple[tuple[Any, ...], int], int] = {}
        # the key of a flat observation from its tolist(), once the evaluator has checked it
        # (the first keyed observation sets it): advance's lookup without the call layers
        self._values_key: Callable[[list[Any]], tuple[Any, ...]] | None = None

    @property
    def final(self) -> int:
        """The index of the last subgoal (the plan's length)."""
        return len(self.subgoals) - 1

    def reached(self, obs: Any) -> np.ndarray:
        """Which subgoals are reached: shape ``batch_shape + (len(subgoals),)``."""
        held = self._evaluate(obs).astype(np.float64)
        if self.match == "fluents":
            return held @ self._required_f == self._sizes
        # exact: Σ_j sign_ij·held_j equals size_i only when every required atom holds and no
        # other atom does
        return held @ self._signed == self._sizes

    def furthest(self, obs: Any) -> np.ndarray | int:
        """Index of the furthest subgoal reached in ``obs``, or -1 when none is."""
        if not batch_shape(obs):
            return self._furthest_one(obs, -1)
        reached = self.reached(obs)
        if reached.ndim == 1:
            hits = np.flatnonzero(reached)
            return int(hits[-1]) if hits.size else -1
        last = reached.shape[-1] - 1 - np.argmax(reached[..., ::-1], axis=-1)
        return np.where(reached.any(axis=-1), last, -1)

    def initial(self, obs: Any) -> np.ndarray | int:
        """Progress right after ``reset``: the furthest subgoal reached, at least 0."""
        furthest = self.furthest(obs)
        return max(furthest, 0) if isinstance(furthest, int) else np.maximum(furthest, 0)

    def advance(self, progress: np.ndarray | int, obs: Any) -> np.ndarray | int:
        """Progress after a step to ``obs``: never smaller than before."""
        if type(obs) is np.ndarray and obs.ndim == 1:  # one flat observation: the step's path
            values_key = self._values_key
            if values_key is not None and type(progress) is int:
                answer = self._furthest_by_key.get((values_key(obs.tolist()), progress))
                if answer is not None:
                    return answer
            return self._furthest_one(obs, int(progress))
        if not batch_shape(obs):  # one observation of another form
            return self._furthest_one(obs, int(progress))
        return np.maximum(progress, self.furthest(obs))

    def _furthest_one(self, obs: Any, floor: int) -> int:
        """max(floor, furthest subgoal reached in one observation), the per-step path.

        Only subgoals that require an atom that holds (or require none) can be reached, so the
        search walks the held atoms' subgoals, furthest first, and stops at ``floor``. It
        gives what :meth:`reached` gives (a test checks this on random observations).
        """
        if self._keyed:  # what holds is a function of the classifiers' keys: remember answers
            if self._values_key is None:
                self._values_key = self._evaluate.values_key(obs)
            remembered = (self._evaluate.key(obs), floor)
            answer = self._furthest_by_key.get(remembered)
            if answer is None:
                if len(self._furthest_by_key) >= 1 << 16:
                    self._furthest_by_key.clear()
                held = self._evaluate.holding(obs)
                answer = self._furthest_by_key[remembered] = self._search(held, floor)
            return answer
        held = self._evaluate.holding(obs)
        if self.match == "exact":
            return max(floor, self._exact.get(frozenset(held), -1))
        return self._search(held, floor)

    def _search(self, held: set[int] | frozenset[int], floor: int) -> int:
        best = max(floor, self._always)
        needs = self._needs
        for j in held:
            for i in self._by_atom[j]:
                if i <= best:
                    break
                if needs[i] <= held:
                    best = i
                    break
        return best
