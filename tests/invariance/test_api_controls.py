"""What the Potential API used to let through: hidden state, growth faster than 1/γ, undeclared
time, writing the observation, magnitude. Each is caught (exit 1) or refused (exit 2) with a
counterexample naming the potential; harmless potentials of the same shape stay preserved."""

from __future__ import annotations

import numpy as np
import pytest

from planshape.cli import main
from planshape.errors import BadInputError, CannotVerifyError, PotentialValueError
from planshape.invariance.check import check_potential, check_shaping
from planshape.invariance.controls import (
    CONTROLS,
    REFUSED,
    GrowingPlanBased,
    HiddenStateBonus,
    SubgoalBonus,
    WritesObservation,
    run_control,
)
from planshape.invariance.shaped import PotentialBased, Shaping, Step
from planshape.invariance.toys import make_toy
from planshape.shaping.potentials import Potential, ShapingContext, make_potential
from planshape.shaping.wrapper import PotentialShaping
from tests.invariance.tabular import TabularEnv


@pytest.mark.parametrize(
    ("name", "phrase"),
    [
        ("hidden-state", "is not a function of the augmented state"),
        ("growth", "grows faster than 1/γ (γ=0.95)"),
    ],
)
def test_the_probes_catch_what_the_q_tables_cannot_show(name, phrase):
    control = next(c for c in CONTROLS if c.name == name)
    verdict = run_control(control)
    assert not verdict.preserved and verdict.status == "violated (not a potential)"
    assert phrase in verdict.not_a_potential


def test_hidden_state_is_control_a_in_disguise_along_an_episode():
    """The argument of control (e): the wrapper's F along an episode is (a)'s bonus exactly."""
    toy = make_toy("reach")
    mdp, plan = toy.mdp, toy.progress
    on_subgoal = np.asarray(plan.reached(mdp.observations))[:, 1:-1].any(axis=1)
    start = int(np.flatnonzero(~on_subgoal & ~mdp.terminal)[0])
    env = PotentialShaping(
        TabularEnv(mdp, start, seed=3),
        HiddenStateBonus(2.0, gamma=toy.gamma),
        plan,
        gamma=toy.gamma,
    )
    env.reset(seed=0)
    rng = np.random.default_rng(0)
    for _ in range(30):
        _, _, terminated, _, info = env.step(int(rng.integers(mdp.n_actions)))
        assert info["shaping"] == pytest.approx(2.0 * on_subgoal[env.env.state], abs=1e-9)
        if terminated:
            break
    # and (a)'s bonus itself changes the optimal policy there
    assert not check_shaping(toy, SubgoalBonus(2.0), toy.setting("discounted")).preserved


def test_growth_is_caught_only_faster_than_one_over_gamma():
    toy = make_toy("reach")
    setting = toy.setting("discounted")
    slow = GrowingPlanBased(1.0 / toy.gamma * 0.98)  # γ^t·φ → 0: a valid dynamic potential
    assert check_shaping(toy, PotentialBased(slow), setting).preserved
    fast = check_shaping(toy, PotentialBased(GrowingPlanBased(1.2)), setting)
    assert not fast.preserved and "t=640" in fast.not_a_potential


class CachedPlanBased(Potential):
    """Stateful in a way that cancels: it memoizes φ by progress."""

    def __init__(self):
        super().__init__()
        self.memo: dict[int, float] = {}
        self.calls = 0

    def potential(self, ctx: ShapingContext) -> float:
        self.calls += 1
        if ctx.progress not in self.memo:
            self.memo[ctx.progress] = ctx.progress / ctx.final
        return self.memo[ctx.progress]


@pytest.mark.parametrize("potential", ["plan-distance", "plan-path", "h-star-geodesic"])
def test_harmless_state_and_every_reference_stay_preserved(potential):
    assert check_potential(CachedPlanBased(), mdps=["reach", "push"]).preserved
    assert check_potential(potential, mdps=["reach", "maze-reach"]).preserved


@pytest.mark.parametrize(("name", "build", "expected"), REFUSED, ids=[r[0] for r in REFUSED])
def test_what_the_api_makes_impossible_is_refused(name, build, expected):
    with pytest.raises(BadInputError, match=expected):
        check_potential(build(), mdps=["reach"])


def test_a_potential_cannot_change_what_the_learner_sees():
    env = PotentialShaping(
        TabularEnv(make_toy("reach").mdp, 0),
        WritesObservation(),
        make_toy("reach").progress,
        gamma=0.95,
    )
    with pytest.raises(PotentialValueError, match="writes into ctx.obs"):
        env.reset(seed=0)


class Sum(Shaping):
    """Two shapings added."""

    def __init__(self, *parts: Shaping):
        self.parts, self.name = parts, " + ".join(p.name for p in parts)

    def transition_bonus(self, aug, step: Step) -> np.ndarray:
        return sum(p.transition_bonus(aug, step) for p in self.parts)


def test_magnitude_cannot_hide_an_invalid_shaping():
    """τ comes from the task's Q-values, not the shaped ones: a huge valid potential can no
    longer make every action tie, nor turn an invalid shaping added to it into 'preserved'."""
    toy = make_toy("reach")
    setting = toy.setting("discounted")
    huge = PotentialBased(make_potential("plan-based", scale=1e9))
    with pytest.raises(CannotVerifyError, match="check the potential at unit scale"):
        check_shaping(toy, huge, setting)
    with pytest.raises(CannotVerifyError):
        check_shaping(toy, Sum(huge, SubgoalBonus(2.0)), setting)
    loud = PotentialBased(make_potential("plan-based", scale=100.0))  # the benchmark's scale
    assert check_shaping(toy, loud, setting).preserved
    assert not check_shaping(toy, Sum(loud, SubgoalBonus(2.0)), setting).preserved


def test_the_command_line_exits_2_on_a_refused_potential(tmp_path, monkeypatch, capsys):
    (tmp_path / "clock.py").write_text(
        "from planshape.shaping.potentials import Potential\n"
        "class Clock(Potential):\n"
        "    def potential(self, ctx):\n"
        "        return 0.01 * ctx.t\n"
    )
    monkeypatch.syspath_prepend(str(tmp_path))
    assert main(["check-invariance", "--potential", "clock:Clock"]) == 2
    err = capsys.readouterr().err
    assert "'clock:Clock' reads ctx.t without declaring time_dependent" in err
