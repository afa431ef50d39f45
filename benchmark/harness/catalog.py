"""``planshape tasks``: what is registered, with its models, predicates and reward variants.

Example:
    >>> rows = describe_tasks(["planshape/Reach-v0"])  # doctest: +SKIP
    >>> rows[0]["models"]["grid"]["predicates"]  # doctest: +SKIP
    ['robot_at']
"""

from __future__ import annotations

import argparse
import json
from collections.abc import Iterable
from typing import Any

from planshape.commands import Handler, subcommand
from planshape.shaping.registration import (
    REWARDS,
    abstract_model,
    instances_summary,
    task_ids,
    task_spec,
)


def describe_tasks(ids: Iterable[str] | None = None) -> list[dict[str, Any]]:
    """One JSON-ready row per task: id, description, horizon, reward variants, its instances
    (``None`` for a fixed task, ``{"train": N, "eval": M}`` for a task-instance distribution,
    whose models are shown for its first training instance; ``"seeded"`` for a task that draws
    its start from the seed), and per model the PDDL files and the fluent predicates its
    classifiers decide."""
    rows = []
    for task_id in ids or task_ids():
        spec = task_spec(task_id)
        models = {}
        for name in spec.models:
            model = abstract_model(spec, name)
            models[name] = {
                "domain": str(model.domain),
                "problem": str(model.problem),
                "predicates": sorted(model.classifiers),
                "geometry": model.geometry is not None,
            }
        rows.append(
            {
                "id": spec.id,
                "description": spec.description,
                "max_episode_steps": spec.max_episode_steps,
                "rewards": list(REWARDS),
                "default_model": spec.default_model,
                "instances": None if spec.fixed else (instances_summary(spec) or "seeded"),
                "models": models,
            }
        )
    return rows


@subcommand("tasks", "list the registered tasks with their models, predicates and rewards")
def _tasks(parser: argparse.ArgumentParser) -> Handler:
    parser.add_argument("ids", nargs="*", help="task ids to describe (default: all)")
    parser.add_argument("--json", action="store_true", help="print JSON")

    def run(args: argparse.Namespace) -> int:
        rows = describe_tasks(args.ids)
        if args.json:
            print(json.dumps(rows, indent=2))
            return 0
        for row in rows:
            instances = row["instances"]
            if isinstance(instances, dict):
                drawn = f", instances {instances['train']} train / {instances['eval']} held out"
            else:
                drawn = ", fixed start" if instances is None else ", start drawn from the seed"
            print(f"{row['id']}  ({row['max_episode_steps']} steps{drawn})  {row['description']}")
            for name, model in row["models"].items():
                default = " (default)" if name == row["default_model"] else ""
                predicates = ", ".join(model["predicates"])
                print(f"    model {name}{default}: predicates {predicates}")
        print(f"reward variants: {', '.join(REWARDS)}; {len(rows)} tasks")
        return 0

    return run
