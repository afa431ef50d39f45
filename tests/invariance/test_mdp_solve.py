"""The tabular MDP type and the solvers, against closed forms and exact policy evaluation."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from planshape.errors import BadInputError
from planshape.invariance.mdp import TabularMDP
from planshape.invariance.shaped import PotentialBased, Step
from planshape.invariance.solve import (
    NotConvergedError,
    backward_induction,
    value_iteration,
)
from planshape.invariance.toys import make_toy, random_toy


def test_from_transitions_merges_repeated_rows_by_probability():
    mdp = TabularMDP.from_transitions(
        n_states=2,
        actions=("a",),
        state=[0, 0, 1],
        action=[0, 0, 0],
        next_state=[1, 1, 1],
        probability=[0.25, 0.75, 1.0],
        reward=[4.0, 0.0, 0.0],
    )
    assert mdp.transitions.nnz == 2
    assert mdp.transitions[[0], [1]].item() == pytest.approx(1.0)
    assert mdp.expected_reward()[0, 0] == pytest.approx(1.0)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"probability": [0.5, 1.0]}, "state 0, action 'a' sums to 0.5"),
        ({"next_state": [2, 0]}, "next_state out of range"),
        ({"reward": [np.nan, 0.0]}, "rewards finite"),
    ],
)
def test_from_transitions_rejects_bad_input(change, message):
    arrays = {
        "state": [0, 1],
        "action": [0, 0],
        "next_state": [1, 0],
        "probability": [1.0, 1.0],
        "reward": [0.0, 0.0],
    }
    with pytest.raises(BadInputError, match=message):
        TabularMDP.from_transitions(n_states=2, actions=("a",), **{**arrays, **change})


def test_continuation_zeroes_terminal_states_and_leaves_transitions_alone():
    toy = random_toy(5, n_states=12, episodic=True)
    mdp = toy.mdp
    before = (mdp.transitions.data.copy(), mdp.transitions.indices.copy())
    C = mdp.continuation.toarray()
    terminal = np.flatnonzero(mdp.terminal)
    assert len(terminal)
    assert np.all(C[:, terminal] == 0)
    assert np.all(C.reshape(mdp.n_states, mdp.n_actions, -1)[terminal] == 0)
    # regression: building C once corrupted the shared index arrays of P
    assert np.array_equal(mdp.transitions.data, before[0])
    assert np.array_equal(mdp.transitions.indices, before[1])
    np.testing.assert_allclose(mdp.transitions.sum(axis=1), 1.0)


def _policy_values(mdp: TabularMDP, policy: np.ndarray, gamma: float) -> np.ndarray:
    """V^π by a dense linear solve: independent of value iteration."""
    C = mdp.continuation.toarray().reshape(mdp.n_states, mdp.n_actions, -1)
    rows = np.arange(mdp.n_states)
    r = mdp.expected_reward()[rows, policy]
    return np.linalg.solve(np.eye(mdp.n_states) - gamma * C[rows, policy], r)


@pytest.mark.parametrize("jacobi", [True, False])
@pytest.mark.parametrize(("seed", "episodic", "gamma"), [(1, True, 0.9), (2, False, 0.97)])
def test_value_iteration_is_exact(seed, episodic, gamma, jacobi):
    mdp = random_toy(seed, n_states=30, episodic=episodic).mdp
    result = value_iteration(mdp.dynamics, mdp.expected_reward(), gamma, jacobi=jacobi)
    greedy = result.q.argmax(axis=1)
    exact = _policy_values(mdp, greedy, gamma)
    alive = ~mdp.terminal
    np.testing.assert_allclose(result.q.max(axis=1)[alive], exact[alive], atol=1e-9)
    # and no policy does better: one exact improvement step changes nothing
    C = mdp.continuation.toarray().reshape(mdp.n_states, mdp.n_actions, -1)
    improved = mdp.expected_reward() + gamma * C @ exact
    assert np.all(improved.max(axis=1)[alive] <= exact[alive] + 1e-9)


def test_initial_guess_changes_speed_not_result():
    mdp = random_toy(3, n_states=25).mdp
    r = mdp.expected_reward()
    cold = value_iteration(mdp.dynamics, r, 0.9)
    warm = value_iteration(mdp.dynamics, r, 0.9, initial=cold.q.max(axis=1))
    wild = value_iteration(mdp.dynamics, r, 0.9, initial=np.full(mdp.n_states, 1e3))
    assert warm.iterations < cold.iterations
    np.testing.assert_allclose(wild.q, cold.q, atol=1e-8)


def test_jacobi_backup_converges_in_few_backups_where_stay_loops():
    # shaped push: where the box is stuck, values converge like γ^k under ordinary backups
    aug = make_toy("push").augmented
    bonus = PotentialBased("distance-varying").expected(aug, Step(0, 0, 0.99, 1))
    r = aug.lift(aug.base.expected_reward()) + bonus
    jacobi = value_iteration(aug.mdp.dynamics, r, 0.99)
    ordinary = value_iteration(aug.mdp.dynamics, r, 0.99, jacobi=False)
    assert jacobi.iterations < 50 < ordinary.iterations
    np.testing.assert_allclose(jacobi.q, ordinary.q, rtol=1e-8, atol=1e-8)


def test_backward_induction_matches_recursion():
    mdp = random_toy(4, n_states=8, n_actions=2, episodic=True).mdp
    C = mdp.continuation.toarray().reshape(mdp.n_states, mdp.n_actions, -1)
    r = mdp.expected_reward()

    def q_at(t, horizon, gamma):
        if t == horizon:
            return np.zeros_like(r)
        v_next = q_at(t + 1, horizon, gamma).max(axis=1)
        return r * (1 + t) + gamma * C @ v_next

    layers = dict(backward_induction(mdp.dynamics, lambda t: r * (1 + t), 1.0, 3))
    assert sorted(layers) == [0, 1, 2]
    for t, q in layers.items():
        np.testing.assert_allclose(q, q_at(t, 3, 1.0), atol=1e-12)


def test_solver_input_errors():
    C = sp.csr_array(np.eye(2))
    r = np.zeros((2, 1))
    with pytest.raises(BadInputError, match="gamma < 1"):
        value_iteration(C, r, 1.0)
    with pytest.raises(BadInputError, match="at least 1 step"):
        next(backward_induction(C, lambda t: r, 1.0, 0))
    with pytest.raises(BadInputError, match="2 states, rewards 3"):
        value_iteration(C, np.zeros((3, 1)), 0.9)
    mdp = random_toy(6, n_states=20, episodic=False).mdp
    with pytest.raises(NotConvergedError):
        value_iteration(mdp.dynamics, mdp.expected_reward(), 0.999, max_iterations=2, jacobi=False)
