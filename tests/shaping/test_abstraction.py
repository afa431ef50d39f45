"""Classifier binding, abstract states and batch classification."""

from __future__ import annotations

import numpy as np
import pytest

from planshape.errors import ClassifierError, RegistrationError, UnknownIdError
from planshape.shaping.abstraction import Abstraction, Vectorized
from tests.toys import PLACES, RADIUS, at, line_task


def test_abstract_state_holds_static_and_classified_atoms():
    abstraction = Abstraction(line_task(), {"at": at})
    state = abstraction.abstract_state(np.array([0.45]))
    assert ("at", "middle") in state and ("at", "left") not in state
    assert ("adjacent", "left", "middle") in state  # static, from :init
    assert abstraction.fluent_atoms == (("at", "left"), ("at", "middle"), ("at", "right"))


def test_missing_classifier_names_the_fluent_predicate():
    with pytest.raises(RegistrationError, match=r"\['at'\].*no classifier"):
        Abstraction(line_task(), {})


def test_classifier_for_unknown_predicate_is_named_with_a_close_match():
    with pytest.raises(UnknownIdError, match="'att'.*did you mean 'at'"):
        Abstraction(line_task(), {"at": at, "att": at})


def test_classifier_for_static_predicate_is_refused():
    with pytest.raises(RegistrationError, match=r"static predicates \['adjacent'\]"):
        Abstraction(line_task(), {"at": at, "adjacent": lambda obs, a, b: True})


def test_classifier_that_raises_names_predicate_and_objects():
    def broken(obs, place):
        return {"left": True}[place]

    abstraction = Abstraction(line_task(), {"at": broken})
    with pytest.raises(ClassifierError, match=r"'at' raised KeyError on objects \(at middle\)"):
        abstraction.abstract_state(np.array([0.0]))


def test_classifier_returning_non_truth_values_is_refused():
    abstraction = Abstraction(line_task(), {"at": lambda obs, place: 0.5})
    with pytest.raises(ClassifierError, match="not truth values"):
        abstraction.abstract_state(np.array([0.0]))


def near_all(obs, groundings):
    centres = np.array([PLACES[g[0]] for g in groundings])
    return np.abs(obs[..., :1] - centres) <= RADIUS


def test_vectorized_and_per_atom_classifiers_agree_on_batches():
    observations = np.linspace(-0.1, 1.1, 97)[:, None]
    per_atom = Abstraction(line_task(), {"at": at}).classify_batch(observations)
    vectorized = Abstraction(line_task(), {"at": Vectorized(near_all)}).classify_batch(observations)
    assert per_atom.shape == (97, 3)
    np.testing.assert_array_equal(per_atom, vectorized)
    one_by_one = np.stack(
        [Abstraction(line_task(), {"at": at}).classify_batch(o) for o in observations]
    )
    np.testing.assert_array_equal(per_atom, one_by_one)


def test_vectorized_classifier_with_wrong_shape_is_refused():
    abstraction = Abstraction(line_task(), {"at": Vectorized(lambda obs, g: np.zeros(2, bool))})
    with pytest.raises(ClassifierError, match=r"shape \(2,\), expected \(3,\)"):
        abstraction.abstract_state(np.array([0.0]))


def _cell_classifier(key_of_values):
    def which(obs, groundings):
        return np.flatnonzero(near_all(obs, groundings)).tolist()

    return Vectorized(
        near_all,
        holding=which,
        key=lambda obs: round(float(obs[0]) * 10),
        key_of_values=key_of_values,
    )


def test_keys_from_one_conversion_are_used_and_agree_with_each_classifiers_key():
    abstraction = Abstraction(line_task(), {"at": _cell_classifier(lambda v: round(v[0] * 10))})
    evaluator = abstraction.evaluator(list(abstraction.fluent_atoms))
    for x in np.linspace(-0.1, 1.1, 49):
        obs = np.array([x])
        assert evaluator.key(obs) == (round(x * 10),) == evaluator._key_per_classifier(obs)
        assert evaluator.holding(obs) == set(np.flatnonzero(evaluator(obs)).tolist())


def test_a_key_of_values_that_disagrees_with_key_is_refused_naming_the_predicate():
    abstraction = Abstraction(line_task(), {"at": _cell_classifier(lambda v: round(v[0] * 100))})
    evaluator = abstraction.evaluator(list(abstraction.fluent_atoms))
    with pytest.raises(ClassifierError, match=r"classifier of 'at' keys observation \[0.45\]"):
        evaluator.key(np.array([0.45]))


def test_a_holding_generator_that_raises_is_named_like_the_classifier():
    def lazily(obs, groundings):
        yield 0
        raise KeyError("middle")

    abstraction = Abstraction(line_task(), {"at": Vectorized(near_all, holding=lazily)})
    evaluator = abstraction.evaluator(list(abstraction.fluent_atoms))
    with pytest.raises(ClassifierError, match=r"'at' raised KeyError"):
        evaluator.holding(np.array([0.0]))
