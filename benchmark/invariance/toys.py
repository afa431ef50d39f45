"""The toy MDPs the checker solves: tabular tasks bound to a PDDL model and its classifiers.

A :class:`ToyProblem` is a :class:`TabularMDP` whose states carry observations, plus the plan
progress tracker (:class:`PlanProgress`: the planner's subgoals and the task's classifiers) and
the geometry hooks that potentials see — built with the same planning, abstraction and potential
code the continuous tasks use. Toys are registered by name with a ``"module:attr"`` entry point,
so nothing is built (or planned) until a toy is made:

=====================  ========================================================================
``reach``              planar reach on the real grid model, continuing: "reach and stay", γ=0.95
``reach-episodic``     the same, but entering the goal terminates the episode
``maze-reach``         planar maze-reach on the real grid model, walls, 10 % slip, continuing
``reach-instance``     one held-out instance of reach's distribution (v1: wall, drawn goal)
``push``               planar push (end effector and box cells) on a coarse grid, episodic
``random-episodic``    a random MDP over random points, a 4-region chain plan, terminal goal
``random-continuing``  the same without termination
=====================  ========================================================================

The planar toys are the planar task family's (:mod:`planshape.tasks.planar.toys`, registered
with the tasks in :mod:`planshape.tasks`); the random ones are here, on a chain
model generated with :func:`planshape.planning.grid_pddl` and planned by Fast Downward.

Example:
    >>> toy = make_toy("random-continuing")
    >>> toy.mdp.n_actions, toy.progress.final, toy.episodic
    (3, 3, False)
"""

from __future__ import annotations

import functools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from planshape.errors import RegistrationError, UnknownIdError
from planshape.invariance.augment import AugmentedMDP, augment
from planshape.invariance.mdp import TabularMDP
from planshape.invariance.registry import (
    TOYS,
    default_toys,
    register_toy,
    toy_names,
)
from planshape.invariance.settings import Setting
from planshape.planning import GridNames, grid_pddl, parse_task, solve_text
from planshape.planning.model import AbstractState
from planshape.shaping.abstraction import Abstraction, Vectorized
from planshape.shaping.potentials import Geometry, load_reference
from planshape.shaping.progress import PlanProgress

__all__ = [
    "PointGeometry",
    "ToyProblem",
    "chain_progress",
    "default_toys",
    "make_toy",
    "random_toy",
    "register_toy",
    "toy_names",
]

#: the planner configuration of the toys (that of the task registration)
SEARCH = "astar-lmcut"


@dataclass(eq=False)
class ToyProblem:
    """A tabular task bound to its abstract model.

    Attributes:
        name, description: for reports.
        mdp: the tabular MDP, with one observation per state.
        progress: the plan's subgoals and the classifiers' reached test.
        geometry: ``locate``/``positions`` hooks for distance potentials (or ``None``).
        gamma: the task's discount (the ``discounted`` setting's γ).
        horizon: the episode length of the finite-horizon settings, and the time cap of
            time-dependent potentials in the discounted one.
        start: the task's start state (where the plan starts), for reports.
    """

    name: str
    description: str
    mdp: TabularMDP
    progress: PlanProgress
    geometry: Geometry | None
    gamma: float
    horizon: int
    start: int | None = None

    @property
    def episodic(self) -> bool:
        """Whether some state terminates the episode."""
        return bool(self.mdp.terminal.any())

    @functools.cached_property
    def augmented(self) -> AugmentedMDP:
        """The MDP over (s, max_idx) (built once)."""
        return augment(self.mdp, self.progress, self.geometry)

    def setting(self, preset: str) -> Setting:
        """The named setting (see :data:`planshape.invariance.settings.PRESETS`) for this toy."""
        return Setting.preset(preset, gamma=self.gamma, horizon=self.horizon)


# ---- building a registered toy ---------------------------------------------------------------


@functools.cache
def make_toy(name: str) -> ToyProblem:
    """Build (once per process) the toy registered as ``name``."""
    if name not in TOYS:
        raise UnknownIdError("toy MDP", name, TOYS, hint="`planshape check-invariance --list`")
    problem = load_reference(TOYS[name][0])()
    if not isinstance(problem, ToyProblem):
        raise RegistrationError(
            f"toy {name!r}: its entry point returned {type(problem).__name__}; it must return a "
            "planshape.invariance.toys.ToyProblem"
        )
    return problem


# ---- random MDPs on a chain plan --------------------------------------------------------------


class PointGeometry:
    """Geometry hooks for point-mass toys: ``obs[:2]`` is the ``"ee"`` position, and the
    ``robot_at`` atom of a subgoal names a region whose centre is the target."""

    #: one entity, a position
    shared_frame = True

    def __init__(self, centres: Mapping[str, np.ndarray]):
        self.centres = {name: np.asarray(c, float) for name, c in centres.items()}

    def locate(self, subgoal: AbstractState) -> Mapping[str, np.ndarray]:
        places = [atom[1] for atom in subgoal if atom[0] == "robot_at"]
        return {"ee": self.centres[places[0]]} if places else {}

    def positions(self, obs: np.ndarray) -> Mapping[str, np.ndarray]:
        return {"ee": np.asarray(obs)[:2]}


_CHAIN = GridNames(domain="chain", problem="chain", cell_type="region", cell_prefix="region")


@functools.cache
def _chain_plan(regions: int):
    """The chain domain ``region_0_0 → … → region_0_{k-1}``, parsed and planned once."""
    pddl = grid_pddl(1, regions, start=(0, 0), goal=(0, regions - 1), names=_CHAIN)
    task = parse_task(pddl.domain, pddl.problem, "<chain domain>", f"<chain-{regions} problem>")
    return task, solve_text(pddl.domain, pddl.problem, search=SEARCH)


def chain_progress(centres: np.ndarray, radius: float) -> tuple[PlanProgress, PointGeometry]:
    """Plan progress through regions ``0 … k−1`` (discs of ``radius`` around ``centres``, in
    the plane of ``obs[:2]``), planned by Fast Downward on a generated chain model."""
    centres = np.asarray(centres, float)
    task, plan = _chain_plan(len(centres))
    names = {f"{_CHAIN.cell_prefix}_0_{j}": centres[j] for j in range(len(centres))}

    def robot_at(obs: np.ndarray, groundings: Sequence[tuple[str, ...]]) -> np.ndarray:
        targets = np.array([names[g[0]] for g in groundings])
        offset = np.asarray(obs, float)[..., None, :2] - targets
        return np.einsum("...i,...i->...", offset, offset) < radius**2

    abstraction = Abstraction(task, {"robot_at": Vectorized(robot_at)})
    return PlanProgress(plan.subgoals, abstraction), PointGeometry(names)


def random_toy(
    seed: int,
    *,
    name: str = "",
    n_states: int = 40,
    n_actions: int = 3,
    regions: int = 4,
    branching: int = 2,
    episodic: bool = True,
    gamma: float = 0.9,
    horizon: int = 8,
) -> ToyProblem:
    """A random MDP over random points of the unit square.

    Each ``(s, a)`` leads to ``branching`` random states with Dirichlet probabilities. The plan
    visits ``regions`` discs (radius 0.2) centred on random states; entering the last one pays
    1 (and terminates when ``episodic``); one transition in five also pays ±0.1 noise.
    Observations are ``(x, y, s)``: the position, and the state's index for tests' tables.
    """
    rng = np.random.default_rng(seed)
    positions = rng.uniform(0.0, 1.0, (n_states, 2))
    centre_states = rng.choice(n_states, size=regions, replace=False)
    centres = positions[centre_states]
    progress, geometry = chain_progress(centres, radius=0.2)
    observations = np.column_stack([positions, np.arange(n_states)])
    success = np.sum((positions - centres[-1]) ** 2, axis=1) < 0.2**2
    s = np.repeat(np.arange(n_states), n_actions * branching)
    a = np.tile(np.repeat(np.arange(n_actions), branching), n_states)
    s2 = np.concatenate(
        [rng.choice(n_states, branching, replace=False) for _ in range(n_states * n_actions)]
    )
    p = rng.dirichlet(np.ones(branching), size=n_states * n_actions).ravel()
    noise = rng.choice([-0.1, 0.1], size=len(s)) * (rng.random(len(s)) < 0.2)
    mdp = TabularMDP.from_transitions(
        n_states=n_states,
        actions=[f"a{i}" for i in range(n_actions)],
        state=s,
        action=a,
        next_state=s2,
        probability=p,
        reward=success[s2].astype(float) + noise,
        terminal=success if episodic else None,
        observations=observations,
    )
    kind = "episodic" if episodic else "continuing"
    return ToyProblem(
        name=name or f"random-{kind}-{seed}",
        description=f"random {kind} MDP (seed {seed}), {n_states} states, {regions}-region plan",
        mdp=mdp,
        progress=progress,
        geometry=geometry,
        gamma=gamma,
        horizon=horizon,
        start=int(centre_states[0]),
    )


def random_episodic() -> ToyProblem:
    """A random episodic toy MDP (fixed seed 1)."""
    return random_toy(1, name="random-episodic", episodic=True)


def random_continuing() -> ToyProblem:
    """A random continuing toy MDP (fixed seed 2)."""
    return random_toy(2, name="random-continuing", episodic=False)


# ---- the toys, one line each --------------------------------------------------------------------

register_toy(
    "random-episodic",
    "planshape.invariance.toys:random_episodic",
    "random MDP, 40 states, 3 actions, stochastic, 4-region chain plan, terminal goal",
)
register_toy(
    "random-continuing",
    "planshape.invariance.toys:random_continuing",
    "random MDP, 40 states, 3 actions, stochastic, 4-region chain plan, continuing",
)
