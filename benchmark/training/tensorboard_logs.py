"""Live training logs: stable-baselines3's logger to TensorBoard, plus the shaping's own scalars.

``planshape bench --tensorboard DIR`` and ``planshape probe --tensorboard DIR`` write one
TensorBoard run per training run into ``DIR/<task>/<entry>/<algo>/seed<N>``; watch them with
``tensorboard --logdir DIR``. Besides the learner's scalars (``rollout/ep_rew_mean``,
``train/loss``, …) each finished training episode adds, averaged over the episodes between two
dumps of the logger:

* ``shaping/shaped_return`` — the return the learner optimises (task reward plus F);
* ``shaping/task_return`` — the same episode under the task's own reward (``reward_original``);
* ``shaping/final_progress`` — ``max_idx`` at the episode's end;
* ``shaping/phi_start`` and ``shaping/phi_end`` — φ of the episode's first state (recovered
  as γ·φ(s1) − F0) and of its last (0 when the episode terminated, correctness rule 2);
* ``eval/success_rate``, ``eval/success_any_rate``, ``eval/final_distance`` and
  ``eval/sparse_return`` at every evaluation point of the run.

Logging reads the step's ``info`` and writes files; it changes neither the run's identity nor
its numbers (a test trains the same spec with and without it). It needs the ``tensorboard``
package: ``pip install 'planshape[tensorboard]'``.

Example:
    >>> from planshape.harness.profiles import RunKey
    >>> log_folder("runs", RunKey("planshape/Reach-v1", "plan-based/grid", "PPO", 3, 1024))
    'runs/Reach-v1/plan-based-grid/PPO/seed3'
"""

from __future__ import annotations

import importlib.util
from pathlib import Path
from typing import Any

from planshape.errors import BadInputError
from planshape.harness.profiles import RunKey


def log_folder(root: str | Path, key: RunKey) -> str:
    """Where the TensorBoard run of ``key`` is written under ``root``."""
    entry = key.entry.replace("/", "-").replace(":", "-")
    return str(Path(root) / key.task.split("/", 1)[-1] / entry / key.algo / f"seed{key.seed}")


def require_tensorboard() -> None:
    """Raise a clear error (exit 2) when the ``tensorboard`` package is not installed."""
    if importlib.util.find_spec("tensorboard") is None:
        raise BadInputError(
            "--tensorboard needs the tensorboard package: pip install 'planshape[tensorboard]'"
        )


def attach(model: Any, root: str | Path, key: RunKey) -> None:
    """Point ``model``'s logger at TensorBoard (and nowhere else) for the run ``key``."""
    from stable_baselines3.common.logger import configure

    require_tensorboard()
    model.set_logger(configure(log_folder(root, key), ["tensorboard"]))


def shaping_callback(gamma: float) -> Any:
    """A stable-baselines3 callback that records the shaping scalars of finished episodes."""
    from stable_baselines3.common.callbacks import BaseCallback

    class ShapingScalars(BaseCallback):
        def __init__(self) -> None:
            super().__init__()
            self.episodes: dict[int, dict[str, float]] = {}

        def _on_step(self) -> bool:
            for env, (info, done) in enumerate(
                zip(self.locals["infos"], self.locals["dones"], strict=True)
            ):
                if "shaping" not in info:  # sparse and dense runs have nothing to add
                    continue
                episode = self.episodes.get(env)
                if episode is None:
                    episode = self.episodes[env] = {
                        "shaped": 0.0,
                        "task": 0.0,
                        "phi_start": gamma * info["potential"] - info["shaping"],
                    }
                episode["shaped"] += float(info["reward_original"]) + info["shaping"]
                episode["task"] += float(info["reward_original"])
                if done:
                    record = self.logger.record_mean
                    record("shaping/shaped_return", episode["shaped"])
                    record("shaping/task_return", episode["task"])
                    record("shaping/final_progress", info["progress"])
                    record("shaping/phi_start", episode["phi_start"])
                    record("shaping/phi_end", info["potential"])
                    del self.episodes[env]
            return True

    return ShapingScalars()


def record_evaluation(model: Any, point: dict[str, float]) -> None:
    """Write one evaluation point of the run at the learner's current step."""
    for name in ("success_rate", "success_any_rate", "final_distance", "sparse_return"):
        if name in point:
            model.logger.record(f"eval/{name}", point[name])
    model.logger.dump(model.num_timesteps)
