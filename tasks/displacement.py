"""A :class:`~planshape.shaping.potentials.Geometry` of displacements between points.

``Geometry.locate(subgoal)`` sees only the abstract subgoal, but in MetaWorld and Fetch the place
an entity must reach moves: the goal is re-drawn every episode and the hand must follow the
object. Measuring each entity *relative to its reference point* makes the target a constant
again: the entity ``"hand-to-puck"`` is ``fingertips − puck`` and the subgoal ``(hand-at
gripper puck)`` wants it at ``0``. ``positions(obs)`` computes every displacement from the
current observation, so a distance potential stays a function of the current state (nothing is
remembered between calls).

Example:
    >>> import numpy as np
    >>> def hand_to_goal(obs):
    ...     return obs[..., 0:2] - obs[..., 2:4]
    >>> geometry = DisplacementGeometry(
    ...     displacements={"hand-to-goal": hand_to_goal},
    ...     targets={"hand-at": ("hand-to-goal", (0.0, 0.0))})
    >>> geometry.locate(frozenset({("hand-at", "gripper", "target")}))
    {'hand-to-goal': array([0., 0.])}
    >>> geometry.positions(np.array([1.0, 1.0, 0.0, 1.0]))
    {'hand-to-goal': array([1., 0.])}
    >>> geometry.locate(frozenset())
    {}
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from planshape.planning.model import AbstractState

Displacement = Callable[[Any], np.ndarray]


@dataclass(frozen=True)
class DisplacementGeometry:
    """Entities are displacement vectors; each fluent predicate wants one of them at a target.

    Args:
        displacements: entity name -> function of the observation giving the entity's current
            displacement (any length; leading batch axes allowed).
        targets: fluent predicate -> ``(entity, target displacement)``. The order is the
            priority order of :meth:`locate` (put the hand's predicates before the object's).
            Predicates left out (e.g. ``holding``) place no entity.
    """

    displacements: Mapping[str, Displacement]
    targets: Mapping[str, tuple[str, Sequence[float]]]
    #: displacements are differences of points, not points of one frame: they do not chain
    shared_frame: ClassVar[bool] = False

    def __post_init__(self) -> None:
        unknown = sorted({e for e, _ in self.targets.values()} - set(self.displacements))
        if unknown:
            raise ValueError(
                f"targets name entities {unknown} that have no displacement function; add them "
                f"to displacements (known: {sorted(self.displacements)})"
            )
        object.__setattr__(self, "_located", {})

    def locate(self, subgoal: AbstractState) -> dict[str, np.ndarray]:
        """Entity -> target displacement for every predicate of ``subgoal`` that places one
        (computed once per subgoal: potentials ask on every step)."""
        cache: dict[AbstractState, dict[str, np.ndarray]] = self._located  # type: ignore[attr-defined]
        located = cache.get(subgoal)
        if located is None:
            located = cache[subgoal] = self._locate(subgoal)
        return located

    def _locate(self, subgoal: AbstractState) -> dict[str, np.ndarray]:
        present = {atom[0] for atom in subgoal}
        located: dict[str, np.ndarray] = {}
        for predicate, (entity, target) in self.targets.items():
            if predicate in present and entity not in located:
                located[entity] = np.asarray(target, dtype=float)
        return located

    def positions(self, obs: Any) -> dict[str, np.ndarray]:
        """Every entity's current displacement in ``obs``."""
        return {entity: np.asarray(fn(obs)) for entity, fn in self.displacements.items()}
