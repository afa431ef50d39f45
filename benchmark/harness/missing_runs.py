"""Which runs a partial profile lacks, named the way its leaderboard's caveat names them."""

from __future__ import annotations

from collections.abc import Iterable

#: how many (task, entry, algorithm) groups of missing runs a caveat names before it counts
NAMED_GROUPS = 4


def name_missing(missing: Iterable[tuple[str, str, str, int]], profile: str) -> str:
    """The missing (task, entry, algo, seed) runs, grouped by task, entry and algorithm.

    A caveat names at most :data:`NAMED_GROUPS` groups and counts the rest, pointing at the
    command that lists every run still to train.

    Example:
        >>> name_missing([("planshape/Reach-v1", "dense", "PPO", s) for s in (4, 0, 1)], "smoke")
        'missing: planshape/Reach-v1 dense PPO seeds 0–1, 4'
        >>> many = [("planshape/Reach-v1", f"e{i}", "PPO", 0) for i in range(6)]
        >>> name_missing(many, "smoke")  # doctest: +NORMALIZE_WHITESPACE
        'missing: planshape/Reach-v1 e0 PPO seed 0; planshape/Reach-v1 e1 PPO seed 0;
        planshape/Reach-v1 e2 PPO seed 0; planshape/Reach-v1 e3 PPO seed 0; and 2 more runs
        (`planshape bench --profile smoke --dry-run` lists them)'
    """
    groups: dict[tuple[str, str, str], list[int]] = {}
    for task, entry, algo, seed in missing:
        groups.setdefault((task, entry, algo), []).append(seed)
    ordered = sorted(groups.items())
    parts = [
        f"{task} {entry} {algo} {'seed' if len(seeds) == 1 else 'seeds'} {_spans(seeds)}"
        for (task, entry, algo), seeds in ordered[:NAMED_GROUPS]
    ]
    rest = sum(len(seeds) for _, seeds in ordered[NAMED_GROUPS:])
    if rest:
        runs = "run" if rest == 1 else "runs"
        parts.append(
            f"and {rest} more {runs} (`planshape bench --profile {profile} --dry-run` lists them)"
        )
    return "missing: " + "; ".join(parts)


def _spans(seeds: Iterable[int]) -> str:
    """Seeds as runs of consecutive numbers.

    >>> _spans([4, 0, 1, 2, 7])
    '0–2, 4, 7'
    """
    spans: list[list[int]] = []
    for seed in sorted(seeds):
        if spans and seed == spans[-1][1] + 1:
            spans[-1][1] = seed
        else:
            spans.append([seed, seed])
    return ", ".join(str(a) if a == b else f"{a}–{b}" for a, b in spans)
