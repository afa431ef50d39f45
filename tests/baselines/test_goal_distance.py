"""The goal-distance control potential: the hand-crafted dense reward's distance as φ."""

from __future__ import annotations

import gymnasium
import numpy as np
import pytest

import planshape  # noqa: F401  (registers the tasks)
from planshape.baselines.goal_distance import GoalDistance, chain_distance
from planshape.errors import PotentialError
from planshape.invariance.toys import PointGeometry
from planshape.shaping.potentials import ShapingContext, make_potential

PLANAR = ["planshape/Reach-v0", "planshape/Push-v0", "planshape/MazeReach-v0"]


def test_registered_as_goal_distance():
    assert isinstance(make_potential("goal-distance"), GoalDistance)


@pytest.mark.parametrize("model", ["grid", "multi"])
@pytest.mark.parametrize("task", PLANAR)
def test_is_the_dense_reward_divided_by_its_start_value(task, model):
    """On a random rollout φ / r_dense is one constant: 1 / d0, d0 the chain at Ŝ[0]'s places."""
    shaped = gymnasium.make(task, reward="shaped", potential="goal-distance", model=model, gamma=1)
    dense = gymnasium.make(task, reward="dense")
    shaped.reset(seed=3)
    dense.reset(seed=3)
    shaped.action_space.seed(3)
    ratios = []
    for _ in range(25):
        action = shaped.action_space.sample()
        *_, info = shaped.step(action)
        _, reward, *_ = dense.step(action)
        ratios.append(info["potential"] / reward)
    assert max(ratios) == pytest.approx(min(ratios), rel=1e-6)
    assert 1.0 < ratios[0] < 5.0  # d0 is a fraction of a metre


def test_chain_and_normalization_by_hand():
    geometry = PointGeometry({"a": (0, 0), "b": (3, 4)})
    subgoals = [frozenset({("robot_at", "a")}), frozenset({("robot_at", "b")})]

    def phi(x, y, progress=0):
        ctx = ShapingContext(np.array([x, y]), progress, 0, subgoals, geometry)
        return GoalDistance()(ctx)

    assert phi(0, 0) == pytest.approx(-1.0)  # at Ŝ[0]'s place: d0 = 5
    assert phi(3, 4) == 0.0
    assert phi(3, 0) == pytest.approx(-4 / 5)
    assert phi(3, 0, progress=1) == phi(3, 0)  # the plan's progress plays no part
    assert chain_distance({"ee": (0, 0), "box": (0, 1)}, (1, 1)) == 2.0


def test_a_goal_without_the_last_entity_is_a_clear_error():
    geometry = PointGeometry({"a": (0, 0)})
    ctx = ShapingContext(np.zeros(2), 0, 0, [frozenset(), frozenset()], geometry)
    with pytest.raises(PotentialError, match="goal-distance.*final subgoal places no 'ee'"):
        make_potential("goal-distance")(ctx)


@pytest.mark.parametrize("potential", ["goal-distance", "plan-path"])
def test_displacement_entities_do_not_chain(potential):
    """MetaWorld's and Fetch's entities are displacements (hand-to-puck, puck-to-goal): the
    distance between two of them means nothing, so a chaining potential refuses them; with a
    single entity there is nothing to chain."""
    from planshape.tasks.displacement import DisplacementGeometry

    def hand_to_puck(obs):
        return obs[0:2] - obs[2:4]

    def puck_to_goal(obs):
        return obs[2:4]

    subgoals = [frozenset({("near", "hand")}), frozenset({("near", "hand"), ("at", "puck")})]
    two = DisplacementGeometry(
        {"hand-to-puck": hand_to_puck, "puck-to-goal": puck_to_goal},
        {"near": ("hand-to-puck", (0, 0)), "at": ("puck-to-goal", (0, 0))},
    )
    ctx = ShapingContext(np.array([1.0, 0, 0, 1]), 0, 0, subgoals, two)
    with pytest.raises(PotentialError, match=f"{potential}.*shared_frame = True"):
        make_potential(potential)(ctx)
    one = DisplacementGeometry({"puck-to-goal": puck_to_goal}, {"at": ("puck-to-goal", (0, 0))})
    ctx = ShapingContext(np.array([1.0, 0, 0, 2]), 0, 0, subgoals, one)
    assert make_potential(potential)(ctx) == -2.0  # no place at Ŝ[0]: d0 = 1 m
