"""Hyperparameters per task family and algorithm: typed, documented tables (rl-zoo style).

Every benchmark run of a (task, algorithm) pair uses exactly these settings, whatever the
reward entry, so entries are compared under equal conditions. γ is the learner's discount and
is also the shaping γ of every shaped entry (correctness rule 1).

* PPO (planar tasks): 8 environments × 128 steps per update, 10 epochs of minibatch 256,
  a [64, 64] MLP, learning rate 3e-4, GAE λ 0.95. Modest, standard settings; the same for
  every entry.
* SAC (planar tasks), "tuned": a [64, 64] MLP (the defaults' [256, 256] is slow on a CPU and
  no better here), learning rate 1e-3, batch 256, 1000 random steps first, one gradient step
  per environment step (four every four steps; the v0 tasks keep one every step, with which
  their stored runs trained), automatic entropy tuning. The source paper ran SAC with untuned
  library defaults; ``SAC-default`` reproduces that (stable-baselines3's defaults but γ and SAC's
  shaping scale).
* MetaWorld and gymnasium-robotics: larger networks and longer episodes (see the table).
* ``shaping_scale`` (every table, every entry's potential): φ is multiplied by
  :data:`SHAPING_SCALE` = 1/(1 − γ) = 100. Potentials are written at unit scale (φ changes by
  about 1 from the plan's start to its end); with γ = 0.99 the sparse reward of a solved
  continuing task is worth up to 1/(1 − γ), so this makes the shaping as loud as the reward it
  guides to. At unit scale a critic learns −φ within a few updates and the guidance is gone
  before the goal is ever seen (PPO on reach at scale 1: 0/5 seeds for every potential). The
  source paper tuned one multiplier per potential by hand; one scale per learner for every
  entry, submissions included, keeps the comparison fair. Sparse and dense runs ignore it
  (and record :data:`UNSHAPED_SCALE`).
* SAC on the planar tasks: :data:`SAC_SHAPING_SCALE` = 10, from SBX-SAC learning curves
  (``planshape probe TASK ENTRY --algo SBX-SAC --shaping-scale S``, 5 seeds, deterministic
  evaluation every 10,000 steps), against the stored runs at 100: on reach (100,000 steps)
  plan-distance/grid solves 4/5 seeds at 10 (final 0.007-0.032 m; seed 1 0.250 m) and 1/5 at 100,
  dense 4/5 (at 30 also 4/5, seeds 0-3, first solved at 20,000-90,000 steps; at 1 seed 0 solves it
  at 90,000: 10 sits inside a wide window that 100 is outside of); h-star-geodesic/grid 1/5 against
  0/5; plan-based/grid 0/5 at both (a step potential, flat inside each cell). On push (150,000)
  plan-distance/grid 3/5 against 1/5 (dense 4/5); at 30 push is worse, 1/4 (seeds 0-3: only seed 1
  solves it, from 90,000; seeds 0, 2 and 4 solve it at 10), so 10, not 30. On maze-reach
  plan-distance/grid holds the goal on 4/5 seeds from 40,000 steps to 100,000 at 10, where at 100
  three of its four seeds lost it by 40,000. Nowhere was 10 worse. (SAC tunes its entropy against
  Q-values of the shaped return, so the reward's scale matters to it; why 100 hurts here is not
  measured.) PPO keeps 100 (at 1 it solved nothing; on push at 10, ``planshape probe push ENTRY
  --shaping-scale 10 --budget 819200``, 5 seeds, it solves what it solves at 100:
  plan-distance/grid 0/5, its plan progress stuck at step 2 of 11 on every seed, short of the
  pushing position, plan-path/grid 0/5, time-varying/grid 2/5; at 1000, time-varying/grid 2/5
  again and plan-distance/grid 0/2, its critic explaining none of the shaped return and its plan
  progress at 8.8-9.0 of 11 without a success; at 10000 plan-distance/grid 0/2; README, the
  planar profile's PPO push cell). The v0 tasks keep 100, with which
  their stored runs trained. MetaWorld and gymnasium-robotics keep 100 too: on MetaWorld
  reach-v4 (``planshape probe planshape/MetaWorld-reach-v4 plan-distance/stages --algo SBX-SAC
  --budget 200000 --chunks 10 --shaping-scale S``, seed 0; success of 10 episodes every 20,000
  steps) plan-distance/stages reaches 0.8 at 120,000 steps at 10 (1.0 at 180,000, 0.8 at
  200,000; training-episode success 0.75) and at 140,000 at 100 (0.5 from 40,000, 1.0 at 160,000
  and 200,000; training-episode success 0.95), against dense's 0.9 at 140,000: one seed, 100 no
  worse than 10, so the rule's scale stays where SAC's planar one is not shown to be better.
  On window-open (240,000 steps), two stored runs at 100 that learned the task and lost it were
  probed again at 10 (``planshape probe planshape/MetaWorld-window-open-v3 ENTRY --algo SBX-SAC
  --seed S --budget 240000 --chunks 12 --shaping-scale 10``; success at any step of 10
  episodes every 20,000 steps): plan-distance-sum/stages seed 2 reads 0.8 at 20,000, 1.0 from
  60,000 but for 0.9 at 100,000 and 160,000-180,000, and ends at 1.0 (at 100: 0.2 at 200,000,
  0.7 at the end); plan-distance/stages seed 4 reads 0.0 to 100,000, 1.0 from 140,000 but for
  0.9 at 180,000 and 220,000, and ends at 1.0 (at 100: 1.0 at 160,000, 0.0 at the end).
  plan-distance-sum/stages seeds 0 and 1, which end at 1.0 at 100, end at 1.0 at 10 too (seed
  0 drops to 0.0 at 120,000 on the way). Seeds chosen for their collapse, not a test of the
  scale. On button-press (120,000 steps, the same command with ``--chunks 6``),
  plan-distance-sum/stages at 10 ends at 0.4 (seed 0: 0.0 to 100,000, the button 0.094 m from
  its goal, untouched, throughout) and 0.7 (seed 1: 0.6 from 100,000), against 0.6 and 0.6 at
  100, where dense reads 1.0 at 60,000-100,000 on every seed (0.96 at the end): no better at
  10. The metaworld profile keeps 100; the metaworld-s10 profile (planshape.harness.profiles)
  runs its cells at 10 with 5 seeds (leaderboard/METAWORLD.md, its metaworld-s10 section).
* ``observe_progress`` (no table sets it; the metaworld-progress profile does): the learner
  sees max_idx / n after the observation (:mod:`planshape.shaping.observed_progress`). An
  exploratory probe suggested it: button-press plan-distance-sum/stages at 10, seed 2, whose
  stored run reads 0.0 at every point (the button untouched), read 0.0, 0.0, 0.0, 0.2, 0.8, 1.0
  at 20,000 ... 120,000 steps with progress observed (a script that wrapped the probe's
  environments; the wrapper it became gives the same training numbers: training-episode
  distance 0.094436333664627 after 6,000 steps either way). One seed; the 5-seed runs are the
  metaworld-progress profile's.
* ``rescale_observations`` (planar tables): the learner sees the observation mapped from its
  Box bounds onto [-1, 1] (:func:`planshape.harness.runner.rescaled`; the shaping still reads
  metres). The raw coordinates span a few tenths of a metre, on which a [64, 64] tanh MLP is
  nearly affine: on maze-reach, PPO's policy mean was an affine function of the position
  (up-right everywhere, so the end effector went over the wall and stopped at the
  workspace's top edge above the goal) and its critic output was 72.0–72.1 at every probed
  position, so it could neither follow the geodesic nor absorb the potential. Rescaled,
  h-star-geodesic and plan-distance solved maze-reach on 2/2 seeds each at the default
  budget, sparse and dense on 0/1. rl-zoo normalizes MuJoCo observations for the same
  reason. ``SAC-default`` keeps raw observations (the paper's untuned setting); MetaWorld and
  gymnasium-robotics observations have no finite bounds to rescale from.

Each table is a frozen dataclass (:class:`PPOSettings`, :class:`SACSettings`) whose fields
carry their documentation (``dataclasses.fields(PPOSettings)[i].metadata["doc"]``); a run
records :meth:`Settings.as_dict`, the fields that are not ``None``, which is also what its id
hashes (the tables were plain dicts before; the serialisation is the same, so no stored run id
changed, and a test checks every committed run).

Example:
    >>> settings = hyperparameters("planshape/Reach-v0", "PPO")
    >>> settings["gamma"], settings["n_envs"]
    (0.99, 8)
"""

from __future__ import annotations

import copy
import dataclasses
from dataclasses import dataclass, field
from typing import Any

from planshape.errors import UnknownIdError

GAMMA = 0.99
#: the multiplier of every potential in training: 1/(1 − γ), see the module docstring; rounded,
#: because in floating point 1/(1 − 0.99) is 99.99999999999991 and the runs record 100.0
SHAPING_SCALE = round(1.0 / (1.0 - GAMMA), 6)
#: φ's multiplier for SAC on the planar tasks, from learning curves (the module docstring)
SAC_SHAPING_SCALE = 10.0
#: what a sparse or dense run records as its ``shaping_scale`` (it has no potential to scale):
#: the rule's value, which every run recorded before tables had scales of their own
UNSHAPED_SCALE = SHAPING_SCALE


def setting(doc: str, default: Any = None) -> Any:
    """A documented field of a settings table; ``None``: the library's default, not recorded.

    Example:
        >>> dataclasses.fields(PPOSettings)[0].metadata["doc"]
        'parallel environments of one run (a DummyVecEnv, each with its own shaping wrapper)'
    """
    return field(default=default, metadata={"doc": doc})


@dataclass(frozen=True)
class Settings:
    """A hyperparameter table: typed, documented fields, serialised into each run's identity.

    :meth:`as_dict` is what a run records (and its id hashes): every field that is not
    ``None``, under the field's name, so a table written as a dataclass gives the very dict the
    stored runs were made with. Subclasses add the algorithm's fields; :meth:`replace` derives
    a variant.

    Example:
        >>> PPO_PLANAR.as_dict()["n_steps"], PPO_PLANAR.replace(n_steps=512).as_dict()["n_steps"]
        (128, 512)
        >>> "learning_rate" in SAC_DEFAULT.as_dict()  # None: the library's default, not recorded
        False
    """

    n_envs: int = setting(
        "parallel environments of one run (a DummyVecEnv, each with its own shaping wrapper)", 1
    )
    gamma: float = setting("the learner's discount, also the shaping γ (correctness rule 1)", GAMMA)
    shaping_scale: float = setting(
        "φ's multiplier in training: 1/(1 − γ), or the learner's own (see the module "
        "docstring); sparse and dense runs ignore it",
        SHAPING_SCALE,
    )
    rescale_observations: bool | None = setting(
        "the learner sees the observation mapped from its Box bounds onto [-1, 1]"
    )
    observe_progress: bool | None = setting(
        "the learner sees plan progress max_idx / n after the observation (shaped runs; "
        "planshape.shaping.observed_progress)"
    )
    learning_rate: float | None = setting("the optimiser's step size")
    batch_size: int | None = setting("minibatch size of one gradient step")
    policy_kwargs: dict[str, Any] | None = setting(  # noqa: RUF009 (a dataclasses.field)
        "the networks: net_arch, the hidden layer sizes of the actor and the critic"
    )

    def as_dict(self) -> dict[str, Any]:
        """The settings a run records: every field that is not ``None``, deep-copied."""
        return {
            f.name: copy.deepcopy(getattr(self, f.name))
            for f in dataclasses.fields(self)
            if getattr(self, f.name) is not None
        }

    def replace(self, **changes: Any) -> Any:
        """A copy with ``changes`` (field names) applied."""
        return dataclasses.replace(self, **changes)


@dataclass(frozen=True)
class PPOSettings(Settings):
    """PPO's table (stable-baselines3's ``PPO`` and SBX's)."""

    n_steps: int | None = setting(
        "steps per environment per rollout: an update every n_envs × n_steps steps"
    )
    n_epochs: int | None = setting("passes over each rollout")
    gae_lambda: float | None = setting("GAE's λ")
    ent_coef: float | None = setting("the entropy bonus's coefficient")


@dataclass(frozen=True)
class SACSettings(Settings):
    """SAC's table (stable-baselines3's ``SAC``, SBX's, and the SBX learners that share it)."""

    buffer_size: int | None = setting("replay buffer capacity (transitions)")
    learning_starts: int | None = setting("uniformly random steps before the first update")
    train_freq: int | None = setting("environment steps between gradient phases")
    gradient_steps: int | None = setting("gradient steps per phase")


PPO_PLANAR = PPOSettings(
    n_envs=8,
    n_steps=128,
    batch_size=256,
    n_epochs=10,
    learning_rate=3e-4,
    gae_lambda=0.95,
    ent_coef=0.0,
    rescale_observations=True,
    policy_kwargs={"net_arch": [64, 64]},
)
SAC_PLANAR = SACSettings(
    shaping_scale=SAC_SHAPING_SCALE,
    learning_rate=1e-3,
    batch_size=256,
    buffer_size=100_000,
    learning_starts=1000,
    # four gradient steps every four environment steps: one gradient step per step, as with
    # 1/1, in one compiled call of SBX's (1.8 times the steps/s of 1/1 on Push-v1, measured
    # side by side)
    train_freq=4,
    gradient_steps=4,
    rescale_observations=True,
    policy_kwargs={"net_arch": [64, 64]},
)
#: the v0 tasks keep the SAC settings their stored runs were trained with (train_freq 1, the
#: rule's shaping scale)
SAC_PLANAR_V0 = SAC_PLANAR.replace(train_freq=1, gradient_steps=1, shaping_scale=SHAPING_SCALE)
#: the source paper's untuned SAC: the library's defaults, but γ and the shaping scale, which is
#: the benchmark's and not the library's, so that it differs from tuned SAC only in the
#: learner's settings
SAC_DEFAULT = SACSettings(shaping_scale=SAC_SHAPING_SCALE)
PPO_ROBOTICS = PPO_PLANAR.replace(
    n_steps=512, batch_size=512, rescale_observations=False, policy_kwargs={"net_arch": [256, 256]}
)
SAC_ROBOTICS = SAC_PLANAR.replace(
    # the rule's scale: on MetaWorld reach-v4 SAC's planar 10 was no better (module docstring)
    shaping_scale=SHAPING_SCALE,
    learning_rate=3e-4,
    learning_starts=5000,
    rescale_observations=False,
    policy_kwargs={"net_arch": [256, 256]},
)

#: the planar families: the fixed tasks and their task-instance distributions
PLANAR_FAMILIES = (
    "Reach",
    "Push",
    "MazeReach",
    *(f"{f}Randomized" for f in ("Reach", "Push", "MazeReach")),
)

#: (task family, algorithm) -> settings; the family is the one each task is registered with
#: ("Reach", "PushRandomized", "MetaWorld", "PointMaze", "FetchReach", ...).
TABLE: dict[tuple[str, str], Settings] = {
    **{(f, "PPO"): PPO_PLANAR for f in PLANAR_FAMILIES},
    **{(f, "SAC"): SAC_PLANAR for f in PLANAR_FAMILIES},
    **{(f, "SAC-default"): SAC_DEFAULT for f in PLANAR_FAMILIES},
    **{(f, "PPO"): PPO_ROBOTICS for f in ("MetaWorld", "PointMaze", "FetchReach", "FetchPush")},
    **{(f, "SAC"): SAC_ROBOTICS for f in ("MetaWorld", "PointMaze", "FetchReach", "FetchPush")},
}


#: (task id, algorithm) -> settings that take precedence over the family's
TASK_TABLE: dict[tuple[str, str], Settings] = {
    (f"planshape/{name}-v0", "SAC"): SAC_PLANAR_V0 for name in ("Reach", "Push", "MazeReach")
}


def family(task_id: str) -> str:
    """The family a task was registered with: ``"planshape/MetaWorld-reach-v3"`` ->
    ``"MetaWorld"`` (:attr:`planshape.shaping.registration.TaskSpec.family`)."""
    from planshape.shaping.registration import task_spec

    return task_spec(task_id).family


def hyperparameters(
    task_id: str,
    algo: str,
    entry: str | None = None,
    *,
    shaping_scale: float | None = None,
    observe_progress: bool = False,
) -> dict[str, Any]:
    """A fresh copy of the settings of ``algo`` (a learner id, e.g. ``SBX-SAC``, whose table is
    ``SAC``'s) on ``task_id``, for a run of ``entry`` (``None``: a shaped entry).

    A ``sparse`` or ``dense`` run ignores ``shaping_scale``, so it records
    :data:`UNSHAPED_SCALE` whatever its table's scale is: a sparse run is the same run, with
    the same id, whichever scale the table gives the shaped entries beside it.
    ``shaping_scale`` replaces the table's scale for a shaped entry (a profile's own scale,
    :attr:`planshape.harness.profiles.Profile.shaping_scale`); ``None`` keeps the table's.
    ``observe_progress`` shows a shaped entry's learner its plan progress
    (:mod:`planshape.shaping.observed_progress`) and is recorded, so it is part of the run's id;
    sparse and dense have no plan and ignore it, and without it nothing is recorded, so no
    stored run's id changes.

    Example:
        >>> hyperparameters("planshape/Reach-v1", "SBX-SAC", "dense")["shaping_scale"]
        100.0
        >>> task = "planshape/MetaWorld-window-open-v3"
        >>> entry = "plan-distance/stages"
        >>> hyperparameters(task, "SBX-SAC", entry)["shaping_scale"]
        100.0
        >>> hyperparameters(task, "SBX-SAC", entry, shaping_scale=10)["shaping_scale"]
        10.0
        >>> hyperparameters(task, "SBX-SAC", "sparse", shaping_scale=10)["shaping_scale"]
        100.0
        >>> hyperparameters(task, "SBX-SAC", entry, observe_progress=True)["observe_progress"]
        True
        >>> "observe_progress" in hyperparameters(task, "SBX-SAC", "dense", observe_progress=True)
        False
    """
    from planshape.training.learners import learner

    table = learner(algo).table
    if (task_id, table) in TASK_TABLE:
        settings = TASK_TABLE[(task_id, table)].as_dict()
    else:
        key = (family(task_id), table)
        if key not in TABLE:
            known = sorted({f for f, a in TABLE if a == algo})
            raise UnknownIdError(
                "task family", key[0], known, hint=f"no {algo} hyperparameters for {task_id}"
            )
        settings = TABLE[key].as_dict()
    if entry in ("sparse", "dense"):
        settings["shaping_scale"] = UNSHAPED_SCALE
    else:
        if shaping_scale is not None:
            settings["shaping_scale"] = float(shaping_scale)
        if observe_progress:
            settings["observe_progress"] = True
    return settings
