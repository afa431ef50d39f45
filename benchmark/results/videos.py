"""Watching a policy: an animation of a run's final deterministic policy, the plan drawn in.

Reward hacking is seen, not read: on maze-reach the dense reward's policy presses against the
wall. :func:`policy_video` trains the run of (task, entry, algorithm, seed) exactly as the
benchmark does — the same spec, so the same numbers as the stored run
(:func:`planshape.harness.runner.train`) — then renders one evaluation episode of its deterministic
policy with the task's ``rgb_array`` rendering, the places of the plan's subgoals drawn as
dots, and writes a GIF. ``planshape render TASK ENTRY [--seed N]`` makes one; files in
``<out>/videos/`` appear on the leaderboard page beside their task.

Example:
    >>> name = video_name(RunKey("planshape/Reach-v1", "plan-based/grid", "PPO", 0, 1))
    >>> name
    'planshape-Reach-v1__plan-based-grid__PPO__seed0.gif'
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

import numpy as np

from planshape.commands import Handler, subcommand
from planshape.errors import BadInputError
from planshape.harness.profiles import RunKey, get_profile

__all__ = ["VIDEOS_DIR", "policy_video", "subgoal_marks", "video_name"]

VIDEOS_DIR = "videos"


def video_name(key: RunKey) -> str:
    """The file name of a run's video in ``<out>/videos/``."""
    parts = (key.task, key.entry, key.algo, f"seed{key.seed}")
    return "__".join(p.replace("/", "-") for p in parts) + ".gif"


def subgoal_marks(task: str, model: str) -> list[tuple[float, float]]:
    """Where the plan of ``task``'s ``model`` puts each entity, subgoal by subgoal."""
    import gymnasium

    env = gymnasium.make(task, reward="shaped", potential="plan-based", model=model, gamma=0.99)
    shaping = env.get_wrapper_attr("progress"), env.get_wrapper_attr("geometry")
    progress, geometry = shaping
    marks: list[tuple[float, float]] = []
    if geometry is not None:
        for subgoal in progress.subgoals:
            for place in geometry.locate(subgoal).values():
                point = tuple(float(v) for v in np.asarray(place, float)[:2])
                if point not in marks:
                    marks.append(point)
    env.close()
    return marks


def policy_video(
    key: RunKey,
    profile: str,
    path: str | Path,
    *,
    model_for_marks: str = "grid",
    frame_seconds: float = 0.08,
) -> dict[str, Any]:
    """Train ``key`` as ``profile`` does, render its deterministic policy on the first
    evaluation episode to a GIF at ``path``; return the run's final evaluation row."""
    import imageio.v3 as iio

    from planshape.harness.runner import make_evaluation_env, train

    spec = get_profile(profile).spec(key)
    learner, rows = train(spec)
    env = make_evaluation_env(key, spec.hyperparameters, render_mode="rgb_array")
    if not hasattr(env.unwrapped, "render_marks"):
        raise BadInputError(f"{key.task}: only the planar tasks draw their plan (render_marks)")
    env.unwrapped.render_marks = subgoal_marks(key.task, key.model or model_for_marks)
    obs, _ = env.reset(**spec.episodes[0])
    frames, done = [env.render()], False
    while not done:
        action, _ = learner.predict(obs, deterministic=True)
        obs, _, terminated, truncated, _ = env.step(action)
        frames.append(env.render())
        done = terminated or truncated
    env.close()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    iio.imwrite(path, np.stack(frames), duration=int(frame_seconds * 1000), loop=0)
    return rows[-1]


@subcommand("render", "train one run and write an animation of its final deterministic policy")
def _render(parser: argparse.ArgumentParser) -> Handler:
    parser.add_argument("task", help="a task id or short name, e.g. maze-reach")
    parser.add_argument("entry", help="sparse, dense or POTENTIAL/MODEL")
    parser.add_argument("--algo", default="PPO", help="a learner id (default: PPO)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--profile", default="default", help="whose budget and settings")
    parser.add_argument(
        "--out", type=Path, default=None, help="results folder (default: the profile's own)"
    )
    return _run_render


def _run_render(args: argparse.Namespace) -> int:
    from planshape.harness.probe import checked_key

    profile = get_profile(args.profile)
    key = checked_key(args.task, args.entry, args.algo, args.seed, budget=1)
    budget = profile.budgets().get((key.task, key.algo))
    if budget is None:
        raise BadInputError(
            f"profile {profile.name!r} has no budget for {key.task} with {key.algo}; pick a "
            "profile that runs it (planshape bench --profile NAME --dry-run lists the runs)"
        )
    key = RunKey(key.task, key.entry, key.algo, key.seed, budget)
    task = key.task
    out = args.out if args.out is not None else Path(profile.folder)
    path = out / VIDEOS_DIR / video_name(key)
    final = policy_video(key, profile.name, path)
    print(
        f"wrote {path}: {task} {args.entry} {args.algo} seed {args.seed}, final success "
        f"{final['success_rate']:.2f}, distance {final['final_distance']:.3f} m"
    )
    return 0
