"""One benchmark run: train a stable-baselines3 learner on one reward entry of one task for a
fixed budget, evaluating it on the task's own metrics along the way.

Evaluation never looks at the training reward: every evaluation point runs episodes of the
deterministic policy on the task with its own sparse reward and records the success rate (the
task's success flag at the episode's end), the final distance to the goal (the source paper's
metric) and the return under the sparse reward (correctness rule 5). Which episodes
(:func:`evaluation_episodes`, evaluation protocol 2):

* a fixed task (``TaskSpec.fixed``: one start, deterministic) runs one episode: more would be
  copies of it, so its success rate is 0 or 1 per run;
* a task-instance distribution runs every instance of its held-out evaluation set, so its
  success rate is the fraction of unseen instances solved;
* any other task (MetaWorld, gymnasium-robotics: start and goal drawn from the seed) runs the
  profile's ``eval_episodes`` seeded episodes.

Each point is recorded with the number of steps the evaluated policy was trained on: it is
taken at the start of a rollout, after the update on the steps before it (protocol 1, the
runs stored before it, evaluated PPO inside a rollout, before that rollout's update, and ran
``eval_episodes`` copies of a fixed task's one episode).

A run is a pure function of its :class:`RunSpec` (rule 6): the learner, the environments and the
evaluation episodes are seeded from it, torch uses one thread, and nothing else is random.
Floating-point results are identical on the same machine and library versions. Across CPU
types an SBX run's are not: XLA compiles for the CPU it runs on, and the last-digit differences
grow into a different run, so each row records the CPU (:mod:`planshape.harness.machine`).

Example:
    >>> from planshape.harness.profiles import RESULTS_ROOT, RunKey
    >>> key = RunKey("planshape/Reach-v0", "sparse", "PPO", 0, 2048)
    >>> spec = RunSpec.create(key, "smoke", eval_every=1024, eval_episodes=2)
    >>> len(spec.run_id)
    16
"""

from __future__ import annotations

import copy
import hashlib
import json
import math
import subprocess
import time
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field
from functools import cache, partial
from importlib import metadata
from pathlib import Path
from typing import Any

import gymnasium
import numpy as np

from planshape.errors import BadInputError
from planshape.harness.machine import cpu_description
from planshape.harness.profiles import RESULTS_ROOT, RunKey
from planshape.results.rows import StoredRow, validate_row
from planshape.shaping.registration import instance_set, task_spec
from planshape.training.hyperparams import hyperparameters
from planshape.training.learners import learner, release_compiled
from planshape.training.threads import fix_compute_threads

PACKAGES = (
    "planshape",
    "stable-baselines3",
    "torch",
    "sbx-rl",
    "jax",
    "jaxlib",
    "gymnasium",
    "mujoco",
    "numpy",
)
EVAL_SEED_OFFSET = 10_000
#: the evaluation protocol of new runs (see the module docstring); stored rows without the
#: field were made with protocol 1
EVAL_PROTOCOL = 2


def evaluation_episodes(task: str, eval_episodes: int) -> list[dict[str, Any]]:
    """The ``reset`` arguments of the episodes one evaluation point runs on ``task`` (protocol
    2): one episode of a fixed task, every held-out instance of a distribution, else
    ``eval_episodes`` seeded episodes.

    Example:
        >>> import planshape
        >>> evaluation_episodes("planshape/Reach-v1", 10)
        [{'seed': 10000}]
        >>> len(evaluation_episodes("planshape/ReachRandomized-v1", 10))
        50
    """
    spec = task_spec(task)
    if spec.fixed:
        return [{"seed": EVAL_SEED_OFFSET}]
    instances = instance_set(spec)
    if instances is not None:
        return [
            {"seed": EVAL_SEED_OFFSET, "options": {"instance": k}}
            for k in range(len(instances.eval))
        ]
    return [{"seed": EVAL_SEED_OFFSET + e} for e in range(eval_episodes)]


def evaluation_text(task: str, episodes: int) -> str:
    """What one evaluation point of ``task`` measures, for the leaderboard."""
    spec = task_spec(task)
    if spec.fixed:
        return "1 episode (a fixed, deterministic task: success is 0 or 1 per run)"
    if spec.instances:
        return f"the {episodes} held-out instances (success: the fraction solved)"
    return f"{episodes} seeded episodes"


@dataclass(frozen=True)
class RunSpec:
    """Everything that determines a run's numbers."""

    key: RunKey
    profile: str
    eval_every: int
    eval_episodes: int
    hyperparameters: dict[str, Any] = field(hash=False)
    invariance: str = "not-checked"
    eval_protocol: int = EVAL_PROTOCOL

    @classmethod
    def create(
        cls,
        key: RunKey,
        profile: str,
        eval_every: int,
        eval_episodes: int,
        invariance: str = "not-checked",
        eval_protocol: int = EVAL_PROTOCOL,
        shaping_scale: float | None = None,
        observe_progress: bool = False,
    ) -> RunSpec:
        """The spec of ``key`` with its task's and algorithm's hyperparameters (``eval_protocol``
        1 only to find runs stored with it: this code evaluates with protocol 2; a
        ``shaping_scale`` replaces the table's for a shaped entry, and ``observe_progress``
        shows its learner the plan progress, as a profile's own settings do)."""
        settings = hyperparameters(
            key.task,
            key.algo,
            key.entry,
            shaping_scale=shaping_scale,
            observe_progress=observe_progress,
        )
        return cls(key, profile, eval_every, eval_episodes, settings, invariance, eval_protocol)

    @property
    def episodes(self) -> list[dict[str, Any]]:
        """The ``reset`` arguments of one evaluation point's episodes."""
        return evaluation_episodes(self.key.task, self.eval_episodes)

    @property
    def run_id(self) -> str:
        """A content hash of what determines the numbers (not of the profile's name or the code
        version, which are recorded as provenance), so stored runs are found again. From
        protocol 2 on it hashes the episodes evaluated, not the profile's ``eval_episodes``
        (which a fixed task or a distribution does not use), and the protocol."""
        identity: dict[str, Any] = {
            **asdict(self.key),
            "eval_every": self.eval_every,
            "eval_episodes": self.eval_episodes,
            "hyperparameters": self.hyperparameters,
        }
        if self.eval_protocol != 1:
            identity["eval_episodes"] = self.episodes
            identity["eval_protocol"] = self.eval_protocol
        text = json.dumps(identity, sort_keys=True)
        return hashlib.sha256(text.encode()).hexdigest()[:16]


@cache
def code_version() -> str:
    """``git describe`` of the checkout the benchmark runs from (the working directory, or the
    source tree of an editable install), else the installed package's version.

    ``-dirty`` marks uncommitted changes to tracked files *outside* ``leaderboard/``: the
    benchmark writes its results there, and its own output does not make the code dirty.
    Read once per process, as its first run starts (:func:`train`): the code a process runs
    is what it imported then, whatever the checkout becomes while a long run trains.
    """
    for folder in (Path.cwd(), Path(__file__).resolve().parents[2]):
        try:
            described = _git(folder, "describe", "--always", "--tags")
            changed = _git(
                folder,
                "status",
                "--porcelain",
                "--untracked-files=no",
                "--",
                ".",
                f":(exclude){RESULTS_ROOT}",
            )
        except (OSError, subprocess.SubprocessError):
            continue
        return described + ("-dirty" if changed else "")
    return f"planshape {package_versions().get('planshape', '?')}"


def _git(folder: Path, *args: str) -> str:
    out = subprocess.run(
        ["git", *args], cwd=folder, capture_output=True, text=True, timeout=10, check=True
    )
    return out.stdout.strip()


@cache
def package_versions() -> dict[str, str]:
    """The installed version of each package in :data:`PACKAGES` that a run records."""
    versions = {}
    for name in PACKAGES:
        try:
            versions[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            versions[name] = "missing"
    return versions


def make_learner(key: RunKey, hyperparameters: dict[str, Any]) -> Any:
    """The learner of ``key`` (stable-baselines3 or SBX, :mod:`planshape.training.learners`) on its
    training VecEnv.

    ``n_envs``, ``shaping_scale``, ``rescale_observations`` and ``observe_progress`` of
    ``hyperparameters`` configure the environments, the rest the algorithm. The settings are
    deep-copied first: stable-baselines3 writes into ``policy_kwargs``, and a run's settings are
    part of its identity. The process's compute threads are fixed first
    (:func:`planshape.training.threads.fix_compute_threads`: PyTorch on one thread, JAX on two
    CPUs), as every stored run had them, so that the numbers do not depend on the machine.
    """
    from planshape.training.learners import make

    fix_compute_threads(learner(key.algo).backend)
    settings = copy.deepcopy(hyperparameters)
    n_envs = settings.pop("n_envs")
    shaping_scale = settings.pop("shaping_scale", 1.0)
    rescale = settings.pop("rescale_observations", False)
    progress = settings.pop("observe_progress", False)
    venv = make_training_env(
        key,
        n_envs,
        settings["gamma"],
        key.seed,
        shaping_scale,
        rescale_observations=rescale,
        observe_progress=progress,
    )
    return make(key.algo, venv, seed=key.seed, device="cpu", verbose=0, **settings)


def make_training_env(
    key: RunKey,
    n_envs: int,
    gamma: float,
    seed: int,
    shaping_scale: float = 1.0,
    rescale_observations: bool = False,
    observe_progress: bool = False,
):
    """The VecEnv a learner trains on: each environment wrapped in its own shaping, inside the
    VecEnv, shaped with the learner's γ and φ multiplied by ``shaping_scale``; the learner sees
    :func:`learner_view` of each environment (its plan progress appended with
    ``observe_progress``, rescaled with ``rescale_observations``). The VecEnv is a
    :class:`~planshape.training.algorithm.FreshInfoVecEnv` (no deep copy of the infos)."""
    from stable_baselines3.common.env_util import make_vec_env

    from planshape.training.algorithm import FreshInfoVecEnv

    env_kwargs: dict[str, Any] = {"reward": key.reward, "render_mode": None}
    if key.reward == "shaped":
        env_kwargs.update(
            potential=key.potential, model=key.model, gamma=gamma, potential_scale=shaping_scale
        )
    settings = {"rescale_observations": rescale_observations, "observe_progress": observe_progress}
    return make_vec_env(
        key.task,
        n_envs=n_envs,
        seed=seed,
        env_kwargs=env_kwargs,
        wrapper_class=partial(learner_view, key=key, hyperparameters=settings),
        vec_env_cls=FreshInfoVecEnv,
    )


def make_evaluation_env(
    key: RunKey, hyperparameters: dict[str, Any], render_mode: str | None = None
) -> gymnasium.Env:
    """The task with its own sparse reward, seen by the learner as in training; a
    distribution's held-out instances."""
    held_out = {"instances": "eval"} if task_spec(key.task).instances else {}
    if render_mode is not None:
        held_out["render_mode"] = render_mode
    return learner_view(gymnasium.make(key.task, **held_out), key, hyperparameters)


def learner_view(
    env: gymnasium.Env, key: RunKey, hyperparameters: Mapping[str, Any]
) -> gymnasium.Env:
    """``env`` as the learner of ``key`` sees it, in training and in evaluation alike: with
    ``observe_progress``, its plan progress appended
    (:func:`planshape.shaping.registration.observe_progress`); with ``rescale_observations``,
    the observation mapped by :func:`rescaled`. Neither is applied without its setting.

    Example:
        >>> import planshape
        >>> key = RunKey("planshape/Reach-v1", "plan-based/single", "PPO", 0, 4096)
        >>> env = learner_view(gymnasium.make(key.task), key, {"observe_progress": True})
        >>> env.observation_space.shape
        (3,)
    """
    if hyperparameters.get("observe_progress"):
        from planshape.shaping.registration import observe_progress

        env = observe_progress(env, key.task, key.model)
    return rescaled(env) if hyperparameters.get("rescale_observations") else env


def rescaled(env: gymnasium.Env) -> gymnasium.Env:
    """``env`` with its observations mapped affinely from their Box bounds onto [-1, 1].

    Outermost wrapper: the shaping inside still classifies the raw observation, and a fixed
    bijection of the observation changes neither the MDP nor its optimal policies. Planar
    coordinates in metres span a few tenths, on which a small tanh MLP is nearly affine
    (see :mod:`planshape.training.hyperparams`).

    Example:
        >>> import planshape
        >>> env = rescaled(gymnasium.make("planshape/Reach-v0"))
        >>> float(env.observation_space.low.min()), float(env.observation_space.high.max())
        (-1.0, 1.0)
    """
    space = env.observation_space
    if not isinstance(space, gymnasium.spaces.Box) or not (
        np.isfinite(space.low).all() and np.isfinite(space.high).all()
    ):
        raise BadInputError(
            f"rescale_observations: {env.spec.id if env.spec else env} has observation space "
            f"{space}, not a Box with finite bounds; set rescale_observations=False in its "
            "hyperparameter table (planshape.training.hyperparams)"
        )
    bound = np.ones(space.shape, space.dtype)
    return gymnasium.wrappers.RescaleObservation(env, -bound, bound)


def evaluate(
    model: Any, env: gymnasium.Env, episodes: int | list[dict[str, Any]], seed: int = 0
) -> dict[str, float]:
    """The deterministic policy on the task's own sparse reward: success rate at the end of
    the episode, success rate at any step of it (MetaWorld's own protocol, whose episodes never
    end on success), mean final distance, mean undiscounted sparse return. ``episodes`` is a
    list of ``reset`` arguments (:func:`evaluation_episodes`), or a count of episodes seeded
    from ``seed`` on. Only reads the policy: the numbers of training do not depend on it."""
    if isinstance(episodes, int):
        episodes = [{"seed": seed + e} for e in range(episodes)]
    successes, reached, distances, returns = [], [], [], []
    for reset in episodes:
        obs, info = env.reset(**reset)
        total, done, ever = 0.0, False, False
        while not done:
            action, _ = model.predict(obs, deterministic=True)
            obs, reward, terminated, truncated, info = env.step(action)
            total += float(reward)
            ever = ever or bool(info.get("success", False))
            done = terminated or truncated
        successes.append(float(bool(info.get("success", False))))
        reached.append(float(ever))
        distances.append(float(info.get("distance", math.nan)))
        returns.append(total)
    return {
        "success_rate": float(np.mean(successes)),
        "success_any_rate": float(np.mean(reached)),
        "final_distance": float(np.mean(distances)),
        "sparse_return": float(np.mean(returns)),
    }


def execute(
    spec: RunSpec, tensorboard: str | None = None, *, progress: bool = False
) -> list[dict[str, Any]]:
    """Train and evaluate one run; return its tidy rows (one per evaluation point)."""
    rows = train(spec, tensorboard, progress=progress)[1]
    release_compiled()  # the learner is gone: free its compiled functions for the next run
    return rows


def train(
    spec: RunSpec, tensorboard: str | None = None, *, progress: bool = False
) -> tuple[Any, list[StoredRow]]:
    """Train and evaluate one run: the trained learner and the run's rows (:func:`execute`,
    which stores the rows; :mod:`planshape.results.videos` renders the learner's policy). With
    ``tensorboard`` (a folder), the run also logs there
    (:mod:`planshape.training.tensorboard_logs`); with ``progress``, a bar over its training
    steps is drawn on stderr when that is a terminal (:mod:`planshape.training.progress`).
    Neither changes any of its numbers."""
    from stable_baselines3.common.callbacks import BaseCallback

    key = spec.key
    run_id = spec.run_id
    gamma = spec.hyperparameters["gamma"]
    version = code_version()  # the code as the run starts, not as a long run ends after an edit
    started = time.perf_counter()
    model = make_learner(key, spec.hyperparameters)
    eval_env = make_evaluation_env(key, spec.hyperparameters)
    callbacks: list[Any] = []
    logs = None
    if tensorboard is not None:
        from planshape.training import tensorboard_logs as logs

        logs.attach(model, tensorboard, key)
        callbacks.append(logs.shaping_callback(gamma))
    if progress:
        from planshape.training.progress import run_progress

        name = f"{key.task.split('/')[-1]} {key.entry} {key.algo} seed{key.seed}"
        callbacks.append(run_progress(name, key.budget))

    points: list[tuple[int, dict[str, float]]] = []
    eval_seconds = [0.0]
    episodes = spec.episodes

    def record() -> None:
        t0 = time.perf_counter()
        points.append((int(model.num_timesteps), evaluate(model, eval_env, episodes)))
        if logs is not None:
            logs.record_evaluation(model, points[-1][1])
        eval_seconds[0] += time.perf_counter() - t0

    class Evaluation(BaseCallback):
        """Evaluates at the start of a rollout, when the policy has been updated on every
        step collected so far (PPO and SAC alike), once ``eval_every`` more steps are in."""

        def __init__(self) -> None:
            super().__init__()
            self.next_at = spec.eval_every

        def _on_rollout_start(self) -> None:
            if self.num_timesteps >= self.next_at and self.num_timesteps < key.budget:
                record()
                while self.next_at <= self.num_timesteps:
                    self.next_at += spec.eval_every

        def _on_step(self) -> bool:
            return True

    record()  # the untrained policy, at step 0
    model.learn(key.budget, callback=[Evaluation(), *callbacks] if callbacks else Evaluation())
    record()
    wall = time.perf_counter() - started
    train_seconds = max(wall - eval_seconds[0], 1e-9)
    model.get_env().close()
    eval_env.close()
    provenance = {
        "run_id": run_id,
        "task": key.task,
        "entry": key.entry,
        "potential": key.potential,
        "model": key.model,
        "algo": key.algo,
        "seed": key.seed,
        "budget": key.budget,
        "profile": spec.profile,
        "eval_episodes": len(episodes),
        "eval_protocol": spec.eval_protocol,
        "evaluation": evaluation_text(key.task, len(episodes)),
        "invariance": spec.invariance,
        "wall_time_s": round(wall, 3),
        "steps_per_s": round(model.num_timesteps / train_seconds, 1),
        "code_version": version,
        "cpu": cpu_description(),
        "packages": package_versions(),
        "hyperparameters": spec.hyperparameters,
        "gamma": gamma,
    }
    last = len(points) - 1
    rows: list[StoredRow] = [
        {**provenance, "step": step, "final": i == last, **metrics}  # type: ignore[typeddict-item]
        for i, (step, metrics) in enumerate(points)
    ]
    for row in rows:  # the schema the loader checks, checked where rows are made
        validate_row(row, f"run {spec.run_id}")
    return model, rows
