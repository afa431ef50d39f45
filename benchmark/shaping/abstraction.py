"""Predicates, classifiers and the abstract state of a low-level state (Definitions 1 and 5).

A *classifier* decides whether one ground atom holds in an observation. It is an ordinary
callable ``classifier(obs, *objects) -> bool`` (the source paper's c_ψ(o1, …, om, s)). When a
predicate has many groundings (a grid of cells), wrap a function that answers all of them at once
in :class:`Vectorized`: it receives the observation and the list of object tuples and returns a
boolean array whose last axis runs over the groundings. Observations may carry leading batch
axes; per-atom classifiers written with ``obs[..., i]`` handle them unchanged.

Static predicates (those no action changes, e.g. ``neighbors``) are never classified: their
truth is the problem's ``:init``.

Example:
    >>> import numpy as np
    >>> from planshape.planning.model import PddlTask, PredicateSignature
    >>> task = PddlTask(
    ...     domain_name="d", problem_name="p",
    ...     predicates={"near": PredicateSignature("near", ("place",)),
    ...                 "linked": PredicateSignature("linked", ("place", "place"))},
    ...     types={"object": None, "place": "object"},
    ...     objects={"a": "place", "b": "place"},
    ...     init=frozenset({("linked", "a", "b")}), goal=frozenset({("near", "b")}),
    ...     static_predicates=frozenset({"linked"}))
    >>> centres = {"a": 0.0, "b": 1.0}
    >>> def near(obs, place):
    ...     return abs(obs[..., 0] - centres[place]) < 0.25
    >>> abstraction = Abstraction(task, {"near": near})
    >>> sorted(abstraction.abstract_state(np.array([0.9])))
    [('linked', 'a', 'b'), ('near', 'b')]
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Hashable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from planshape.errors import BadInputError, ClassifierError, RegistrationError, UnknownIdError
from planshape.planning.model import AbstractState, Atom, PddlTask, format_atom

Classifier = Callable[..., Any]


@dataclass(frozen=True)
class Vectorized:
    """Marks a classifier that answers every requested grounding of its predicate in one call.

    ``fn(obs, groundings)`` gets the observation (with any leading batch axes) and a list of
    object tuples, and returns a boolean array of shape ``obs.shape[:-1] + (len(groundings),)``.

    ``holding(obs, groundings)``, optional, answers the same question for *one* observation
    (no batch axes) sparsely: the positions in ``groundings`` of the groundings that hold. It
    is the per-step fast path of the shaping wrapper, worth writing when few groundings hold
    at a time and they can be found without testing every one (a grid cell from a floor
    division, a spatial hash). It must agree with ``fn``; when it is absent, ``fn`` is used.

    ``key(obs)``, optional, is a discretization of one observation that determines what
    ``holding`` answers (the same key, the same groundings hold: a grid cell's index). When
    every classifier of an evaluator has one, the evaluator remembers each answer by its keys,
    and a shaping step costs the keys and one lookup.

    ``key_of_values(values)``, optional with ``key``, is the same key computed from
    ``obs.tolist()`` of a flat (1-D) observation array. When every classifier of an evaluator
    has one, the evaluator converts the observation once for all of them instead of each
    classifier slicing and converting it on its own (on push's two entities, about half of a
    key's cost). It must equal ``key(obs)``: the evaluator compares the two on the first
    observation it keys and refuses a classifier whose two keys disagree.

    Example:
        >>> import numpy as np
        >>> centres = {"a": 0.0, "b": 1.0}
        >>> def near_all(obs, groundings):
        ...     c = np.array([centres[g[0]] for g in groundings])
        ...     return np.abs(obs[..., :1] - c) < 0.25
        >>> def near_which(obs, groundings):
        ...     return [i for i, g in enumerate(groundings) if abs(obs[0] - centres[g[0]]) < 0.25]
        >>> near = Vectorized(near_all, holding=near_which)
        >>> near.fn(np.array([0.1]), [("a",), ("b",)]).tolist()
        [True, False]
        >>> list(near.holding(np.array([0.1]), [("a",), ("b",)]))
        [0]
        >>> cell = Vectorized(near_all, holding=near_which, key=lambda obs: round(float(obs[0])),
        ...                   key_of_values=lambda values: round(values[0]))
        >>> cell.key(np.array([0.9])) == cell.key_of_values(np.array([0.9]).tolist())
        True
    """

    fn: Callable[[np.ndarray, Sequence[tuple[str, ...]]], np.ndarray]
    holding: Callable[[Any, Sequence[tuple[str, ...]]], Iterable[int]] | None = None
    key: Callable[[Any], Hashable] | None = None
    key_of_values: Callable[[list[Any]], Hashable] | None = None


def check_classifiers(task: PddlTask, classifiers: Mapping[str, Classifier]) -> None:
    """Fail fast, naming the predicates, when classifiers do not cover the domain exactly.

    Every fluent predicate needs a classifier; a classifier must name a predicate the domain
    declares, and static predicates take their truth from ``:init`` instead.
    """
    where = f"domain {task.domain_name!r}" + (f" ({task.domain_file})" if task.domain_file else "")
    unknown = sorted(set(classifiers) - set(task.predicates))
    if unknown:
        raise UnknownIdError(
            "predicate",
            unknown[0],
            task.predicates,
            hint=f"classifiers name predicates that {where} does not declare: {unknown}",
        )
    static = sorted(set(classifiers) & task.static_predicates)
    if static:
        raise RegistrationError(
            f"classifiers given for static predicates {static} of {where}: no action changes "
            "them, so their truth comes from the problem's :init. Remove these classifiers."
        )
    missing = sorted(task.fluent_predicates - set(classifiers))
    if missing:
        raise RegistrationError(
            f"fluent predicates {missing} of {where} have no classifier; add one per predicate "
            "(a callable classifier(obs, *objects) -> bool)."
        )


#: how many keyed answers an evaluator remembers before it starts again (a 0.05 m grid over the
#: planar workspace has 143 cells; push's (end effector, object) pairs about 10^4)
_MAX_REMEMBERED = 1 << 16


class AtomEvaluator:
    """Evaluates a fixed, ordered list of fluent atoms on an observation, as a boolean array.

    Atoms are grouped by predicate so that a :class:`Vectorized` classifier is called once per
    predicate per observation.
    """

    def __init__(self, atoms: Sequence[Atom], classifiers: Mapping[str, Classifier]):
        self.atoms: tuple[Atom, ...] = tuple(atoms)
        groups: dict[str, list[int]] = {}
        for index, atom in enumerate(self.atoms):
            groups.setdefault(atom[0], []).append(index)
        self._groups = [
            (
                predicate,
                classifiers[predicate],
                np.asarray(indices, dtype=np.intp),
                [self.atoms[i][1:] for i in indices],
                indices,
            )
            for predicate, indices in groups.items()
        ]
        # Atoms grouped by predicate keep their order inside a group, so with one predicate
        # (the common case for progress tracking) the classifier's answer is the result.
        self._single = len(self._groups) == 1
        # With a key on every classifier, one observation's answer is remembered by its keys.
        keys = [getattr(c, "key", None) for _, c, _, _, _ in self._groups]
        self._keys = keys if keys and all(k is not None for k in keys) else None
        self._held_by_key: dict[tuple[Hashable, ...], frozenset[int]] = {}
        # ... and, when every classifier can key a flat observation's values, from one tolist()
        readers = [getattr(c, "key_of_values", None) for _, c, _, _, _ in self._groups]
        self._key_of_values = (
            _joined_keys(readers)
            if self._keys is not None and all(r is not None for r in readers)
            else None
        )
        self._key_of_values_checked = False

    def __call__(self, obs: Any) -> np.ndarray:
        """Truth of every atom: shape ``batch_shape + (len(atoms),)``.

        ``obs`` is an array (batch axes first, features last) or a mapping of such arrays,
        as Gymnasium's Dict spaces give (the batch shape is then read from its first value).
        """
        if not isinstance(obs, np.ndarray | Mapping):
            obs = np.asarray(obs)
        if self._single:
            predicate, classifier, _, groundings, _ = self._groups[0]
            return _classify(predicate, classifier, obs, groundings)
        out = np.zeros((*batch_shape(obs), len(self.atoms)), dtype=bool)
        for predicate, classifier, indices, groundings, _ in self._groups:
            out[..., indices] = _classify(predicate, classifier, obs, groundings)
        return out

    def holding(self, obs: Any) -> set[int] | frozenset[int]:
        """The positions in :attr:`atoms` of the atoms that hold in *one* observation.

        The same truth as ``__call__``, computed without building arrays where the classifiers
        allow: per-atom classifiers are called once each, and a :class:`Vectorized` one with
        a ``holding`` function lists only what holds. This is the shaping wrapper's per-step
        path, where a handful of small numpy operations would cost more than the classifiers.
        """
        if not isinstance(obs, np.ndarray | Mapping):
            obs = np.asarray(obs)
        if self._keys is not None:
            key = self.key(obs)
            remembered = self._held_by_key.get(key)
            if remembered is None:
                if len(self._held_by_key) >= _MAX_REMEMBERED:
                    self._held_by_key.clear()
                remembered = self._held_by_key[key] = frozenset(self._holding(obs))
            return remembered
        return self._holding(obs)

    @property
    def keyed(self) -> bool:
        """Whether every classifier has a key, so that what holds is a function of :meth:`key`."""
        return self._keys is not None

    def key(self, obs: Any) -> tuple[Hashable, ...]:
        """The classifiers' keys of one observation (only when :attr:`keyed`): observations
        with equal keys have the same atoms holding."""
        key_of_values = self._key_of_values
        if key_of_values is not None and type(obs) is np.ndarray and obs.ndim == 1:
            key = key_of_values(obs.tolist())
            if not self._key_of_values_checked:
                self._check_key_of_values(obs, key)
            return key
        return self._key_per_classifier(obs)

    def values_key(self, obs: Any) -> Callable[[list[Any]], tuple[Hashable, ...]] | None:
        """:meth:`key` of a flat observation array from its ``tolist()``, for a caller that
        converts the observation once for several uses; None where the classifiers cannot key
        values or ``obs`` (a sample, checked here as :meth:`key` checks) is not flat."""
        if self._key_of_values is None or type(obs) is not np.ndarray or obs.ndim != 1:
            return None
        self.key(obs)
        return self._key_of_values

    def _key_per_classifier(self, obs: Any) -> tuple[Hashable, ...]:
        keys = self._keys
        assert keys is not None, "key() of an evaluator whose classifiers have no key"
        if len(keys) == 1:
            return (keys[0](obs),)
        return tuple([k(obs) for k in keys])

    def _check_key_of_values(self, obs: np.ndarray, key: tuple[Hashable, ...]) -> None:
        """Refuse classifiers whose ``key_of_values`` disagrees with their ``key``."""
        for (predicate, *_), fast, slow in zip(
            self._groups, key, self._key_per_classifier(obs), strict=True
        ):
            if fast != slow:
                raise ClassifierError(
                    f"the Vectorized classifier of {predicate!r} keys observation "
                    f"{obs.tolist()} as {slow!r} with key(obs) but as {fast!r} with "
                    "key_of_values(obs.tolist()); the two must be the same function of the "
                    "observation: fix key_of_values or leave it out"
                )
        self._key_of_values_checked = True

    def _holding(self, obs: Any) -> set[int]:
        held: set[int] = set()
        for predicate, classifier, _, groundings, positions in self._groups:
            if not isinstance(classifier, Vectorized):
                for index, objects in zip(positions, groundings, strict=True):
                    if _holds(predicate, classifier, obs, objects):
                        held.add(index)
                continue
            holding = classifier.holding
            if holding is not None:
                try:
                    found = holding(obs, groundings)
                    if type(found) is not list:  # drawn here, so that its errors are named
                        found = list(found)
                except Exception as exc:
                    raise _classifier_error(predicate, exc, groundings) from exc
            else:
                found = np.flatnonzero(_classify(predicate, classifier, obs, groundings)).tolist()
            held.update(map(positions.__getitem__, found))
        return held


def _joined_keys(
    readers: Sequence[Callable[[list[Any]], Hashable]],
) -> Callable[[list[Any]], tuple[Hashable, ...]]:
    """One function giving every classifier's key from one observation's values (one and two
    classifiers, the common cases, without building a list)."""
    if len(readers) == 1:
        (only,) = readers
        return lambda values: (only(values),)
    if len(readers) == 2:
        first, second = readers
        return lambda values: (first(values), second(values))
    return lambda values: tuple([read(values) for read in readers])


def batch_shape(obs: Any) -> tuple[int, ...]:
    """The leading (batch) axes of an observation array, or of a mapping's first array."""
    if isinstance(obs, Mapping):
        obs = next(iter(obs.values()))
    shape = obs.shape if isinstance(obs, np.ndarray) else np.shape(obs)
    return shape[:-1]


def _classify(
    predicate: str, classifier: Classifier, obs: Any, groundings: list[tuple[str, ...]]
) -> np.ndarray:
    if isinstance(classifier, Vectorized):
        try:
            values = classifier.fn(obs, groundings)
        except Exception as exc:
            raise _classifier_error(predicate, exc, groundings) from exc
        values = np.asarray(values)
        expected = (*batch_shape(obs), len(groundings))
        if values.shape != expected:
            raise ClassifierError(
                f"vectorized classifier of predicate {predicate!r} returned shape {values.shape}, "
                f"expected {expected} (batch shape + number of groundings)"
            )
        return _as_truth(predicate, values, groundings[0] if groundings else ())
    columns = []
    for objects in groundings:
        try:
            value = classifier(obs, *objects)
        except Exception as exc:
            raise _atom_error(predicate, exc, objects) from exc
        columns.append(_as_truth(predicate, np.asarray(value), objects))
    return np.stack(columns, axis=-1) if columns else np.zeros((*batch_shape(obs), 0), bool)


def _classifier_error(
    predicate: str, exc: Exception, groundings: Sequence[tuple[str, ...]]
) -> ClassifierError:
    return ClassifierError(
        f"classifier of predicate {predicate!r} raised {type(exc).__name__}: {exc} "
        f"(objects {list(groundings[:3])}{'…' if len(groundings) > 3 else ''})"
    )


def _atom_error(predicate: str, exc: Exception, objects: tuple[str, ...]) -> ClassifierError:
    return ClassifierError(
        f"classifier of predicate {predicate!r} raised {type(exc).__name__} on objects "
        f"{format_atom((predicate, *objects))}: {exc}"
    )


def _holds(predicate: str, classifier: Classifier, obs: Any, objects: tuple[str, ...]) -> bool:
    """One per-atom classifier on one observation, with the checks of :func:`_classify`."""
    try:
        value = classifier(obs, *objects)
    except Exception as exc:
        raise _atom_error(predicate, exc, objects) from exc
    if value.__class__ is bool or value.__class__ is np.bool_:
        return bool(value)
    return bool(_as_truth(predicate, np.asarray(value), objects))


def _as_truth(predicate: str, values: np.ndarray, objects: tuple[str, ...]) -> np.ndarray:
    if values.dtype == bool:
        return values
    if values.dtype.kind in "iu" and np.isin(values, (0, 1)).all():
        return values.astype(bool)
    raise ClassifierError(
        f"classifier of predicate {predicate!r} on {format_atom((predicate, *objects))} returned "
        f"{values.dtype} values, not truth values; return a bool (or a boolean array)"
    )


class Abstraction:
    """A PDDL task's predicates bound to classifiers: observation -> abstract state.

    Args:
        task: the parsed domain and problem.
        classifiers: one classifier per fluent predicate (see :func:`check_classifiers`).
    """

    def __init__(self, task: PddlTask, classifiers: Mapping[str, Classifier]):
        check_classifiers(task, classifiers)
        self.task = task
        self.classifiers = dict(classifiers)
        self.static_atoms: AbstractState = task.static_atoms()
        self.fluent_atoms: tuple[Atom, ...] = tuple(
            (name, *objects)
            for name in sorted(task.fluent_predicates)
            for objects in self.groundings(name)
        )
        self._all = AtomEvaluator(self.fluent_atoms, self.classifiers)

    def groundings(self, predicate: str) -> list[tuple[str, ...]]:
        """Every tuple of objects of the right types for ``predicate``."""
        signature = self.task.predicates[predicate]
        pools = [self.task.objects_of_type(t) for t in signature.parameter_types]
        return list(itertools.product(*pools))

    def is_static(self, atom: Atom) -> bool:
        return atom[0] in self.task.static_predicates

    def evaluator(self, atoms: Sequence[Atom]) -> AtomEvaluator:
        """An evaluator for a subset of the fluent atoms (what progress tracking needs)."""
        unknown = [a for a in atoms if a[0] not in self.classifiers]
        if unknown:
            raise RegistrationError(f"atoms {unknown[:3]} are not fluent atoms of this domain")
        return AtomEvaluator(atoms, self.classifiers)

    def classify_batch(self, observations: Any) -> np.ndarray:
        """Truth of every fluent atom for a batch: shape ``(N, len(self.fluent_atoms))``."""
        return self._all(observations)

    def abstract_state(self, obs: Any) -> AbstractState:
        """ŝ = Abstract(s): the fluent atoms that hold, plus the static atoms of ``:init``."""
        if batch_shape(obs):
            raise BadInputError("abstract_state takes one observation; use classify_batch for many")
        atoms = self.fluent_atoms
        return self.static_atoms | {atoms[i] for i in self._all.holding(obs)}
