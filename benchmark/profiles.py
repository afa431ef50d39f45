"""Benchmark profiles: which runs make up a benchmark, with their fixed budgets.

A profile is a list of blocks; a block is a grid of tasks × reward entries × algorithms ×
seeds with one training budget (environment steps) per task. An *entry* is ``"sparse"``,
``"dense"`` or ``"<potential>/<model>"``: a potential shaped from one PDDL granularity.

==========  ================================================================================
profile     what it runs
==========  ================================================================================
smoke       reach, three entries, PPO, one seed, 4k steps (about a minute; a test runs it)
default     the source paper's grid with PPO × 5 seeds, plus SAC on the main entries ×
            2 seeds (5 on push), plus the planning-derived potentials on the grid models and
            the goal-distance control × PPO × 5 seeds — what ``tox -e bench`` runs; 3.1 h
            of runs, about 95 minutes on 2 cores
paper       the source paper's full grid: reach, push, maze-reach × {sparse, dense, 3
            potentials × 3 models} × PPO, SAC and SAC-default × 5 seeds
full        ``paper`` plus MetaWorld and gymnasium-robotics tasks
metaworld   the 8 MetaWorld tasks × {sparse, dense, plan-based, plan-distance} × PPO × 2 seeds
            at 102k steps: the part of ``full``'s MetaWorld block that 2 CPU cores train in
            about 80 minutes (``full`` needs days there, see :data:`METAWORLD_PROFILE`)
==========  ================================================================================

Example:
    >>> runs = list(PROFILES["smoke"].runs())
    >>> len(runs), runs[0].task, runs[0].entry
    (3, 'planshape/Reach-v0', 'sparse')
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field

from planshape.errors import UnknownIdError
from planshape.registration import task_spec

PLANAR = ("planshape/Reach-v0", "planshape/Push-v0", "planshape/MazeReach-v0")
PUSH = ("planshape/Push-v0",)
PAPER_POTENTIALS = ("plan-based", "time-varying", "distance-varying")
#: the source paper's granularities of the planar models
PAPER_MODELS = ("single", "multi", "grid")
#: planning-derived potentials beyond the paper, meaningful on the grid models
PLANNING_POTENTIALS = ("plan-distance", "plan-path", "h-star", "h-star-geodesic")
#: the grid models of the planar tasks (push also has one with diagonal, sliding pushes)
GRID_MODELS = ("grid", "grid-diagonal")
#: the control entry: the hand-crafted dense reward's distance as a potential
CONTROL_POTENTIALS = ("goal-distance",)
METAWORLD = tuple(
    f"planshape/MetaWorld-{name}-v3"
    for name in (
        "reach",
        "push",
        "pick-place",
        "door-open",
        "drawer-open",
        "drawer-close",
        "button-press-topdown",
        "window-open",
    )
)
ROBOTICS = (
    "planshape/PointMaze_UMaze-v3",
    "planshape/PointMaze_Medium-v3",
    "planshape/FetchReach-v4",
    "planshape/FetchPush-v4",
)


@dataclass(frozen=True)
class RunKey:
    """The identity of one training run inside a profile (the settings come from elsewhere)."""

    task: str
    entry: str
    algo: str
    seed: int
    budget: int

    @property
    def potential(self) -> str | None:
        return None if self.entry in ("sparse", "dense") else self.entry.rsplit("/", 1)[0]

    @property
    def model(self) -> str | None:
        return None if self.entry in ("sparse", "dense") else self.entry.rsplit("/", 1)[1]

    @property
    def reward(self) -> str:
        return self.entry if self.entry in ("sparse", "dense") else "shaped"


def entries(task: str, potentials: Sequence[str], models: Sequence[str] | None = None) -> list[str]:
    """``sparse``, ``dense`` and every potential × model of ``task`` (or the given models)."""
    known = list(task_spec(task).models)
    chosen = known if models is None else [m for m in models if m in known]
    return ["sparse", "dense"] + [f"{p}/{m}" for p in potentials for m in chosen]


@dataclass(frozen=True)
class Block:
    """A grid of runs: tasks × entries × algorithms × seeds, with a budget per task.

    Attributes:
        tasks: task ids.
        algos: algorithm names (see :mod:`planshape.hyperparams`).
        seeds: training seeds.
        budgets: task -> environment steps of training.
        potentials: potentials shaped for every model of each task (beside sparse and dense).
        models: restrict the shaped entries to these models (all of the task's by default).
        include_sparse_dense: whether the block has the sparse and dense references.
    """

    tasks: Sequence[str]
    algos: Sequence[str]
    seeds: Sequence[int]
    budgets: Mapping[str, int]
    potentials: Sequence[str] = PAPER_POTENTIALS
    models: Sequence[str] | None = None
    include_sparse_dense: bool = True

    def runs(self) -> Iterator[RunKey]:
        for task in self.tasks:
            names = entries(task, self.potentials, self.models)
            if not self.include_sparse_dense:
                names = names[2:]
            for entry in names:
                for algo in self.algos:
                    for seed in self.seeds:
                        yield RunKey(task, entry, algo, seed, self.budgets[task])


@dataclass(frozen=True)
class Profile:
    """A named benchmark: blocks of runs plus how they are evaluated.

    Attributes:
        name: the profile's name.
        description: one line for ``--help`` and the leaderboard header.
        blocks: the runs.
        eval_every: evaluate the policy every this many environment steps (and at the end).
        eval_episodes: deterministic evaluation episodes per evaluation point.
    """

    name: str
    description: str
    blocks: Sequence[Block]
    eval_every: int
    eval_episodes: int
    caveats: Sequence[str] = field(default_factory=tuple)

    def runs(
        self,
        *,
        tasks: Sequence[str] | None = None,
        seeds: Sequence[int] | None = None,
        extra_potentials: Sequence[str] = (),
    ) -> Iterator[RunKey]:
        """Every run, optionally only for some tasks or seeds, plus runs of extra potentials
        (a submission) over every model of each task, with each block's algorithms."""
        seen: set[RunKey] = set()
        for block in self.blocks:
            keys = list(block.runs())
            for potential in extra_potentials:
                extra = Block(
                    block.tasks,
                    block.algos,
                    block.seeds,
                    block.budgets,
                    (potential,),
                    include_sparse_dense=False,
                )
                keys += list(extra.runs())
            for key in keys:
                if tasks is not None and key.task not in tasks:
                    continue
                if seeds is not None and key.seed not in seeds:
                    continue
                if key not in seen:
                    seen.add(key)
                    yield key

    def budgets(self) -> dict[tuple[str, str], int]:
        """(task, algo) -> budget, for the leaderboard header."""
        return {(t, a): b.budgets[t] for b in self.blocks for t in b.tasks for a in b.algos}


SMOKE = Profile(
    name="smoke",
    description="reach, 3 entries, PPO, 1 seed, 4096 steps: checks the pipeline end to end",
    blocks=(
        Block(
            tasks=("planshape/Reach-v0",),
            algos=("PPO",),
            seeds=(0,),
            budgets={"planshape/Reach-v0": 4096},
            potentials=("plan-based",),
            models=("multi",),
        ),
    ),
    eval_every=2048,
    eval_episodes=5,
    caveats=("smoke profile: budgets far too small to learn; for checking the pipeline only",),
)

# Multiples of PPO's rollout (8 environments × 128 steps), so PPO trains exactly the budget.
_PLANAR_BUDGETS = {
    "planshape/Reach-v0": 40 * 1024,
    "planshape/Push-v0": 80 * 1024,
    "planshape/MazeReach-v0": 80 * 1024,
}
_SAC_BUDGETS = {
    "planshape/Reach-v0": 10_000,
    "planshape/Push-v0": 15_000,
    "planshape/MazeReach-v0": 15_000,
}


def _shaped_only(
    tasks: Sequence[str],
    algo: str,
    seeds: int,
    budgets: Mapping[str, int],
    potentials: Sequence[str],
    models: Sequence[str],
) -> Block:
    """A block of shaped entries only (its sparse and dense runs are in another block)."""
    return Block(
        tasks, (algo,), tuple(range(seeds)), budgets, potentials, models, include_sparse_dense=False
    )


DEFAULT = Profile(
    name="default",
    description=(
        "reach, push, maze-reach × {sparse, dense, 3 potentials × 3 models} × PPO × 5 seeds, "
        "plus SAC (tuned) on sparse, dense, the grid potentials, plan-path and goal-distance × "
        "2 seeds (5 on push for sparse, dense, plan-path and goal-distance), plus the "
        "planning-derived potentials (plan-distance, plan-path, h-star, h-star-geodesic) on "
        "the grid models and the goal-distance control × PPO × 5 seeds"
    ),
    blocks=(
        Block(PLANAR, ("PPO",), tuple(range(5)), _PLANAR_BUDGETS, models=PAPER_MODELS),
        # two SAC seeds (five on push, below): SAC runs take 1–2 minutes each on a core
        Block(
            PLANAR,
            ("SAC",),
            tuple(range(2)),
            _SAC_BUDGETS,
            PAPER_POTENTIALS + CONTROL_POTENTIALS,
            models=("grid",),
        ),
        _shaped_only(PLANAR, "SAC", 2, _SAC_BUDGETS, ("plan-path",), GRID_MODELS),
        # push with SAC is where a potential matches dense: 5 seeds for that comparison
        Block(PUSH, ("SAC",), tuple(range(5)), _SAC_BUDGETS, CONTROL_POTENTIALS, models=("grid",)),
        _shaped_only(PUSH, "SAC", 5, _SAC_BUDGETS, ("plan-path",), GRID_MODELS),
        _shaped_only(PLANAR, "PPO", 5, _PLANAR_BUDGETS, PLANNING_POTENTIALS, GRID_MODELS),
        _shaped_only(PLANAR, "PPO", 5, _PLANAR_BUDGETS, CONTROL_POTENTIALS, ("grid",)),
    ),
    eval_every=10_000,
    eval_episodes=10,
    caveats=(
        "SAC runs get smaller budgets than PPO (SAC takes one gradient step per environment "
        "step; on 2 CPU cores these budgets keep the profile near an hour and a half)",
        "every potential's φ is multiplied by shaping_scale = 1/(1 − γ) = 100 (planshape."
        "hyperparams); the source paper tuned a multiplier per potential by hand, this "
        "benchmark applies one rule to every entry",
        "episodes are 40 (reach, push) and 50 (maze-reach) steps, not the paper's 25: the "
        "goals cannot be reached in 25 steps of 0.02 m",
        "PPO and SAC see the observation rescaled from its bounds to [-1, 1] "
        "(rescale_observations, planshape.hyperparams); on raw metres no entry solved "
        "maze-reach",
        "goal-distance is a control, not a planning-derived potential: the dense reward's own "
        "distance used as a potential; where it also trails dense, the gap is what keeping "
        "the optimal policy costs, not what the plan lacks",
    ),
)

PAPER = Profile(
    name="paper",
    description="the source paper's grid: 3 tasks × 11 entries × PPO, SAC, SAC-default × 5 seeds",
    blocks=(
        Block(
            PLANAR,
            ("PPO",),
            tuple(range(5)),
            {t: 2 * b for t, b in _PLANAR_BUDGETS.items()},
            models=PAPER_MODELS,
        ),
        Block(
            PLANAR,
            ("SAC", "SAC-default"),
            tuple(range(5)),
            {t: 30_000 for t in PLANAR},
            models=PAPER_MODELS,
        ),
    ),
    eval_every=10_000,
    eval_episodes=20,
)

FULL = Profile(
    name="full",
    description="paper plus MetaWorld (8 tasks) and gymnasium-robotics (PointMaze, Fetch)",
    blocks=(
        *PAPER.blocks,
        Block(
            METAWORLD + ROBOTICS,
            ("PPO", "SAC"),
            tuple(range(5)),
            {t: 500_000 for t in METAWORLD + ROBOTICS},
            potentials=("plan-based", "distance-varying", "plan-distance"),
        ),
    ),
    eval_every=50_000,
    eval_episodes=20,
)

#: PPO's rollout on MetaWorld is 8 environments × 512 steps; 25 rollouts
_METAWORLD_BUDGET = 25 * 8 * 512

METAWORLD_PROFILE = Profile(
    name="metaworld",
    description=(
        "the 8 MetaWorld tasks × {sparse, dense, plan-based, plan-distance} on the stages model "
        "× PPO × 2 seeds, 102,400 steps each"
    ),
    blocks=(
        Block(
            METAWORLD,
            ("PPO",),
            (0, 1),
            {t: _METAWORLD_BUDGET for t in METAWORLD},
            potentials=("plan-based", "plan-distance"),
        ),
    ),
    eval_every=4 * 8 * 512,
    eval_episodes=10,
    caveats=(
        "a reduction of the full profile's MetaWorld block (500k steps × 5 seeds × PPO and SAC "
        "× 5 entries) to what 2 CPU cores train in about 80 minutes (2.64 h of runs): PPO "
        "trains MetaWorld at about 1,300 steps/s on one core and SAC ([256, 256], one gradient "
        "step per step) at about 50, so the full block would take days; 102k steps are 25 PPO "
        "updates, far below the millions MetaWorld tasks usually need",
        "observations are MetaWorld's raw ones (no finite bounds to rescale from)",
    ),
)

PROFILES: dict[str, Profile] = {p.name: p for p in (SMOKE, DEFAULT, PAPER, FULL, METAWORLD_PROFILE)}


def get_profile(name: str) -> Profile:
    if name not in PROFILES:
        raise UnknownIdError("profile", name, PROFILES)
    return PROFILES[name]
