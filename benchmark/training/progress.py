"""A tqdm bar over one run's training steps, as a stable-baselines3 callback.

It only observes (it reads ``num_timesteps`` and never stops training), so a run trained with it
has the numbers of a run trained without. ``planshape bench --workers 1`` shows it on a terminal
below the session's bar; off a terminal (a log file) it draws nothing.

>>> import io
>>> from stable_baselines3 import PPO
>>> model = PPO("MlpPolicy", "CartPole-v1", n_steps=64, batch_size=64, n_epochs=1, seed=0)
>>> progress = run_progress("CartPole", 128, file=io.StringIO(), bar=True)
>>> _ = model.learn(128, callback=progress)
>>> progress.bar.n, progress.bar.total
(128, 128)
"""

from __future__ import annotations

import sys
from typing import IO, Any


def run_progress(name: str, budget: int, *, file: IO[str] | None = None, bar: bool | None = None):
    """The callback: a bar named ``name`` from 0 to ``budget`` steps, removed when training ends
    (``bar``: None shows it only when ``file``, stderr by default, is a terminal)."""
    from stable_baselines3.common.callbacks import BaseCallback
    from tqdm import tqdm

    class RunProgress(BaseCallback):
        def __init__(self) -> None:
            super().__init__()
            self.bar: Any = None

        def _on_training_start(self) -> None:
            self.bar = tqdm(
                total=budget,
                desc=name,
                unit="step",
                unit_scale=True,
                file=file if file is not None else sys.stderr,
                disable=None if bar is None else not bar,
                dynamic_ncols=True,
                leave=False,
            )

        def _on_step(self) -> bool:
            self.bar.update(max(min(self.num_timesteps, budget) - self.bar.n, 0))
            return True

        def _on_training_end(self) -> None:
            self.bar.update(max(min(self.num_timesteps, budget) - self.bar.n, 0))
            self.bar.close()

    return RunProgress()
