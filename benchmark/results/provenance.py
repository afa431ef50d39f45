"""Provenance: how the stored results were produced, and the caveats that follow from it.

:func:`describe_runs` reads, from the rows alone, what a leaderboard's header shows — budgets,
seeds, evaluations, code and package versions, discounts, hyperparameters, run time — and
derives plain sentences about anything that weakens a comparison (mixed versions, unequal
seed counts, missing or tied references, invariance violations, uncommitted code).

Example:
    >>> info = describe_runs([])
    >>> info["n_runs"], info["caveats"]
    (0, [])
"""

from __future__ import annotations

from collections import Counter, defaultdict
from collections.abc import Iterable
from typing import Any

import numpy as np

from planshape.results.cells import (
    REFERENCE_ENTRIES,
    SPARSE,
    Cells,
    cells,
    finished_runs,
    references,
)
from planshape.results.rows import Row, evaluation_text
from planshape.results.stats import normalized_score

__all__ = ["CPU_NOT_RECORDED", "describe_runs"]


def _settings(finals: list[dict[str, Any]]) -> dict[str, Any]:
    """Budgets (task -> algo -> steps), distinct hyperparameters, package versions seen."""
    budgets: dict[str, dict[str, int]] = defaultdict(dict)
    hyper: dict[str, dict[str, list[Any]]] = defaultdict(lambda: defaultdict(list))
    packages: dict[str, set[str]] = defaultdict(set)
    for f in finals:
        budgets[f["task"]][f["algo"]] = f["budget"]
        settings = hyper[f["task"]][f["algo"]]
        if f["hyperparameters"] not in settings:
            settings.append(f["hyperparameters"])
        for name, version in (f["packages"] or {}).items():
            packages[str(name)].add(str(version))
    return {
        "budgets": {t: dict(sorted(b.items())) for t, b in sorted(budgets.items())},
        "packages": {name: sorted(v) for name, v in sorted(packages.items())},
        "hyperparameters": {
            t: {a: settings for a, settings in sorted(by_algo.items())}
            for t, by_algo in sorted(hyper.items())
        },
    }


#: what :func:`describe_runs` counts a run under when its rows predate the ``cpu`` field
CPU_NOT_RECORDED = "not recorded"


def _cpu_counts(finals: list[dict[str, Any]]) -> dict[str, int]:
    """How many runs each CPU trained (the rows' ``cpu``), most first, then by name.

    Example:
        >>> _cpu_counts([{"cpu": "AMD EPYC (avx2)"}, {}, {"cpu": "AMD EPYC (avx2)"}])
        {'AMD EPYC (avx2)': 2, 'not recorded': 1}
    """
    counts = Counter(f.get("cpu") or CPU_NOT_RECORDED for f in finals)
    return dict(sorted(counts.items(), key=lambda item: (-item[1], item[0])))


def _provenance(
    rows: list[Row], finals: list[dict[str, Any]], groups: Cells, incomplete: list[str]
) -> dict[str, Any]:
    seed_counts = [len(g) for g in groups.values()]
    settings = _settings(finals)
    return {
        "n_runs": len(finals),
        "n_rows": len(rows),
        "profiles": sorted({f["profile"] for f in finals}),
        "budgets": settings["budgets"],
        "seeds": sorted({f["seed"] for f in finals}),
        "seeds_per_entry": [min(seed_counts), max(seed_counts)] if seed_counts else [],
        "eval_episodes": sorted({f["eval_episodes"] for f in finals}),
        "evaluations": {
            t: sorted({evaluation_text(f) for f in finals if f["task"] == t})
            for t in sorted({f["task"] for f in finals})
        },
        "code_versions": sorted({f["code_version"] for f in finals}),
        "cpus": _cpu_counts(finals),
        "packages": settings["packages"],
        "gammas": sorted({f["gamma"] for f in finals}),
        "hyperparameters": settings["hyperparameters"],
        "wall_time_s": float(sum(f["wall_time_s"] for f in finals)),
        "incomplete_runs": incomplete,
    }


def _version_caveats(info: dict[str, Any], profile: str | None) -> list[str]:
    """Incomplete runs, single seeds, mixed code, profiles, packages and discounts."""
    caveats = []
    incomplete = info["incomplete_runs"]
    if incomplete:
        caveats.append(
            f"{len(incomplete)} run(s) have no final evaluation row and are left out: "
            f"{', '.join(incomplete)}"
        )
    if info["seeds_per_entry"] and info["seeds_per_entry"][0] < 2:
        caveats.append(
            "some entries have a single seed: they get no confidence interval, and one seed says "
            "little about an RL method"
        )
    if len(info["code_versions"]) > 1:
        versions = ", ".join(info["code_versions"])
        caveats.append(f"results come from several code versions: {versions}")
    if any(v.endswith("-dirty") for v in info["code_versions"]):
        caveats.append("some runs ran on a working tree with uncommitted changes (-dirty)")
    other_profile = profile is not None and info["profiles"] not in ([profile], [])
    if len(info["profiles"]) > 1 or other_profile:
        caveats.append(
            f"rows come from profile(s) {', '.join(info['profiles'])}"
            + (f", not only {profile!r}" if profile is not None else "")
        )
    mixed = {n: v for n, v in info["packages"].items() if len(v) > 1}
    for name, versions in mixed.items():
        caveats.append(f"runs used different versions of {name}: {', '.join(versions)}")
    if len(info["gammas"]) > 1:
        caveats.append(f"runs used different discounts: {', '.join(map(str, info['gammas']))}")
    return caveats


def _reference_caveats(groups: Cells, task: str, algo: str) -> list[str]:
    """Unequal seed counts, and missing or tied references, of one task and algorithm."""
    caveats = []
    counts = {e: len(g) for (t, a, e), g in groups.items() if (t, a) == (task, algo)}
    if len(set(counts.values())) > 1:
        caveats.append(
            f"{task} / {algo}: entries have unequal numbers of seeds "
            f"({min(counts.values())} to {max(counts.values())})"
        )
    missing = [e for e in REFERENCE_ENTRIES if e not in counts]
    if missing:
        caveats.append(
            f"{task} / {algo}: no {' or '.join(missing)} entry, so normalized scores"
            + (" and P(improve over sparse)" if SPARSE in missing else "")
            + " are n/a"
        )
        return caveats
    for metric, label in (("success_rate", "success"), ("final_distance", "final distance")):
        sparse, dense = references(groups, task, algo, metric)
        if np.isnan(normalized_score(sparse, sparse, dense)):
            caveats.append(
                f"{task} / {algo}: dense is no better than sparse on mean final {label}, "
                f"so normalized {label} is n/a there"
            )
    return caveats


def _invariance_caveats(groups: Cells) -> list[str]:
    violated = sorted(
        {
            (t, e)
            for (t, _, e), g in groups.items()
            for r in g
            if r.final["invariance"] == "violated"
        }
    )
    if not violated:
        return []
    return [
        "the invariance check found a changed optimal policy for: "
        + ", ".join(f"{e} on {t}" for t, e in violated)
        + "; those entries are not policy-invariant shaping"
    ]


def describe_runs(rows: Iterable[Row], profile: str | None = None) -> dict[str, Any]:
    """Provenance of the results, for a leaderboard header, and caveats derived from it.

    Returns a dict with ``n_runs``, ``n_rows``, ``profiles``, ``budgets`` (task -> algo ->
    steps), ``seeds`` (every seed), ``seeds_per_entry`` ([fewest, most] seeds of any
    task/entry/algo), ``eval_episodes``, ``code_versions``, ``cpus`` (the CPU each run trained on
    -> how many runs; runs whose rows predate the ``cpu`` field count as ``'not recorded'``),
    ``packages`` (name -> versions seen),
    ``gammas``, ``hyperparameters`` (task -> algo -> distinct settings), ``wall_time_s`` (the
    sum over runs), ``incomplete_runs`` (run ids without a final row) and ``caveats``: plain
    sentences about anything that weakens a comparison (mixed code or package versions, a
    profile other than ``profile``, unequal seed counts, missing references, references that
    tie, invariance violations, uncommitted code).
    """
    rows = list(rows)
    runs, incomplete = finished_runs(rows)
    groups = cells(runs)
    info = _provenance(rows, [r.final for r in runs], groups, incomplete)
    caveats = _version_caveats(info, profile)
    for task, algo in sorted({(t, a) for t, a, _ in groups}):
        caveats += _reference_caveats(groups, task, algo)
    info["caveats"] = caveats + _invariance_caveats(groups)
    return info
