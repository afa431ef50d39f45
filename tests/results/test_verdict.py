"""The budget check: what a (task, algorithm) cell can decide, and that the leaderboard says it."""

from __future__ import annotations

import pytest

from planshape.results.leaderboard import render_leaderboard
from planshape.results.verdict import MIN_SEEDS, SOLVED, budget_check
from tests.results.synthetic import make_run


def _cell(seeds: int = 5, **success: float) -> list[dict[str, object]]:
    """Summary rows of one cell: entry -> mean final success (``_`` stands for ``/``)."""
    return [
        {"entry": entry.replace("_", "/"), "n_seeds": seeds, "success_mean": value}
        for entry, value in success.items()
    ]


@pytest.mark.parametrize(
    ("cell", "status"),
    [
        # dense solves, sparse does not: the comparison can go either way
        (_cell(sparse=0.4, dense=0.94, plan_grid=0.2), "decides"),
        (_cell(sparse=0.0, dense=SOLVED, plan_grid=0.0), "decides"),
        # maze-reach: dense trapped by design, a shaped entry solves it, sparse does not
        (_cell(sparse=0.0, dense=0.0, plan_grid=1.0), "decides"),
        # drawer-close counted at the episode's end: sparse solves it too
        (_cell(sparse=0.88, dense=0.94, plan_stages=0.94), "separates-little"),
        (_cell(sparse=0.9, dense=0.1, plan_grid=1.0), "separates-little"),
        # button-press, push with PPO at 81,920 steps: nothing solves it
        (_cell(sparse=0.4, dense=0.62, plan_stages=0.36), "no-verdict"),
        (_cell(sparse=0.0, dense=0.0, plan_grid=0.0), "no-verdict"),
        (_cell(sparse=0.0, dense=SOLVED - 0.01, plan_grid=SOLVED - 0.01), "no-verdict"),
        # too few seeds, however clear the means
        (_cell(seeds=MIN_SEEDS - 1, sparse=0.0, dense=1.0, plan_grid=1.0), "no-verdict"),
        # no dense entry to check the budget against
        (_cell(sparse=0.0, plan_grid=1.0), "no-verdict"),
        # no sparse entry: nothing shows the task needs shaping at this budget
        (_cell(dense=0.9, plan_grid=0.5), "no-verdict"),
        (_cell(dense=0.0, plan_grid=1.0), "no-verdict"),
    ],
)
def test_status(cell, status):
    assert budget_check(cell).status == status


def test_the_sentence_names_the_levels_and_the_best_shaped_entry():
    text = budget_check(_cell(sparse=0.4, dense=0.62, plan_stages=0.36, other_grid=0.1)).text
    assert text.startswith("no verdict: no entry reaches 0.8 mean success")
    assert "dense 0.62, sparse 0.40, best shaped plan/stages 0.36" in text


def test_a_missing_sparse_entry_is_named():
    text = budget_check(_cell(dense=0.9, plan_grid=0.5)).text
    assert text.startswith("no verdict: no sparse entry to show whether the budget separates")


def test_the_seed_count_is_named():
    rows = _cell(sparse=0.0, dense=1.0) + _cell(seeds=2, plan_grid=1.0)
    assert "some entries have 2 seeds, fewer than 5" in budget_check(rows).text


def test_the_leaderboard_prints_each_cells_check(tmp_path):
    rows = []
    for seed in range(5):
        rows += make_run(seed=seed, final_success=0.0)
        rows += make_run(entry="dense", seed=seed, final_success=0.0)
        rows += make_run(entry="plan-distance/grid", seed=seed, final_success=1.0)
        rows += make_run(seed=seed, algo="SAC", final_success=0.2)
        rows += make_run(entry="dense", seed=seed, algo="SAC", final_success=0.3)
    header = {"profile": "test", "command": "planshape bench --profile test", "caveats": []}
    render_leaderboard(rows, tmp_path, header, reps=50)
    text = (tmp_path / "LEADERBOARD.md").read_text()
    ppo = text.split("### PPO — budget")[1].split("###")[0]
    sac = text.split("### SAC — budget")[1].split("###")[0]
    assert "**Budget check**: decides: dense ends short of 0.8" in ppo
    assert "**Budget check**: no verdict: no entry reaches 0.8" in sac
    assert "Budget check</strong>: no verdict" in (tmp_path / "index.html").read_text()
