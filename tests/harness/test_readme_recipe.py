"""The README's recipe for training what a leaderboard cell trains runs as written (with a tiny
budget), and builds the benchmark's own learner: same settings, same VecEnv, same numbers."""

from __future__ import annotations

import re
from pathlib import Path

README = Path(__file__).resolve().parents[2] / "README.md"


def test_the_readme_recipe_trains_the_benchmarks_run():
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(encoding="utf-8"), re.S)
    recipe = next(b for b in blocks if "make_learner(key" in b)
    namespace: dict = {}
    exec(recipe.replace("budget=245_760", "budget=1_024"), namespace)
    model, key = namespace["model"], namespace["key"]
    assert model.num_timesteps == 1024
    assert model.gamma == 0.99 and model.n_steps == 128 and model.env.num_envs == 8
    assert key.entry == "plan-distance/grid"
