"""Benchmark profiles: which runs make up a benchmark, with their fixed budgets.

A profile is a list of blocks; a block is a grid of tasks × reward entries × algorithms ×
seeds with one training budget (environment steps) per task. An *entry* is ``"sparse"``,
``"dense"`` or ``"<potential>/<model>"``: a potential shaped from one PDDL granularity.

============  ==============================================================================
profile       what it runs (results folder)
============  ==============================================================================
smoke         reach, three entries, PPO, one seed, 4k steps (about a minute; a test runs it)
default       the source paper's tasks (v1), 5 seeds per cell, budgets from learning curves:
              reach and maze-reach × {sparse, dense, plan-based × 3 models, plan-distance,
              plan-path, goal-distance on the grid model} × PPO, push × {sparse, dense,
              plan-distance/grid} × SAC — what ``tox -e bench`` runs, under an hour on 2 cores
              (``leaderboard/``)
planar        the v1 tasks' full grid × PPO and SAC × 5 seeds at the default's budgets (hours)
instances     the task-instance distributions × {sparse, dense, plan-based, plan-distance,
              plan-path, goal-distance} × PPO × 5 seeds, scored on the held-out instances
paper         the source paper's full grid: reach, push, maze-reach × {sparse, dense, 3
              potentials × 3 models} × PPO, SAC and SAC-default × 5 seeds
full          ``paper`` plus MetaWorld and gymnasium-robotics tasks
metaworld     the 8 MetaWorld tasks × {sparse, dense, plan-based, plan-distance} × PPO ×
              2 seeds at 102k steps: the part of ``full``'s MetaWorld block that 2 CPU cores
              train in about 80 minutes (``full`` needs days there, see
              :data:`METAWORLD_PROFILE`)
default-v0    archived: ``default`` on the v0 tasks, evaluated with protocol 1, kept for its
              stored runs (``leaderboard/default-v0/``); ``planshape bench`` refuses it
metaworld-v0  archived: ``metaworld`` with reach-v3, protocol 1 (``leaderboard/metaworld-v0/``)
============  ==============================================================================

Every profile's results live in their own folder (:attr:`Profile.folder`): ``leaderboard/``
for the default profile, ``leaderboard/<name>/`` for any other.

Example:
    >>> runs = list(PROFILES["smoke"].runs())
    >>> len(runs), runs[0].task, runs[0].entry
    (3, 'planshape/Reach-v1', 'sparse')
    >>> PROFILES["smoke"].folder, PROFILES["default"].folder
    ('leaderboard/smoke', 'leaderboard')
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

from planshape.errors import UnknownIdError
from planshape.harness.missing_runs import name_missing
from planshape.results.measure import SuccessMeasure, describe, measured
from planshape.results.outcome import CONTROL_POTENTIALS
from planshape.shaping.registration import task_spec
from planshape.training.hyperparams import SAC_SHAPING_SCALE, SHAPING_SCALE

if TYPE_CHECKING:
    from planshape.harness.runner import RunSpec

#: the folder under which every profile's results are stored
RESULTS_ROOT = "leaderboard"

#: stable-baselines3's SAC (PyTorch) and SBX's (JAX). Tuned SAC runs with SBX: measured side by
#: side (``python -m planshape.perf.training``), it trains the planar tasks 2.4-3.0 times as
#: fast (Push-v1: 625 against 227 steps/s sparse, 506-566 against 201-212 shaped), with the same
#: hyperparameters; stable-baselines3 stays available as ``SAC`` (and its library defaults,
#: which the source paper ran, as ``SAC-default``)
SAC, SBX_SAC = "SAC", "SBX-SAC"

#: the planar tasks the profiles run: v1, the source paper's (reach behind its wall, push with
#: its cylinder)
PLANAR = ("planshape/Reach-v1", "planshape/Push-v1", "planshape/MazeReach-v1")
PUSH = ("planshape/Push-v1",)
#: the task-instance distributions of the v1 planar tasks (evaluated on held-out instances)
RANDOMIZED = (
    "planshape/ReachRandomized-v1",
    "planshape/PushRandomized-v1",
    "planshape/MazeReachRandomized-v1",
)
#: the v0 planar tasks of the archived ``default-v0`` profile
PLANAR_V0 = ("planshape/Reach-v0", "planshape/Push-v0", "planshape/MazeReach-v0")
PAPER_POTENTIALS = ("plan-based", "time-varying", "distance-varying")
#: the source paper's granularities of the planar models
PAPER_MODELS = ("single", "multi", "grid")
#: planning-derived potentials beyond the paper, meaningful on the grid models
PLANNING_POTENTIALS = ("plan-distance", "plan-path", "h-star", "h-star-geodesic")
#: the grid models of the planar tasks (push also has one with diagonal, sliding pushes)
GRID_MODELS = ("grid", "grid-diagonal")
METAWORLD_V0 = tuple(
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
#: the MetaWorld tasks the profiles run: reach-v4 observes the fingertip centre, so that its
#: plan's last subgoal holds on the step of MetaWorld's success
METAWORLD = tuple(t.replace("MetaWorld-reach-v3", "MetaWorld-reach-v4") for t in METAWORLD_V0)
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
        algos: algorithm names (see :mod:`planshape.training.hyperparams`).
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
        eval_episodes: deterministic evaluation episodes per evaluation point, on tasks that
            draw their start from the seed (a fixed task runs one episode, a distribution its
            held-out instances: :func:`planshape.harness.runner.evaluation_episodes`).
        caveats: what a reader of its leaderboard must know.
        archived: for a profile kept only for its stored runs, why it cannot be run any more
            and how to reproduce it (``planshape bench`` refuses it).
        success_measure: which episodes its leaderboard counts as solved
            (:mod:`planshape.results.measure`): ``"end"`` — the success flag on the episode's
            last step; ``"any-step"`` — at any step (MetaWorld's protocol). Only how stored
            rows are scored: it is no part of a run's id.
        shaping_scale: φ's multiplier for every shaped run of the profile, in place of the
            hyperparameter tables' (:mod:`planshape.training.hyperparams`); ``None`` keeps the
            tables'. It is part of each shaped run's settings, so of its id; sparse and dense
            runs have no scale, so they are the same runs (same ids) as another profile's.
        observe_progress: every shaped run's learner sees its plan progress after the
            observation (:mod:`planshape.shaping.observed_progress`); recorded in its settings,
            so part of its id. Sparse and dense runs have no plan: their ids do not change.
    """

    name: str
    description: str
    blocks: Sequence[Block]
    eval_every: int
    eval_episodes: int
    caveats: Sequence[str] = field(default_factory=tuple)
    archived: str = ""
    success_measure: SuccessMeasure = "end"
    shaping_scale: float | None = None
    observe_progress: bool = False

    @property
    def folder(self) -> str:
        """Where its results are stored, relative to the repository root: ``leaderboard/`` for
        the default profile, ``leaderboard/<name>/`` for every other."""
        return RESULTS_ROOT if self.name == "default" else f"{RESULTS_ROOT}/{self.name}"

    def spec(self, key: RunKey, invariance: str = "not-checked") -> RunSpec:
        """The :class:`planshape.harness.runner.RunSpec` of one of its runs: the profile's
        evaluation settings and, for a shaped entry, its :attr:`shaping_scale` if it has one
        and its :attr:`observe_progress`.

        Example:
            >>> key = RunKey("planshape/Reach-v1", "dense", "PPO", 0, 4096)
            >>> PROFILES["smoke"].spec(key).hyperparameters["n_envs"]
            8
        """
        from planshape.harness.runner import RunSpec

        return RunSpec.create(
            key,
            self.name,
            self.eval_every,
            self.eval_episodes,
            invariance=invariance,
            shaping_scale=self.shaping_scale,
            observe_progress=self.observe_progress,
        )

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

    def header(self, rows: Sequence[Mapping[str, Any]] = ()) -> dict[str, Any]:
        """What a leaderboard of this profile's stored ``rows`` states above its tables: the
        same whichever command renders it (``planshape bench`` or ``planshape leaderboard``),
        and free of dates, so re-rendering unchanged rows leaves every file byte-identical.
        The command reproduces the rows: the profile plus each submitted potential in them.

        Example:
            >>> PROFILES["smoke"].header()["command"]
            'planshape bench --profile smoke'
        """
        own = {key.potential for key in self.runs()}
        submitted = sorted({str(r["potential"]) for r in rows if r.get("potential")} - own)
        command = self.archived or " ".join(
            ["planshape bench --profile", self.name, *(f"--potential {p}" for p in submitted)]
        )
        current = self._current(rows)
        stale = sorted(
            {
                (str(r["run_id"]), int(r["budget"]))
                for r, ok in zip(rows, current, strict=True)
                if not ok
            }
        )
        planned = {(k.task, k.entry, k.algo, k.seed) for k in self.runs()}
        stored = {
            (r["task"], r["entry"], r["algo"], int(r["seed"]))
            for r, ok in zip(rows, current, strict=True)
            if ok
        } & planned
        partial = (
            [
                f"partial: {len(stored)} of the profile's {len(planned)} runs are stored; "
                "the others have not been trained yet "
                f"({name_missing(planned - stored, self.name)})"
            ]
            if rows and len(stored) < len(planned) and not self.archived
            else []
        )
        kept = (
            [
                f"{len(stale)} stored runs at budgets or settings this profile no longer uses "
                f"(e.g. runs/{stale[0][0]}.jsonl, {stale[0][1]:,} steps) stay in runs/ and are "
                "not shown"
            ]
            if stale
            else []
        )
        measure = [] if self.success_measure == "end" else [describe(self.success_measure)]
        return {
            "profile": self.name,
            "description": self.description,
            "command": command,
            "caveats": [*partial, *measure, *self.caveats, *kept, *self._counted_at_end(rows)],
            "eval_every": self.eval_every,
            "eval_episodes": self.eval_episodes,
        }

    def budgets(self) -> dict[tuple[str, str], int]:
        """(task, algo) -> budget, for the leaderboard header."""
        return {(t, a): b.budgets[t] for b in self.blocks for t in b.tasks for a in b.algos}

    def shows(self, row: Mapping[str, Any]) -> bool:
        """Whether a stored row is one of this profile's cells as the profile is now: its task
        and algorithm are in the profile at the row's budget, and it trained with the settings
        the hyperparameter tables give its run now (:func:`current_settings`). A run stored
        before a budget or a table changed stays in the store, but is not mixed into the cells
        of the new budget or settings.

        Example:
            >>> from planshape.training.hyperparams import hyperparameters
            >>> smoke = PROFILES["smoke"]
            >>> settings = hyperparameters("planshape/Reach-v1", "PPO")
            >>> row = {"task": "planshape/Reach-v1", "entry": "dense", "algo": "PPO",
            ...        "budget": 4096, "hyperparameters": settings}
            >>> smoke.shows(row), smoke.shows({**row, "budget": 2048})
            (True, False)
            >>> smoke.shows({**row, "hyperparameters": {**settings, "learning_rate": 1e-3}})
            False
        """
        return self._current([row])[0]

    def shown(self, rows: Sequence[Mapping[str, Any]]) -> list[Mapping[str, Any]]:
        """The rows :meth:`shows` keeps, with success counted by the profile's
        :attr:`success_measure` (:func:`planshape.results.measure.measured`: a cell with a run
        that cannot be counted so stays counted at the episode's end, and :meth:`header` says
        so).

        Example:
            >>> row = {"run_id": "r", "success_rate": 0.0, "success_any_rate": 1.0}
            >>> METAWORLD_PROFILE.success_measure
            'any-step'
            >>> row |= {"task": "t", "algo": "SBX-SAC"}
            >>> [r["success_rate"] for r in METAWORLD_PROFILE._measured([row])]
            [1.0]
        """
        return self._measured(self._kept(rows))

    def _measured(self, rows: Sequence[Mapping[str, Any]]) -> list[Mapping[str, Any]]:
        return measured(rows, self.success_measure)[0]

    def _counted_at_end(self, rows: Sequence[Mapping[str, Any]]) -> list[str]:
        """The caveats on the cells the success measure leaves counted at the episode's end
        (:func:`planshape.results.measure.measured`), if any."""
        at_end = measured(self._kept(rows), self.success_measure)[1]
        return [
            f"{task} / {algo}: success counted at the episode's end, not at any step: "
            f"{len(ids)} of its stored runs predate the any-step rate (e.g. runs/{ids[0]}.jsonl). "
            f"Trained again (planshape bench --profile {self.name} --out DIR, with DIR empty), "
            "each run repeats its stored curve under the same id with the rate added; "
            f"planshape adopt DIR --out {self.folder} then replaces the old files"
            for (task, algo), ids in at_end.items()
        ]

    def _kept(self, rows: Sequence[Mapping[str, Any]]) -> list[Mapping[str, Any]]:
        """The rows :meth:`shows` keeps, as stored."""
        return [r for r, ok in zip(rows, self._current(rows), strict=True) if ok]

    def _current(self, rows: Sequence[Mapping[str, Any]]) -> list[bool]:
        """:meth:`shows` of every row, with the budget table built once."""
        budgets = self.budgets()
        return [
            budgets.get((r["task"], r["algo"])) == int(r["budget"])
            and r["hyperparameters"]
            == current_settings(
                r["task"], r["algo"], r["entry"], self.shaping_scale, self.observe_progress
            )
            for r in rows
        ]


@cache
def current_settings(
    task: str,
    algo: str,
    entry: str,
    shaping_scale: float | None = None,
    observe_progress: bool = False,
) -> dict[str, Any]:
    """The settings a run of ``entry`` by ``algo`` on ``task`` trains with now
    (:func:`planshape.training.hyperparams.hyperparameters`, read once per process: the tables
    are constants), with a profile's own ``shaping_scale`` if it has one and its
    ``observe_progress``. Callers compare with it and must not change it.

    Example:
        >>> current_settings("planshape/Reach-v1", "PPO", "dense")["n_envs"]
        8
    """
    from planshape.training.hyperparams import hyperparameters

    return hyperparameters(
        task, algo, entry, shaping_scale=shaping_scale, observe_progress=observe_progress
    )


SMOKE = Profile(
    name="smoke",
    description="reach, 3 entries, PPO, 1 seed, 4096 steps: checks the pipeline end to end",
    blocks=(
        Block(
            tasks=("planshape/Reach-v1",),
            algos=("PPO",),
            seeds=(0,),
            budgets={"planshape/Reach-v1": 4096},
            potentials=("plan-based",),
            models=("multi",),
        ),
    ),
    eval_every=2048,
    eval_episodes=5,
    caveats=("smoke profile: budgets far too small to learn; for checking the pipeline only",),
)

# Budgets are multiples of PPO's rollout (8 environments × 128 steps), so PPO trains exactly
# the budget. The same per task for a version and its distribution.

#: the v0 tasks' budgets (their stored runs): chosen before learning curves were measured
_V0_PPO_STEPS = {"Reach": 40 * 1024, "Push": 80 * 1024, "MazeReach": 80 * 1024}
_V0_SAC_STEPS = {"Reach": 10_000, "Push": 15_000, "MazeReach": 15_000}

#: PPO on the v1 tasks, from learning curves of ``planshape probe`` (evaluation of the
#: deterministic policy every 40,960 steps, seeds 0-2; the rule: dense reaches success on reach
#: and push, a planning-derived potential on maze-reach, where dense is trapped by the wall):
#:
#: * Reach 245,760: dense succeeds at 245,760 on 3/3 seeds (training-episode success 0.93,
#:   0.86, 0.87), the first point where all three do; at 204,800 none did.
#: * MazeReach 122,880: plan-distance/grid succeeds from 81,920 on 3/3 seeds and at every
#:   point after (training success 0.52-0.64 at 122,880); h-star-geodesic/grid 3/3 at 204,800.
#: * Push 819,200. Dense's curves to 655,360 (``planshape probe push dense --budget 655360 --chunks
#:   16``, seeds 0-4): seeds 0, 3 and 4 succeed from 204,800, 245,760 and 327,680 and at every point
#:   after (training success 0.97-1.00 from 368,640); seed 1 succeeds at 368,640, loses it from
#:   409,600 to 614,400 (training success down to 0.02 at 491,520) and succeeds from 655,360 on,
#:   held to 1,024,000 (seed 1 probed to 1,024,000: training success 0.89 at 655,360, 1.00 from
#:   778,240); seed 2 never moves the cylinder (0.34 m at every point). So dense is 3/5 from 327,680
#:   to 614,400 (the previous budget, 327,680, gave 3/5: the rule not met) and 4/5 from 655,360 on;
#:   819,200 leaves a quarter of margin past that point.
_PPO_STEPS = {"Reach": 240 * 1024, "Push": 800 * 1024, "MazeReach": 120 * 1024}
#: SBX-SAC on the v1 tasks (train_freq 4 × 4 gradient steps), from the same kind of curves
#: every 10,000 steps (``planshape probe TASK ENTRY --algo SBX-SAC --chunks …``), seeds 0-4:
#:
#: * Push 150,000: dense's deterministic policy succeeds on seeds 0-3 at every point from
#:   120,000 to 250,000 (first success at 100k, 110k, 50k, 30k; training success 0.94-1.00 at
#:   120k, 1.00 from 150k); seed 4 never succeeds up to 250,000 (training success 0.00 at every
#:   point). So dense is 4/5 = 0.8 from 120,000 on and the rule holds at 150,000 with 30k of
#:   margin; at 100,000 (the previous budget) it was 3/5, as the stored runs show.
#: * Reach 100,000: dense's deterministic policy succeeds from 30k, 40k, 60k and 80k on seeds
#:   4, 3, 0 and 1 and at every point after (but one: seed 4 at 120k); seed 2 never does up to
#:   150,000 (training success 0.02 there). Dense is 4/5 = 0.8 from 80,000 on: the rule holds
#:   at 100,000 with 20k of margin.
#: * MazeReach 50,000. At the rule's shaping scale (100) it was a transient: plan-distance/grid's
#:   deterministic policy succeeded at 30k on seeds 0, 1, 3, 4 but seeds 1, 3, 4 lost it by 40k
#:   (the ball learns to stop short) and no planning-derived potential held it up to 100k, so the
#:   budget was 30,000. With SAC's own scale (10, planshape.training.hyperparams), ``planshape
#:   probe maze-reach plan-distance/grid --algo SBX-SAC --budget 100000 --chunks 10``, seeds
#:   0-4: seeds 0, 1, 2 succeed from 30k, seed 3 from 40k, and all four at every point after, to
#:   100k (final distance 0.01-0.03 m); seed 4 never (0.25-0.34 m). So plan-distance holds 4/5
#:   from 40,000 on, and 50,000 leaves 10k of margin past the point where it is reached.
_SAC_STEPS = {"Reach": 100_000, "Push": 150_000, "MazeReach": 50_000}


def _per_task(steps: Mapping[str, int], tasks: Sequence[str]) -> dict[str, int]:
    """Budgets of ``tasks`` by their family (``planshape/PushRandomized-v1`` is a push task)."""
    return {t: steps[task_spec(t).family.removesuffix("Randomized")] for t in tasks}


_PLANAR_BUDGETS = _per_task(_PPO_STEPS, PLANAR + RANDOMIZED)
_SAC_BUDGETS = _per_task(_SAC_STEPS, PLANAR + RANDOMIZED)
_V0_BUDGETS = _per_task(_V0_PPO_STEPS, PLANAR_V0)
_V0_SAC_BUDGETS = _per_task(_V0_SAC_STEPS, PLANAR_V0)
REACH, MAZE = "planshape/Reach-v1", "planshape/MazeReach-v1"


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


def _v0_default_blocks() -> tuple[Block, ...]:
    """The blocks of the archived default profile of the v0 tasks (its stored runs)."""
    planar, push = PLANAR_V0, ("planshape/Push-v0",)
    return (
        Block(planar, ("PPO",), tuple(range(5)), _V0_BUDGETS, models=PAPER_MODELS),
        Block(
            planar,
            (SAC,),
            tuple(range(2)),
            _V0_SAC_BUDGETS,
            PAPER_POTENTIALS + CONTROL_POTENTIALS,
            models=("grid",),
        ),
        _shaped_only(planar, SAC, 2, _V0_SAC_BUDGETS, ("plan-path",), GRID_MODELS),
        Block(push, (SAC,), tuple(range(5)), _V0_SAC_BUDGETS, CONTROL_POTENTIALS, ("grid",)),
        _shaped_only(push, SAC, 5, _V0_SAC_BUDGETS, ("plan-path",), GRID_MODELS),
        _shaped_only(planar, "PPO", 5, _V0_BUDGETS, PLANNING_POTENTIALS, GRID_MODELS),
        _shaped_only(planar, "PPO", 5, _V0_BUDGETS, CONTROL_POTENTIALS, ("grid",)),
    )


_DEFAULT_DESCRIPTION = (
    "reach, push, maze-reach × {sparse, dense, 3 potentials × 3 models} × PPO × 5 seeds, "
    "plus SAC (tuned) on sparse, dense, the grid potentials, plan-path and goal-distance × "
    "2 seeds (5 on push for sparse, dense, plan-path and goal-distance), plus the "
    "planning-derived potentials (plan-distance, plan-path, h-star, h-star-geodesic) on "
    "the grid models and the goal-distance control × PPO × 5 seeds"
)
_SAC_BUDGET_CAVEAT = (
    "SAC runs get smaller budgets than PPO (SAC takes one gradient step per environment "
    "step; on 2 CPU cores these budgets keep the profile near an hour and a half)"
)
_RESCALED_CAVEAT = (
    "PPO and SAC see the observation rescaled from its bounds to [-1, 1] "
    "(rescale_observations, planshape.training.hyperparams); on raw metres no entry solved "
    "maze-reach"
)
#: the archived v0 profile's: every table scaled φ by the rule then
_V0_SHARED_CAVEATS = (
    "every potential's φ is multiplied by shaping_scale = 1/(1 − γ) = 100 (planshape."
    "hyperparams); the source paper tuned a multiplier per potential by hand, this "
    "benchmark applies one rule to every entry",
    _RESCALED_CAVEAT,
)
_SHARED_CAVEATS = (
    f"every potential's φ is multiplied by shaping_scale: 1/(1 − γ) = {SHAPING_SCALE:g} for "
    f"PPO, {SAC_SHAPING_SCALE:g} for SAC (planshape.training.hyperparams: at {SHAPING_SCALE:g}, "
    "SAC's planning-derived potentials trailed sparse on reach and lost maze-reach after "
    f"30,000 steps; at {SAC_SHAPING_SCALE:g} plan-distance/grid solves reach on 4 of 5 seeds, as "
    "dense does); the source paper tuned a multiplier per potential "
    "by hand, this benchmark applies one per learner to every entry, and sparse and dense "
    "runs have none",
    _RESCALED_CAVEAT,
)
_V1_CAVEATS = (
    "the tasks are the source paper's (v1): reach behind its wall, push with its cylinder, "
    "its subgoal-based dense rewards; episodes are 50 (reach, maze-reach) and 40 (push) "
    "steps, not the paper's 25, in which the goals cannot be reached at 0.02 m per step",
    "each task starts every episode in one state and is deterministic, so every "
    "evaluation point is one episode and a run's success is 0 or 1",
    "goal-distance is a control, not a planning-derived potential: the straight-line "
    "distance to the goal (v0's dense reward) used as a potential",
    "SAC is SBX's (JAX), SBX-SAC, with stable-baselines3's SAC hyperparameters; budgets per "
    "task and algorithm come from measured learning curves (planshape.harness.profiles)",
)

#: the entries of the default profile: the references, the paper's plan-based potential on its
#: three models, and the planning-derived potentials and the control on the grid model
_DEFAULT_PPO_ENTRIES = (
    Block(
        (REACH, MAZE),
        ("PPO",),
        tuple(range(5)),
        _PLANAR_BUDGETS,
        ("plan-based", "plan-distance", *CONTROL_POTENTIALS),
        ("grid",),
    ),
)
_DEFAULT_SAC_ENTRIES = (
    Block(PUSH, (SBX_SAC,), tuple(range(5)), _SAC_BUDGETS, ("plan-distance",), ("grid",)),
)

DEFAULT = Profile(
    name="default",
    description=(
        "reach and maze-reach × {sparse, dense, plan-based, plan-distance and goal-distance "
        "on the grid model} × PPO, and push × {sparse, dense, plan-distance on the grid "
        "model} × SAC, 5 seeds each, on the source paper's tasks (v1), at budgets from "
        "measured learning curves; the rest of the paper's grid (the single and multi models, "
        "plan-path, the h* potentials) is in the planar profile"
    ),
    blocks=(*_DEFAULT_PPO_ENTRIES, *_DEFAULT_SAC_ENTRIES),
    eval_every=10_000,
    eval_episodes=10,
    caveats=(
        "what fits in an hour on 2 CPU cores: PPO on reach and maze-reach, SAC on push (PPO's "
        f"dense reward needs {_PPO_STEPS['Push']:,} steps on push, where it solves 4 of 5 "
        "seeds: 25 more runs of about 2.4 minutes each would take this profile past its hour, "
        "so PPO's push cells are the planar profile's); the paper's other potentials and "
        "models, plan-path, SAC on reach and maze-reach and PPO on push are in the planar "
        "profile (the single- and multi-model and plan-path runs this profile "
        "carried until it was measured at 68 minutes from an empty folder are there)",
        "SAC on push trains 150,000 steps: dense's learning curves (seeds 0-4) succeed on 4 of "
        "5 seeds from 120,000 steps on (seed 4 never moves the cylinder), so 0.8 is the most "
        "dense reaches here; the runs at the previous budget, 100,000 (dense 3/5), stay "
        "stored",
        *_SHARED_CAVEATS,
        *_V1_CAVEATS,
    ),
)

#: why the planar budgets that replaced earlier ones are what they are (the planar and paper
#: profiles train at them)
_PLANAR_BUDGET_CAVEATS = (
    f"PPO on push trains {_PPO_STEPS['Push']:,} steps: dense's learning curves (seeds "
    "0-4) succeed on 4 of 5 seeds from 655,360 steps on (seed 2 never moves the "
    "cylinder) and on 3 of 5 before; the runs at the previous budget, 327,680 (dense 3/5, "
    "short of the rule's 0.8), stay stored",
    f"SAC on maze-reach trains {_SAC_STEPS['MazeReach']:,} steps: plan-distance/grid's "
    f"learning curves (SAC's shaping scale, {SAC_SHAPING_SCALE:g}) solve it on 4 of 5 seeds "
    "from 40,000 steps on and keep it to 100,000 (planshape.harness.profiles); the runs at "
    f"the previous budget, 30,000 (chosen at scale {SHAPING_SCALE:g}, where it was a "
    "transient), stay stored",
)

PLANAR_PROFILE = Profile(
    name="planar",
    description=(
        "reach, push, maze-reach × {sparse, dense, 3 potentials × 3 models, the "
        "planning-derived potentials on the grid models, goal-distance} × PPO and SAC × 5 "
        "seeds, on the source paper's tasks (v1): the default profile's grid in full (hours "
        "on 2 CPU cores)"
    ),
    blocks=(
        Block(PLANAR, ("PPO",), tuple(range(5)), _PLANAR_BUDGETS, models=PAPER_MODELS),
        Block(PLANAR, (SBX_SAC,), tuple(range(5)), _SAC_BUDGETS, models=PAPER_MODELS),
        *(
            _shaped_only(PLANAR, algo, 5, budgets, PLANNING_POTENTIALS, GRID_MODELS)
            for algo, budgets in (("PPO", _PLANAR_BUDGETS), (SBX_SAC, _SAC_BUDGETS))
        ),
        *(
            _shaped_only(PLANAR, algo, 5, budgets, CONTROL_POTENTIALS, ("grid",))
            for algo, budgets in (("PPO", _PLANAR_BUDGETS), (SBX_SAC, _SAC_BUDGETS))
        ),
    ),
    eval_every=10_000,
    eval_episodes=10,
    caveats=(
        *_PLANAR_BUDGET_CAVEATS,
        *_SHARED_CAVEATS,
        *_V1_CAVEATS,
    ),
)

DEFAULT_V0 = Profile(
    name="default-v0",
    description=_DEFAULT_DESCRIPTION
    + ", on the v0 tasks (reach without its wall, push with a box)",
    blocks=_v0_default_blocks(),
    eval_every=10_000,
    eval_episodes=10,
    caveats=(
        _SAC_BUDGET_CAVEAT,
        *_V0_SHARED_CAVEATS,
        "episodes are 40 (reach, push) and 50 (maze-reach) steps, not the paper's 25: the "
        "goals cannot be reached in 25 steps of 0.02 m",
        "goal-distance is a control, not a planning-derived potential: the dense reward's own "
        "distance used as a potential; where it also trails dense, the gap is what keeping "
        "the optimal policy costs, not what the plan lacks",
        "v0 tasks differ from the source paper's: reach has no wall, push's object is a square "
        "box; evaluation protocol 1 ran 10 copies of the one deterministic episode and "
        "recorded PPO's points before the rollout's update",
    ),
    archived=(
        "archived: the default profile of the v0 tasks, evaluated with protocol 1; kept for "
        "its stored runs (leaderboard/default-v0). Reproduce it: git checkout 802aaba, "
        "then tox -e bench"
    ),
)

PAPER = Profile(
    name="paper",
    description=(
        "the source paper's grid (reach, push, maze-reach × {sparse, dense, 3 potentials × 3 "
        "models}) × PPO, tuned SAC (SBX-SAC) and untuned SAC (SAC-default: stable-baselines3's "
        "library defaults, as the paper ran SAC with its library's) × 5 seeds, at the planar "
        "profile's budgets, so that SAC-default is compared with tuned SAC at budgets where "
        "tuned SAC's dense reward solves reach and push (the PPO and SBX-SAC runs are the "
        "planar profile's: copy them in)"
    ),
    blocks=(
        Block(PLANAR, ("PPO",), tuple(range(5)), _PLANAR_BUDGETS, models=PAPER_MODELS),
        Block(PLANAR, (SBX_SAC, "SAC-default"), tuple(range(5)), _SAC_BUDGETS, models=PAPER_MODELS),
    ),
    eval_every=10_000,
    eval_episodes=10,
    caveats=(
        "SAC-default is stable-baselines3's SAC with its library defaults (a [256, 256] MLP, "
        "learning rate 3e-4, a 10^6 buffer, 100 random steps, one gradient step per step) and "
        "raw observations; the paper used EasyRL's defaults, which this does not reproduce",
        *_PLANAR_BUDGET_CAVEATS,
        *_SHARED_CAVEATS,
        *_V1_CAVEATS,
    ),
)

FULL = Profile(
    name="full",
    description="paper plus MetaWorld (8 tasks) and gymnasium-robotics (PointMaze, Fetch)",
    blocks=(
        *PAPER.blocks,
        Block(
            METAWORLD + ROBOTICS,
            ("PPO", SBX_SAC),
            tuple(range(5)),
            {t: 500_000 for t in METAWORLD + ROBOTICS},
            potentials=("plan-based", "distance-varying", "plan-distance"),
        ),
    ),
    eval_every=50_000,
    eval_episodes=20,
    caveats=PAPER.caveats,
)

#: PPO's rollout on MetaWorld is 8 environments × 512 steps; 25 rollouts
_METAWORLD_BUDGET = 25 * 8 * 512

_RAW_OBSERVATIONS_CAVEAT = (
    "observations are MetaWorld's raw ones (no finite bounds to rescale from)"
)

_METAWORLD_CAVEATS = (
    "a reduction of the full profile's MetaWorld block (500k steps × 5 seeds × PPO and SAC "
    "× 5 entries) to what 2 CPU cores train in about 80 minutes (2.64 h of runs): PPO "
    "trains MetaWorld at about 1,300 steps/s on one core and SAC ([256, 256], one gradient "
    "step per step) at about 50, so the full block would take days; 102k steps are 25 PPO "
    "updates, far below the millions MetaWorld tasks usually need",
    _RAW_OBSERVATIONS_CAVEAT,
)


def _metaworld(name: str, tasks: Sequence[str], caveats: Sequence[str] = (), archived: str = ""):
    """The metaworld profile on ``tasks``."""
    return Profile(
        name=name,
        description=(
            "the 8 MetaWorld tasks × {sparse, dense, plan-based, plan-distance} on the stages "
            "model × PPO × 2 seeds, 102,400 steps each"
        ),
        blocks=(
            Block(
                tasks,
                ("PPO",),
                (0, 1),
                {t: _METAWORLD_BUDGET for t in tasks},
                potentials=("plan-based", "plan-distance"),
                models=("stages",),
            ),
        ),
        eval_every=4 * 8 * 512,
        eval_episodes=10,
        caveats=(*_METAWORLD_CAVEATS, *caveats),
        archived=archived,
    )


#: SBX-SAC on MetaWorld: the tasks on which the dense reward reaches ≥ 0.8 success within the
#: budget, each budget from dense's learning curve (``planshape probe planshape/MetaWorld-TASK
#: dense --algo SBX-SAC --budget 200000 --chunks 10``, seed 0; success over 10 deterministic
#: episodes every 20,000 steps):
#: reach-v4: 0.1, 0.2, 0.5, 0.6, 0.4, 0.6, 0.9, 0.8, 0.8, 1.0 at 20,000 ... 200,000 (final
#: distance 0.030 m; 25 minutes on one of two busy cores) -> 200,000. Over the profile's 5
#: seeds dense ends at 1.0, 0.7, 0.5, 0.3, 0.3 at the episode's end (mean 0.56; final distance
#: 0.030-0.077 m) and at 1.0, 1.0, 1.0, 0.9, 0.8 at any step, the profile's count (mean 0.94;
#: the seed mean is 0.80 or more from 60,000 steps on): the rule holds.
#: drawer-close-v3: 0.2, 0.7, 0.9, 1.0, 0.9, 1.0, 0.9, 0.9, 1.0, 1.0 (≥ 0.9 from 60,000 on) ->
#: 100,000, which leaves dense's other seeds room beyond seed 0's 60,000. Over the profile's 5
#: seeds dense ends at 0.9, 0.9, 1.0, 0.9, 1.0 at the episode's end (mean 0.94) and at 1.0 on
#: every seed at any step, the profile's count: the rule holds, but sparse ends at 1.0 too.
#: door-open-v3: 0.0 up to 60,000, then 0.1, 0.0, 0.4, 0.0, 0.1, 0.5, 0.6 (final distance 0.117
#: m, still falling): short of 0.8 at 200,000 at the episode's end. Probed again to 400,000
#: (``--budget 400000 --chunks 20``; its end-of-episode points repeat these), counted at any
#: step as the profile counts: 0.0, 0.0, 0.0, 0.1, 0.1, 0.9, 0.6, 0.3, 0.8, 0.9 at 20,000 ...
#: 200,000, then 1.0, 0.9, 1.0, 0.9, 1.0, 1.0, 1.0, 1.0, 0.8, 1.0 to 400,000 (end of episode
#: 0.3-0.8 from 200,000 on) -> 240,000: 60,000 past 180,000, from where the any-step success
#: stays at 0.8 or more. Dense's 5 seeds at 240,000 (trained as the profile would) end at 0.9,
#: 0.9, 1.0, 0.0, 0.6 at any step (mean 0.68; seed 3 opens the door in no episode at any
#: point) -> not in the profile: short of 0.8 at 240,000, and one seed not learning at all says
#: a larger budget needs its own 5-seed check first.
#: window-open-v3: 0.0 up to 60,000, then 0.2, 0.0, 0.7, 0.7, 0.5, 0.5, 0.4 (training-episode
#: success 0.65 at the end): short of 0.8 at 200,000 at the episode's end. Probed again to
#: 400,000 (``--budget 400000 --chunks 20``; its end-of-episode points repeat these), counted
#: at any step: 0.0, 0.0, 0.0, 0.2, 0.0, 0.7, 0.7, 0.5, 0.9, 0.8 at 20,000 ... 200,000, then
#: 1.0, 1.0, 0.9, 0.9, 0.9, 0.5, 1.0, 1.0, 1.0, 1.0 to 400,000 (end of episode 1.0 from
#: 360,000) -> 240,000 (60,000 past 180,000; one point at 0.5, 320,000), kept only if dense's
#: 5 seeds at that budget reach 0.8 (door-open's did not). They end at 1.0, 0.9, 0.9, 0.9, 1.0
#: at any step, the profile's count (mean 0.94; every seed at 0.8 or more from 200,000 on), and
#: at 0.8, 0.6, 0.8, 0.9, 0.7 at the episode's end (mean 0.76): the rule holds.
#: button-press-topdown-v3: 0.0, 0.0, 0.1, 0.0, 0.0, 0.5, 0.5, 0.2, 0.4, 0.7 (training-episode
#: success 1.00 at the end, still rising): short of 0.8 at 200,000 at the episode's end. Probed
#: again to 400,000 (``--budget 400000 --chunks 20``; its end-of-episode points repeat these),
#: counted at any step: 0.0, 0.1, 0.3, 0.3, 0.0, 0.5, 0.8, 0.8, 1.0, 1.0 at 20,000 ... 200,000
#: and 1.0 at every point after (end of episode 1.0 from 220,000; final distance 0.009 m) ->
#: 200,000: 60,000 past 140,000, from where the any-step success stays at 0.8 or more.
#: window-close-v3: 0.0, 0.3, 1.0, 0.5, 0.0, 1.0, 0.6, 1.0, 0.5, 1.0 (final distance 0.008 m;
#: training-episode success 0.80, 0.85, 0.95 over the last three points) -> 200,000, where both
#: the deterministic and the training-episode success have reached 0.8; the deterministic
#: policy swings between points, so other seeds' final points may fall short. Over the
#: profile's 5 seeds dense ends at 1.0, 0.9, 0.4, 0.8, 0.2 at the episode's end (mean 0.66),
#: and at 1.0, 0.9, 0.8, 0.8, 1.0 at any step, the profile's count (mean 0.90): the rule holds.
#: button-press-v3: 0.0, 0.0, 0.0, 0.9, 1.0, 1.0, 0.8, 0.7, 0.9, 0.9 (final distance 0.021 m)
#: -> 120,000: 40,000 past seed 0's first 0.8, as for drawer-close; 200,000 would cost two
#: thirds more for a curve no higher after 120,000. Over the profile's 5 seeds dense ends at
#: 1.0, 0.1, 0.9, 0.3, 0.8 (mean 0.62): short of the rule. Its deterministic success swings
#: between points (seed 3: 1.0 at 100,000, 0.3 at 120,000; seed 1 never above 0.4), so one
#: seed's curve did not predict the others'. At any step, the profile's count, dense ends at 1.0,
#: 0.8, 1.0, 1.0, 1.0 (mean 0.96; the runs trained again, each repeating its stored rows): the
#: rule holds, as on window-close.
METAWORLD_SAC_BUDGETS: dict[str, int] = {
    "planshape/MetaWorld-reach-v4": 200_000,
    "planshape/MetaWorld-drawer-close-v3": 100_000,
    "planshape/MetaWorld-window-close-v3": 200_000,
    "planshape/MetaWorld-button-press-v3": 120_000,
    "planshape/MetaWorld-button-press-topdown-v3": 200_000,
    "planshape/MetaWorld-window-open-v3": 240_000,
}
#: the evaluation interval of the probes that chose the budgets, so that a seed-0 bench run
#: repeats its probe's curve
_METAWORLD_SAC_EVAL_EVERY = 20_000
#: the tasks whose plans move an object after the hand is in place: there ``plan-distance``
#: measures only the hand's offset from a place that moves with the object (under the scripted
#: expert φ rises over that step by 17 % and 18 % of what the drawer's and window's travel is
#: worth, and by 22 % of the button's while it is pressed in; leaderboard/METAWORLD.md) and
#: ``plan-distance-sum`` measures the object too (≥ 90 %; tests/tasks/test_metaworld.py). On
#: reach-v4 they are equal.
#: What the 5-seed runs measured is on leaderboard/metaworld and in leaderboard/METAWORLD.md,
#: derived from the stored runs, not copied here.
METAWORLD_OBJECT_TASKS = tuple(t for t in METAWORLD_SAC_BUDGETS if "reach" not in t)
#: button-press-topdown's second geometry, ``stages-above`` (planshape.tasks.metaworld.button):
#: ``stages`` places only the hand's horizontal offset from the button, and a hand moved
#: straight to that target stops against the button's box, 11 cm below its top, where the
#: predicate does not hold. ``stages-above`` places the hand over the button's top, where the
#: scripted expert presses from. Only the distance potentials use a geometry (plan-based on
#: stages-above would repeat plan-based/stages's numbers), so the profile runs those two on it.
_TOPDOWN = "planshape/MetaWorld-button-press-topdown-v3"

#: what the page of every SBX-SAC MetaWorld profile says about its budgets and evaluation
_METAWORLD_SAC_CAVEATS = (
    "budgets per task from SBX-SAC learning curves of the dense reward (planshape.harness."
    "profiles): at each, dense's deterministic success on seed 0 has reached 0.8; over 5 "
    "seeds dense ends short of 0.8 at the episode's end on button-press (0.62), reach-v4 "
    "(0.56) and window-close (0.66), and reaches it at any step on window-close (0.90), "
    "button-press (0.96) and reach-v4 (0.94); on drawer-close it reaches it both ways "
    "(0.94 at the episode's end, 1.00 at any step); on button-press-topdown, whose budget "
    "comes from an any-step curve, 0.88 at any step (0.60 at the episode's end); on "
    "window-open, likewise, 0.94 at any step (0.76 at the episode's end)",
    "each evaluation point runs 10 deterministic episodes from starts drawn from fixed "
    "seeds; MetaWorld episodes are 500 steps and never terminate",
)

METAWORLD_PROFILE = Profile(
    name="metaworld",
    description=(
        "MetaWorld tasks on which SAC's dense reward reaches 0.8 success within the budget × "
        "{sparse, dense, plan-based, plan-distance, and plan-distance-sum where the plan moves "
        "an object} on the stages model (and plan-distance, plan-distance-sum on "
        "button-press-topdown's stages-above) × SAC (SBX) × 5 seeds"
    ),
    blocks=(
        Block(
            tuple(METAWORLD_SAC_BUDGETS),
            (SBX_SAC,),
            tuple(range(5)),
            METAWORLD_SAC_BUDGETS,
            potentials=("plan-based", "plan-distance"),
            models=("stages",),
        ),
        Block(
            METAWORLD_OBJECT_TASKS,
            (SBX_SAC,),
            tuple(range(5)),
            METAWORLD_SAC_BUDGETS,
            potentials=("plan-distance-sum",),
            models=("stages",),
            include_sparse_dense=False,
        ),
        Block(
            (_TOPDOWN,),
            (SBX_SAC,),
            tuple(range(5)),
            METAWORLD_SAC_BUDGETS,
            potentials=("plan-distance", "plan-distance-sum"),
            models=("stages-above",),
            include_sparse_dense=False,
        ),
    ),
    eval_every=_METAWORLD_SAC_EVAL_EVERY,
    eval_episodes=10,
    success_measure="any-step",
    caveats=(
        *_METAWORLD_SAC_CAVEATS,
        f"every potential's φ is multiplied by shaping_scale = 1/(1 − γ) = {SHAPING_SCALE:g}, "
        f"not SAC's planar {SAC_SHAPING_SCALE:g}: probes at {SAC_SHAPING_SCALE:g} brought no "
        "shaped entry to dense on reach-v4 (plan-distance/stages, seeds 1-4) or button-press "
        "(plan-distance-sum/stages, seeds 0-1), and held the goal on window-open where runs at "
        f"{SHAPING_SCALE:g} lost it (planshape.training.hyperparams); sparse and dense runs "
        "have none; the metaworld-s10 profile runs the same cells at "
        f"{SAC_SHAPING_SCALE:g}",
        _RAW_OBSERVATIONS_CAVEAT,
    ),
)
#: The metaworld profile's cells with every potential at SAC's planar scale,
#: :data:`SAC_SHAPING_SCALE`, instead of the rule's 100. At 100, holding a goal whose φ is near
#: its top costs (1 − γ)·100·φ ≈ 1 reward a step, the sparse reward's own size; the stored
#: runs at 100 learn and lose the goal (window-open, reach-v4, window-close; on button-press
#: every shaped entry ends below sparse). Probes at 10 (planshape.training.hyperparams) held
#: it. Sparse and dense runs have no scale: they are the metaworld profile's runs, ids and all
#: (copied from leaderboard/metaworld with ``planshape adopt``), and only the shaped runs train.
METAWORLD_S10_PROFILE = dataclasses.replace(
    METAWORLD_PROFILE,
    name="metaworld-s10",
    description=(
        "the metaworld profile's cells with every potential's φ multiplied by SAC's planar "
        f"shaping scale, {SAC_SHAPING_SCALE:g}, instead of 1/(1 − γ) = {SHAPING_SCALE:g}: "
        "sparse and dense are the metaworld profile's runs"
    ),
    shaping_scale=SAC_SHAPING_SCALE,
    caveats=(
        *_METAWORLD_SAC_CAVEATS,
        f"every potential's φ is multiplied by {SAC_SHAPING_SCALE:g}, SAC's planar shaping "
        f"scale, not the rule's {SHAPING_SCALE:g} (the metaworld profile's); sparse and dense "
        "runs have none and are the metaworld profile's runs",
        _RAW_OBSERVATIONS_CAVEAT,
    ),
)
#: The metaworld-s10 profile's cells with every shaped run's learner seeing its plan progress
#: (max_idx / n) after MetaWorld's observation (:mod:`planshape.shaping.observed_progress`):
#: φ depends on progress, which the observation alone does not determine (button-press's
#: ``(hand-in-front)`` holds anywhere in a slab in front of the button), so without it the
#: critic's targets carry noise of up to half φ's scale. The exploratory probe that suggested it
#: is in planshape.training.hyperparams. Sparse and dense have no plan: they are the metaworld
#: profile's runs, ids and all.
METAWORLD_PROGRESS_PROFILE = dataclasses.replace(
    METAWORLD_S10_PROFILE,
    name="metaworld-progress",
    description=(
        "the metaworld-s10 profile's cells (φ multiplied by "
        f"{SAC_SHAPING_SCALE:g}) with every shaped run's learner seeing its plan progress "
        "after the observation: sparse and dense are the metaworld profile's runs"
    ),
    observe_progress=True,
    caveats=(
        *_METAWORLD_SAC_CAVEATS,
        f"every potential's φ is multiplied by {SAC_SHAPING_SCALE:g} (as in metaworld-s10), "
        "and every shaped run's learner sees its plan progress max_idx / n as one more number "
        "after MetaWorld's 39, in training and evaluation; sparse and dense runs see the 39 "
        "only and are the metaworld profile's runs",
        _RAW_OBSERVATIONS_CAVEAT,
    ),
)
#: A held-out test of the MetaWorld question (a planning-derived potential at least dense, or
#: faster, on at least half the tasks), fixed before any of its runs trained: the variants
#: above were chosen after the metaworld runs had been seen, on the same tasks, so their
#: verdicts are not a clean test. Everything here was decided from those profiles alone:
#:
#: * the tasks: MetaWorld tasks that no profile had trained with SAC, in waves, each fixed in
#:   code before any run of it (:data:`METAWORLD_HOLDOUT_CANDIDATES`);
#: * one budget for all, 200,000 steps, the metaworld profile's most common, set before any
#:   curve of these tasks was seen;
#: * one shaped entry, ``plan-distance-sum/stages``, with φ × 10 and the plan progress observed
#:   (metaworld-progress's configuration and its best entry on 4 of its 5 object tasks), so that
#:   no cell's verdict is the best of several entries;
#: * the rule's qualification: a task decides only if dense's 5 seeds reach a mean success of
#:   0.8 at any step at the budget. Dense trains first; a task whose dense seed 0 ends below 0.5
#:   is dropped before its other runs (it cannot qualify without the other four seeds averaging
#:   0.875 or more), and the drop is stated here with the curve
#:   (:data:`METAWORLD_HOLDOUT_SCREENED_OUT`).
#:
#: A later wave is chosen after the earlier waves' dense screens only, never after a shaped or
#: sparse run of the profile, so the shaped entry's comparison with dense stays held out.
METAWORLD_HOLDOUT_CANDIDATES = tuple(
    f"planshape/MetaWorld-{name}-v3"
    for name in (
        # wave 1 (commit abea209): the registered tasks no profile had trained with SAC
        "drawer-open",
        "push",
        "pick-place",
        # wave 2, registered for it after wave 1's screens of drawer-open and push: one
        # press, slide or swing each, like the tasks whose dense reward qualified in the
        # metaworld profile (handle-press like button-press, plate-slide like drawer-close,
        # faucet-open like window-open); door-close was left out: MetaWorld's reset leaves its
        # door inside the safe, and the door swings 6-9 mm a step on its own after it, which
        # tests/tasks/test_metaworld.py refuses
        "handle-press",
        "plate-slide",
        "faucet-open",
    )
)
#: candidates the screen dropped: dense's seed 0 (any-step success of 10 deterministic
#: episodes at 0, 20,000, ..., 200,000 steps; ``planshape bench --profile metaworld-holdout
#: --tasks TASK --seeds 0 -k dense``), not stored (as the probes that chose the other MetaWorld
#: budgets are not)
METAWORLD_HOLDOUT_SCREENED_OUT: dict[str, str] = {
    "planshape/MetaWorld-drawer-open-v3": (
        "dense seed 0: 0.0 at every point (its handle 0.19 m from the goal throughout)"
    ),
    "planshape/MetaWorld-push-v3": (
        "dense seed 0: 0.0 to 140,000, then 0.2, 0.0, 0.1 (final distance 0.28 m)"
    ),
    "planshape/MetaWorld-pick-place-v3": (
        "dense seed 0: 0.0 at every point but 0.2 at 160,000 (final distance 0.43 m)"
    ),
}
METAWORLD_HOLDOUT_TASKS = tuple(
    t for t in METAWORLD_HOLDOUT_CANDIDATES if t not in METAWORLD_HOLDOUT_SCREENED_OUT
)
METAWORLD_HOLDOUT_BUDGET = 200_000
METAWORLD_HOLDOUT_PROFILE = dataclasses.replace(
    METAWORLD_PROGRESS_PROFILE,
    name="metaworld-holdout",
    description=(
        "a held-out test fixed before its runs: MetaWorld tasks no other profile trained with "
        "SAC × "
        "{sparse, dense, plan-distance-sum on the stages model, φ multiplied by "
        f"{SAC_SHAPING_SCALE:g} and the plan progress observed}} × SAC (SBX) × 5 seeds, "
        f"{METAWORLD_HOLDOUT_BUDGET:,} steps each"
    ),
    blocks=(
        Block(
            METAWORLD_HOLDOUT_TASKS,
            (SBX_SAC,),
            tuple(range(5)),
            dict.fromkeys(METAWORLD_HOLDOUT_TASKS, METAWORLD_HOLDOUT_BUDGET),
            potentials=("plan-distance-sum",),
            models=("stages",),
        ),
    ),
    caveats=(
        "fixed before any of its runs trained (tasks, budget, the one shaped entry and its "
        "settings; planshape.harness.profiles): a held-out test of the configuration the "
        "metaworld-progress profile was chosen to be, on tasks none of the SAC MetaWorld "
        "profiles ran",
        f"one budget for every task, {METAWORLD_HOLDOUT_BUDGET:,} steps, set before any of "
        "their learning curves was seen; a task decides only where dense's 5 seeds reach a "
        "mean success of 0.8 there",
        "dropped by the screen (dense's seed 0 below 0.5 at the budget) before their other "
        "runs: "
        + "; ".join(
            f"{task.removeprefix('planshape/')}, {why}"
            for task, why in METAWORLD_HOLDOUT_SCREENED_OUT.items()
        ),
        "each evaluation point runs 10 deterministic episodes from starts drawn from fixed "
        "seeds; MetaWorld episodes are 500 steps and never terminate",
        f"the shaped entry's φ is multiplied by {SAC_SHAPING_SCALE:g} and its learner sees its "
        "plan progress max_idx / n after MetaWorld's 39 numbers; sparse and dense see the 39 "
        "only",
        _RAW_OBSERVATIONS_CAVEAT,
    ),
)
METAWORLD_V0_PROFILE = _metaworld(
    "metaworld-v0",
    METAWORLD_V0,
    caveats=(
        "reach-v3's hand-at lags MetaWorld's success by 2-5 steps (reach-v4 fixes it); "
        "evaluation protocol 1 recorded PPO's points before the rollout's update",
    ),
    archived=(
        "archived: the metaworld profile with reach-v3, evaluated with protocol 1; kept for "
        "its stored runs (leaderboard/metaworld-v0). Reproduce with git checkout 802aaba, then "
        "tox -e bench -- --profile metaworld --out leaderboard/metaworld"
    ),
)

#: the three planning-derived entries that solved the most of the fixed tasks with PPO (the
#: planar profile, 5 seeds: plan-based/grid 1.0 + 0.8 + 0.0 mean success over maze-reach, reach
#: and push; time-varying/grid 0.2 + 1.0 + 0.4; plan-distance/grid 1.0 + 0.0 + 0.0, tied with
#: distance-varying/grid; plan-path/grid solved none)
INSTANCE_POTENTIALS = ("plan-based", "time-varying", "plan-distance")
#: PPO on the distributions, from learning curves of ``planshape probe
#: planshape/ReachRandomized-v1 ENTRY --budget 409600 --chunks 10`` (each point: the 50 held-out
#: instances): dense's held-out success is 0.00-0.06 at every point up to 409,600 on seeds 0-2
#: (0.06, 0.04, 0.00 at the end; training-episode success 0.12, 0.04, 0.03; final distance
#: 0.155-0.160 m from 0.22-0.26 m untrained), and plan-based/grid's 0.00 at every point (seeds
#: 0-1). So no PPO budget this machine can afford satisfies the rule (dense ≥ 0.8) on the reach
#: distribution: more than 1.7 times the fixed task's budget does not bring dense to 0.1. The
#: profile keeps the fixed task's budget there, and says so in a caveat.
#: On the maze-reach distribution (``planshape probe planshape/MazeReachRandomized-v1 ENTRY
#: --budget 245760 --chunks 10``, held-out success per point), dense solves 0.00 of the held-out
#: instances at every point on seeds 0-1 (final distance 0.20-0.21 m, stuck at the wall as on
#: the fixed task), plan-distance/grid 0.00 at every point but seed 1's last (0.04), and
#: plan-based/grid 0.20, 0.12, 0.00 at the fixed task's 122,880 and 0.42, 0.22, 0.28 at 245,760
#: (seeds 0-2; seed 0 from 98,304 on between 0.12 and 0.42, seed 2 still rising). 245,760 is
#: where a planning-derived potential solves a fifth to two fifths of the unseen instances and
#: dense none, so the maze distribution trains twice the fixed task's PPO budget. Four times
#: that budget would not make the cell decide (``--budget 983040 --chunks 8``, held-out success
#: at 122,880 ... 983,040): plan-based/grid seed 0 0.20 0.42 0.60 0.60 0.58 0.66 0.62 0.62, seed
#: 2 0.00 0.28 0.74 0.72 0.94 0.84 0.84 0.78; time-varying/grid seed 1 0.60 0.78 0.84 0.90 0.90
#: 0.92 0.88 0.90, seeds 0 and 2 0.00 at every point (the hand drifts away: training distance
#: 0.33 m rising to 0.39-0.41 m); and sparse catches up, seed 3 0.00 0.40 0.72 0.80 0.88 0.88
#: 0.88 0.88, seed 0 0.00 0.00 0.02 0.10 0.10 0.14 0.18 0.22. No shaped entry nears a mean of
#: 0.8 while sparse's best seed passes it, so more budget buys sparse more than the potentials.
#: SBX-SAC on the reach distribution (``planshape probe planshape/ReachRandomized-v1 dense
#: --algo SBX-SAC --budget 300000 --chunks 10``, seed 0): dense solves 0.00 of the held-out
#: instances up to 90,000 (the fixed task's budget is 100,000), then 0.06, 0.20, 0.34, 0.54,
#: 0.62, 0.70 and 0.66 at 120,000 ... 300,000 (training-episode success 0.84 at the end). One
#: seed, short of the rule (0.8) but the first budget at which dense solves most unseen
#: instances, so the reach distribution trains SBX-SAC for 300,000 steps. The profile's 5 seeds
#: of dense there end at 0.66, 0.52, 0.14, 0.22 and 0.74 (IQM 0.47): still short of the rule.
#: SBX-SAC on the maze-reach distribution (``planshape probe planshape/MazeReachRandomized-v1
#: ENTRY --algo SBX-SAC --budget 150000 --chunks 15``, seeds 0-1): plan-distance/grid solves
#: 0.50, 0.82, 0.98, 1.00, 1.00 and 0.32, 0.58, 0.72, 0.88, 0.94 of the held-out instances at
#: 10,000 ... 50,000 steps and 0.96-1.00 from there to 150,000 (final distance 0.02 m); dense
#: 0.00 at every point on both seeds (0.19-0.22 m: the wall). The fixed task's budget, 50,000,
#: is where the potential has solved the distribution, so the maze distribution keeps it.
#: On the push distribution (the cylinder up to 3 cells beside and 5 above or below its goal, so
#: the hand must often go round it) nothing learns within a budget this machine affords, so the
#: profile keeps the fixed task's budgets and its push cells are not trained: ``planshape probe
#: planshape/PushRandomized-v1 ENTRY --algo SBX-SAC --budget 300000 --chunks 10`` (seed 0,
#: held-out success per point): dense, plan-distance/grid and plan-based/grid solve 0.00 of the
#: held-out instances at every point (final distance 0.24-0.25 m, about where it starts; training
#: episodes 0.00-0.02); dense to 1,000,000 steps (``--budget 1000000``) at most 0.04 (0.04 at
#: 600,000, 0.00 at the end; final distance 0.218 m; training episodes 0.03); PPO's dense
#: (``--budget 819200``, the fixed task's) 0.00 at every point (0.25 m).
_INSTANCE_PPO_BUDGETS = {**_PLANAR_BUDGETS, "planshape/MazeReachRandomized-v1": 245_760}
_INSTANCE_SAC_BUDGETS = {**_SAC_BUDGETS, "planshape/ReachRandomized-v1": 300_000}

INSTANCES = Profile(
    name="instances",
    description=(
        "the task-instance distributions of reach, push and maze-reach × {sparse, dense, "
        "plan-based, time-varying and plan-distance on the grid models, goal-distance} × PPO "
        "and SAC (SBX) × 5 seeds, trained on 100 instances and evaluated on 50 held-out ones"
    ),
    blocks=tuple(
        Block(
            RANDOMIZED,
            (algo,),
            tuple(range(5)),
            budgets,
            (*INSTANCE_POTENTIALS, *CONTROL_POTENTIALS),
            models=("grid",),
        )
        for algo, budgets in (("PPO", _INSTANCE_PPO_BUDGETS), (SBX_SAC, _INSTANCE_SAC_BUDGETS))
    ),
    eval_every=10_000,
    eval_episodes=10,
    caveats=(
        "every evaluation point runs the 50 held-out instances: success is the fraction of "
        "unseen instances solved",
        "PPO on the maze distribution trains 245,760 steps, from learning curves (plan-based/"
        "grid solves 0.22-0.42 of the held-out instances there, dense 0.00); the other budgets "
        "are the fixed tasks': on the reach distribution PPO's dense reward solved at most 0.06 "
        "of the held-out instances up to 409,600 steps (3 seeds), so a PPO reach cell compares "
        "entries that all fail; SBX-SAC on the reach distribution trains 300,000 steps, chosen "
        "from one seed's curve of its dense reward (0.66 of the held-out instances there, 0.00 "
        "up to 90,000); over 5 seeds dense solves 0.14-0.74 there, short of the rule's 0.8; "
        "SBX-SAC on the maze distribution keeps the fixed task's "
        f"{_SAC_STEPS['MazeReach']:,}, where "
        "plan-distance/grid's curves solve 0.94-1.00 of the held-out instances (seeds 0-1) and "
        "dense's 0.00; on the push distribution no entry solves more than 0.04 of the held-out "
        "instances within 1,000,000 SBX-SAC steps (dense, seed 0; plan-distance/grid and "
        "plan-based/grid 0.00 to 300,000) or PPO's 819,200 (dense 0.00), so its cells are not "
        "trained",
        *_SHARED_CAVEATS,
    ),
)

PROFILES: dict[str, Profile] = {
    p.name: p
    for p in (
        SMOKE,
        DEFAULT,
        PLANAR_PROFILE,
        PAPER,
        FULL,
        METAWORLD_PROFILE,
        METAWORLD_S10_PROFILE,
        METAWORLD_PROGRESS_PROFILE,
        METAWORLD_HOLDOUT_PROFILE,
        INSTANCES,
        DEFAULT_V0,
        METAWORLD_V0_PROFILE,
    )
}


def get_profile(name: str) -> Profile:
    """The registered profile ``name``; an unknown name is bad input that lists the known ones."""
    if name not in PROFILES:
        raise UnknownIdError("profile", name, PROFILES)
    return PROFILES[name]


def profile_of_folder(out: str | Path) -> Profile | None:
    """The profile whose own results folder ``out`` is (:attr:`Profile.folder`, relative to
    the working directory), else ``None``.

    Example:
        >>> profile_of_folder("leaderboard/metaworld").name, profile_of_folder("/tmp/x")
        ('metaworld', None)
    """
    return next(
        (p for p in PROFILES.values() if Path(p.folder).resolve() == Path(out).resolve()), None
    )
