"""The potential registry, references and the source paper's potentials."""

from __future__ import annotations

import numpy as np
import pytest

from planshape.baselines.paper import DistanceVarying, PlanBased, TimeVarying
from planshape.errors import BadInputError, UnknownIdError
from planshape.shaping.potentials import Potential, ShapingContext, make_potential, potential_ids

SUBGOALS = (frozenset({("at", "a")}), frozenset({("at", "b")}), frozenset({("at", "c")}))


class Constant(Potential):
    def potential(self, ctx: ShapingContext) -> float:
        return 2.0


class NotAPotential:
    pass


def ctx(progress=0, t=0, obs=None, geometry=None):
    return ShapingContext(obs=obs, progress=progress, t=t, subgoals=SUBGOALS, geometry=geometry)


def test_reference_potentials_are_registered():
    assert {"plan-based", "time-varying", "distance-varying"} <= set(potential_ids())
    assert isinstance(make_potential("plan-based"), PlanBased)
    assert make_potential("time-varying", scale=3.0).scale == 3.0


def test_module_attr_reference_and_errors():
    made = make_potential("tests.shaping.test_potentials:Constant")
    assert made(ctx()) == 2.0 and made.name == "tests.shaping.test_potentials:Constant"
    with pytest.raises(UnknownIdError, match="did you mean 'plan-based'"):
        make_potential("plan-base")
    with pytest.raises(BadInputError, match="cannot import module 'no_such_module'"):
        make_potential("no_such_module:Thing")
    with pytest.raises(BadInputError, match="has no attribute 'Missing'"):
        make_potential("tests.shaping.test_potentials:Missing")
    with pytest.raises(BadInputError, match="does not subclass"):
        make_potential("tests.shaping.test_potentials:NotAPotential")


def test_paper_potentials_by_hand():
    assert PlanBased()(ctx(progress=1)) == 0.5
    assert PlanBased(normalize=False)(ctx(progress=1)) == 1.0
    assert TimeVarying()(ctx(progress=2, t=3)) == pytest.approx(1.0 / 4)
    assert TimeVarying.time_dependent and not PlanBased.time_dependent


class LineGeometry:
    centres = {"a": 0.0, "b": 1.0, "c": 2.0}  # noqa: RUF012

    def locate(self, subgoal):
        (atom,) = subgoal
        return {"ee": np.array([self.centres[atom[1]], 0.0]), "box": np.array([5.0, 0.0])}

    def positions(self, obs):
        return {"ee": np.asarray(obs[:2]), "box": np.asarray(obs[2:])}


def test_distance_varying_measures_first_unmet_entity_towards_next_subgoal():
    phi = DistanceVarying(tolerance=0.1)
    geometry = LineGeometry()
    # progress 0: next subgoal is b at x=1; ee at x=0.25 -> -0.75
    assert phi(ctx(0, obs=np.array([0.25, 0.0, 0.0, 0.0]), geometry=geometry)) == -0.75
    # ee within tolerance of b: the box (at 0, target 5) is measured next
    assert phi(ctx(0, obs=np.array([1.05, 0.0, 2.0, 0.0]), geometry=geometry)) == -3.0
    # at the end of the plan the target stays the last subgoal
    assert phi(ctx(2, obs=np.array([2.0, 0.0, 5.0, 0.0]), geometry=geometry)) == 0.0
    with pytest.raises(BadInputError, match="locate/positions"):
        phi(ctx(0, obs=np.zeros(4)))


def test_potential_scale_multiplies_the_shaping_term_and_leaves_the_reference_alone():
    import gymnasium

    import planshape  # noqa: F401  (registers the tasks)
    from planshape.baselines.paper import PlanBased
    from planshape.harness.profiles import RunKey
    from planshape.harness.runner import make_training_env

    def shaping_terms(scale: float) -> list[float]:
        env = gymnasium.make(
            "planshape/Reach-v0",
            reward="shaped",
            potential="plan-distance",
            model="multi",
            gamma=0.99,
            potential_scale=scale,
        )
        env.reset(seed=0)
        return [env.step(np.array([0.1, 1.0], np.float32))[4]["shaping"] for _ in range(10)]

    loud, quiet = shaping_terms(100.0), shaping_terms(1.0)
    assert any(q != 0 for q in quiet)
    assert loud == pytest.approx([100 * q for q in quiet])
    reference = PlanBased(scale=2.0)
    assert reference.rescaled(3.0).scale == 6.0 and reference.scale == 2.0
    with pytest.raises(BadInputError, match="finite and positive"):
        reference.rescaled(-1.0)
    key = RunKey("planshape/Reach-v0", "plan-based/multi", "PPO", 0, 1024)
    venv = make_training_env(key, 1, 0.99, 0, shaping_scale=100.0)
    assert venv.get_attr("potential")[0].scale == 100.0
