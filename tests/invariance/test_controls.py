"""The negative controls: each provably changes the optimal policy on its toy, and the checker
says so — at the state the argument points to. Their corrected versions pass."""

from __future__ import annotations

import numpy as np
import pytest

from planshape.invariance import check_potential
from planshape.invariance.check import check_shaping
from planshape.invariance.controls import (
    CONTROLS,
    ActionPotential,
    ShiftedPlanBased,
    run_control,
)
from planshape.invariance.shaped import PotentialBased, Step
from planshape.invariance.solve import value_iteration
from planshape.invariance.toys import make_toy
from planshape.shaping.potentials import Potential, make_potential


@pytest.mark.parametrize("control", CONTROLS, ids=lambda c: c.name)
def test_every_negative_control_is_caught(control):
    verdict = run_control(control)
    assert not verdict.preserved
    if verdict.not_a_potential:  # (e), (f): shown by the probes, before any solving
        return
    assert verdict.harmful > 0
    assert verdict.counterexample is not None and verdict.counterexample.harmful


def _shaped_q(control_name: str):
    control = next(c for c in CONTROLS if c.name == control_name)
    toy = make_toy(control.toy)
    aug = toy.augmented
    bonus = control.build().expected(aug, Step(0, 0, toy.gamma, toy.horizon))
    r = aug.lift(toy.mdp.expected_reward())
    original = value_iteration(aug.mdp.dynamics, r, toy.gamma).q
    shaped = value_iteration(aug.mdp.dynamics, r + bonus, toy.gamma).q
    return toy, aug, original, shaped


def test_subgoal_bonus_parks_next_to_the_goal():
    toy, _, original, shaped = _shaped_q("subgoal-bonus")
    # the plan's last intermediate subgoal is the cell below the goal, entered from below
    plan = toy.progress
    n = plan.final
    below = int(np.flatnonzero(plan.reached(toy.mdp.observations)[:, n - 1])[0])
    x = (n - 1) * toy.mdp.n_states + below  # progress n−1: it was just reached
    up, stay = toy.mdp.actions.index("up"), toy.mdp.actions.index("stay")
    assert original[x].argmax() == up  # enter the goal
    assert shaped[x, stay] > shaped[x, up]  # park: 2 per step beats the goal's 1


def test_no_gamma_never_enters_the_goal_from_next_to_it():
    toy, _, original, shaped = _shaped_q("no-gamma")
    plan, n_s = toy.progress, toy.mdp.n_states
    n = plan.final
    last = int(np.flatnonzero(plan.reached(toy.mdp.observations)[:, n - 1])[0])
    x = (n - 1) * n_s + last
    enter = int(original[x].argmax())
    phi = 2.0 * (n - 1) / n
    assert shaped[x, enter] == pytest.approx(1.0 - phi)  # 1 + 0 − φ: negative
    assert shaped[x].max() == pytest.approx(0.0, abs=1e-9)  # staying: φ − φ = 0 forever
    assert shaped[x, enter] < shaped[x].max()


def test_nonzero_terminal_potential_never_completes_the_push():
    toy, aug, original, shaped = _shaped_q("no-terminal-zero")
    x = int(aug.reset_progress[toy.start]) * toy.mdp.n_states + toy.start
    assert original[x].max() > 0  # the push can be completed from the start
    phi0 = -3.0 + aug.plan_progress[x] / aug.progress.final
    assert shaped[x].max() == pytest.approx(-phi0)  # never terminating: Σ F = −φ0


def test_action_potential_stays_put():
    toy, aug, original, shaped = _shaped_q("action-potential")
    x = int(aug.reset_progress[toy.start]) * toy.mdp.n_states + toy.start
    stay = toy.mdp.actions.index("stay")
    assert original[x].argmax() != stay
    assert shaped[x].argmax() == stay


@pytest.mark.parametrize(
    ("toy", "shaping"),
    [
        ("push", lambda: PotentialBased(ShiftedPlanBased(-3.0))),  # zeroed at termination
        ("reach-episodic", lambda: PotentialBased(make_potential("plan-based", scale=2.0))),
        ("reach-episodic", lambda: ActionPotential("plan-based", {"stay": 0.0})),
    ],
    ids=["shift-with-terminal-zero", "scale-2-with-gamma", "action-offset-zero"],
)
def test_the_corrected_controls_pass(toy, shaping):
    toy_problem = make_toy(toy)
    for preset in ("discounted", "finite-horizon", "undiscounted"):
        assert check_shaping(toy_problem, shaping(), toy_problem.setting(preset)).preserved


class FastButWrong(Potential):
    """plan-based whose step function (what the wrapper would train with) counts double."""

    def potential(self, ctx):
        return ctx.progress / ctx.final

    def specialize(self, ctx):
        final = ctx.final
        return lambda obs, progress: 2 * progress / final


class TimedButTimeless(Potential):
    """time-varying whose step function forgets the time: right at t = 0 only."""

    time_dependent = True

    def potential(self, ctx):
        return ctx.progress / ctx.final / (ctx.t + 1)

    def specialize(self, ctx):
        final = ctx.final
        return lambda obs, progress, t: progress / final


def test_a_time_dependent_step_function_is_compared_after_the_first_step_too():
    report = check_potential(TimedButTimeless, mdps=["reach"], settings=["finite-horizon"])
    assert not report.preserved
    (verdict,) = report.verdicts
    assert "specialize() gives" in verdict.not_a_potential and ", t 1)" in verdict.not_a_potential
    assert check_potential(
        make_potential("time-varying"), mdps=["reach"], settings=["finite-horizon"]
    ).preserved


def test_a_step_function_that_disagrees_with_the_potential_is_caught():
    report = check_potential(FastButWrong, mdps=["reach"], settings=["discounted"])
    assert not report.preserved
    (verdict,) = report.verdicts
    assert "specialize() gives" in verdict.not_a_potential
    # the same potential without the disagreeing step function passes
    assert check_potential(
        make_potential("plan-based"), mdps=["reach"], settings=["discounted"]
    ).preserved
