"""``planshape probe``: train one benchmark run and print what happens inside the learner.

The leaderboard shows where a run ends; the probe shows how it got there. It trains exactly the
benchmark's run of (task, entry, algorithm, seed, budget), with the benchmark's hyperparameters,
and at each of ``chunks`` checkpoints prints:

* ``train_distance`` / ``train_success``: the mean final distance and the success rate of the
  training episodes that ended since the last checkpoint (the stochastic policy, on the
  environment the learner trains on);
* ``progress``: their mean plan progress (max_idx) at the end, out of the plan length
  (shaped entries only);
* ``explained_variance``: how much of the returns of the last rollout the critic predicts
  (PPO; stable-baselines3's ``train/explained_variance``);
* ``action_std``: the policy's mean action standard deviation (PPO);
* ``eval_success`` / ``eval_distance``: the benchmark's evaluation (the deterministic policy on
  the task's sparse reward); ``eval_success_any``: its episodes in which the task's success
  flag was set at some step, not only at the end (MetaWorld's own protocol).

It is how the push diagnosis in ``planshape.training.hyperparams`` was made: with a potential, PPO's
critic explains almost nothing of the shaped return for the first ~80k steps, in which the
policy follows the potential towards the goal; once the critic has learned −φ (explained
variance 0 → 0.6–0.9), the shaped advantages are the sparse task's, which are zero where the
goal was never reached, and the policy drifts back.

Example:
    >>> rows = probe(RunKey("planshape/Reach-v0", "plan-based/grid", "PPO", 0, 2048), chunks=2,
    ...              eval_episodes=1)  # doctest: +SKIP
    >>> [row["step"] for row in rows]  # doctest: +SKIP
    [1024, 2048]
"""

from __future__ import annotations

import argparse
import json
import math
from typing import Any

import numpy as np

from planshape.commands import Handler, subcommand
from planshape.errors import BadInputError
from planshape.harness.profiles import RunKey
from planshape.training.hyperparams import hyperparameters

__all__ = ["checked_key", "checked_scale", "probe"]


def probe(
    key: RunKey,
    chunks: int = 8,
    eval_episodes: int = 10,
    tensorboard: str | None = None,
    shaping_scale: float | None = None,
    observe_progress: bool = False,
) -> list[dict[str, Any]]:
    """Train ``key`` in ``chunks`` equal parts; one row of learner statistics after each.
    With ``tensorboard`` (a folder) the run also logs there
    (:mod:`planshape.training.tensorboard_logs`). ``shaping_scale`` replaces the table's
    multiplier of φ (:data:`planshape.training.hyperparams.SHAPING_SCALE`) for this run only:
    how budgets and scales are chosen from curves before a table changes; every row records
    the scale it trained with. ``observe_progress`` shows the learner its plan progress
    (:mod:`planshape.shaping.observed_progress`), as a profile with that setting does.
    """
    from stable_baselines3.common.callbacks import BaseCallback

    from planshape.harness.runner import (
        evaluate,
        evaluation_episodes,
        make_evaluation_env,
        make_learner,
    )

    if chunks < 1 or key.budget < chunks:
        raise BadInputError(
            f"probe: --chunks must be between 1 and the budget ({key.budget}); got {chunks}"
        )
    if shaping_scale is not None:
        shaping_scale = checked_scale(key, shaping_scale)
    if observe_progress and key.reward != "shaped":
        raise BadInputError(
            f"--observe-progress shows a plan's progress; entry {key.entry!r} has no plan "
            "(give a POTENTIAL/MODEL entry or drop the option)"
        )
    settings = hyperparameters(
        key.task,
        key.algo,
        key.entry,
        shaping_scale=shaping_scale,
        observe_progress=observe_progress,
    )
    model = make_learner(key, settings)
    eval_env = make_evaluation_env(key, settings)
    ended: list[dict[str, Any]] = []

    class EpisodeEnds(BaseCallback):
        def _on_step(self) -> bool:
            for done, info in zip(self.locals["dones"], self.locals["infos"], strict=True):
                if done:
                    ended.append(info)
            return True

    callbacks: list[Any] = [EpisodeEnds()]
    if tensorboard is not None:
        from planshape.training import tensorboard_logs

        tensorboard_logs.attach(model, tensorboard, key)
        callbacks.append(tensorboard_logs.shaping_callback(settings["gamma"]))
    rows = []
    plan_length = _plan_length(model)
    for chunk in range(chunks):
        target = key.budget * (chunk + 1) // chunks
        model.learn(target - model.num_timesteps, reset_num_timesteps=False, callback=callbacks)
        logged = model.logger.name_to_value
        scores = evaluate(model, eval_env, evaluation_episodes(key.task, eval_episodes))
        rows.append(
            {
                "step": int(model.num_timesteps),
                "train_episodes": len(ended),
                "train_distance": _mean(info.get("distance") for info in ended),
                "train_success": _mean(float(bool(info.get("success"))) for info in ended),
                "progress": _mean(info.get("progress") for info in ended),
                "plan_length": plan_length,
                "explained_variance": _number(logged.get("train/explained_variance")),
                "action_std": _action_std(model),
                "eval_success": scores["success_rate"],
                "eval_success_any": scores["success_any_rate"],
                "eval_distance": scores["final_distance"],
                "shaping_scale": settings["shaping_scale"] if key.reward == "shaped" else None,
            }
        )
        ended.clear()
        if tensorboard is not None:
            tensorboard_logs.record_evaluation(model, scores)
    model.get_env().close()
    eval_env.close()
    return rows


def checked_scale(key: RunKey, scale: float) -> float:
    """``--shaping-scale`` checked: a finite positive number, for a shaped entry (sparse and
    dense ignore it, so a scale there is a mistake in the command); else
    :class:`BadInputError` (exit 2).

    Example:
        >>> checked_scale(RunKey("planshape/Reach-v1", "plan-distance/grid", "SBX-SAC", 0, 1), 10)
        10.0
    """
    if key.reward != "shaped":
        raise BadInputError(
            f"--shaping-scale multiplies a potential; entry {key.entry!r} has none "
            "(give a POTENTIAL/MODEL entry or drop the option)"
        )
    if not math.isfinite(scale) or scale <= 0:
        raise BadInputError(f"--shaping-scale must be a finite number > 0; got {scale}")
    return float(scale)


def checked_key(task: str, entry: str, algo: str, seed: int, budget: int) -> RunKey:
    """The run of a command line (``probe``, ``render``), every part checked before anything
    trains: a short task name as ``bench --tasks`` takes it, a known learner, an entry the task
    has, a seed ≥ 0 and a budget ≥ 1 (else :class:`BadInputError`, exit 2).

    Example:
        >>> checked_key("maze-reach", "plan-distance/grid", "PPO", 0, 1024).task
        'planshape/MazeReach-v1'
    """
    from planshape.shaping.potentials import potential_ids
    from planshape.shaping.registration import task_spec
    from planshape.suite.session import resolve_tasks
    from planshape.training.learners import learner

    (task,) = resolve_tasks(task) or [task]
    learner(algo)  # an unknown learner is an UnknownIdError naming the known ones
    if entry not in ("sparse", "dense"):
        potential, _, model = entry.rpartition("/")
        models = list(task_spec(task).models)
        if not potential or model not in models:
            raise BadInputError(
                f"entry {entry!r}: write sparse, dense or POTENTIAL/MODEL with a model of "
                f"{task} ({', '.join(models)})"
            )
        if potential not in potential_ids() and ":" not in potential:
            raise BadInputError(
                f"entry {entry!r}: unknown potential {potential!r}; known: "
                + ", ".join(potential_ids())
            )
    if seed < 0 or budget < 1:
        raise BadInputError("--seed must be ≥ 0, --budget and --episodes ≥ 1")
    return RunKey(task, entry, algo, seed, budget)


def _mean(values: Any) -> float | None:
    numbers = [float(v) for v in values if v is not None]
    return float(np.mean(numbers)) if numbers else None


def _number(value: Any) -> float | None:
    return float(value) if value is not None and math.isfinite(float(value)) else None


def _action_std(model: Any) -> float | None:
    log_std = getattr(model.policy, "log_std", None)
    return float(log_std.detach().exp().mean()) if log_std is not None else None


def _plan_length(model: Any) -> int | None:
    """The plan's length, or None without shaping or when it changes between instances."""
    try:
        shaping = model.get_env().env_method("get_wrapper_attr", "per_instance", indices=[0])[0]
        progress = model.get_env().env_method("get_wrapper_attr", "progress", indices=[0])[0]
    except AttributeError:
        return None
    return None if shaping else int(progress.final)


def _cell(value: Any, width: int, digits: int = 3) -> str:
    if value is None:
        return "-".rjust(width)
    if isinstance(value, float):
        return f"{value:.{digits}f}".rjust(width)
    return str(value).rjust(width)


def format_rows(rows: list[dict[str, Any]]) -> str:
    """The probe's rows as a fixed-width table."""
    columns = [
        ("step", "step", 8),
        ("train_distance", "train dist", 10),
        ("train_success", "train succ", 10),
        ("progress", "progress", 8),
        ("plan_length", "of", 3),
        ("explained_variance", "expl var", 8),
        ("action_std", "std", 6),
        ("eval_distance", "eval dist", 9),
        ("eval_success", "eval succ", 9),
        ("eval_success_any", "any step", 8),
    ]
    lines = [" ".join(title.rjust(width) for _, title, width in columns)]
    for row in rows:
        lines.append(" ".join(_cell(row[name], width) for name, _, width in columns))
    return "\n".join(lines)


@subcommand("probe", "train one benchmark run and print the learner's statistics as it learns")
def _probe_command(parser: argparse.ArgumentParser) -> Handler:
    parser.add_argument("task", help="a task id or short name, as bench --tasks: push, Push-v1")
    parser.add_argument("entry", help="sparse, dense or POTENTIAL/MODEL")
    parser.add_argument("--algo", default="PPO", help="a learner id: PPO, SAC, SBX-SAC, ...")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--budget", type=int, default=81_920, help="environment steps")
    parser.add_argument("--chunks", type=int, default=8, help="checkpoints (default: 8)")
    parser.add_argument("--episodes", type=int, default=10, help="evaluation episodes")
    parser.add_argument("--json", action="store_true", help="print JSON rows")
    parser.add_argument(
        "--shaping-scale",
        type=float,
        metavar="S",
        help="multiply φ by S instead of the hyperparameter table's 1/(1 − γ) (shaped entries)",
    )
    parser.add_argument(
        "--observe-progress",
        action="store_true",
        help="the learner sees its plan progress after the observation (shaped entries)",
    )
    parser.add_argument(
        "--tensorboard", metavar="DIR", help="also log the run to TensorBoard under DIR"
    )

    def run(args: argparse.Namespace) -> int:
        if args.episodes < 1:
            raise BadInputError("--seed must be ≥ 0, --budget and --episodes ≥ 1")
        key = checked_key(args.task, args.entry, args.algo, args.seed, args.budget)
        if args.tensorboard:
            from planshape.training.tensorboard_logs import require_tensorboard

            require_tensorboard()
        rows = probe(
            key,
            args.chunks,
            args.episodes,
            args.tensorboard,
            args.shaping_scale,
            args.observe_progress,
        )
        print(json.dumps(rows) if args.json else format_rows(rows))
        return 0

    return run
