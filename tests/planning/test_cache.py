"""The plan cache: hits skip parsing and planning; damaged entries are replanned and rewritten."""

from __future__ import annotations

import json
import logging
import pickle

import pytest

from planshape.planning import CACHE_DIR_ENV, PlanCache, cache_key, read_pddl, solve

solve_module = __import__("planshape.planning.solve", fromlist=["solve"])


@pytest.fixture
def cache_dir(tmp_path):
    return tmp_path / "plans"


def entry_path(cache_dir, domain, problem, search="astar-lmcut"):
    key = cache_key(read_pddl(domain), read_pddl(problem), search)
    return PlanCache(cache_dir).path(key)


def test_hit_returns_the_same_plan_without_parsing_or_planning(
    domain, problem, cache_dir, monkeypatch
):
    cold = solve(domain, problem, cache_dir=cache_dir)
    assert not cold.from_cache and cold.planner_seconds > 0
    assert entry_path(cache_dir, domain, problem).is_file()

    def forbidden(*args, **kwargs):
        raise AssertionError("a cache hit must not parse or plan")

    monkeypatch.setattr(solve_module, "parse_task", forbidden)
    monkeypatch.setattr(solve_module, "plan_text", forbidden)
    hit = solve(domain, problem, cache_dir=cache_dir)
    assert hit.from_cache and hit.planner_seconds == 0.0
    assert hit == cold
    assert hit.actions == cold.actions and list(hit.subgoals) == list(cold.subgoals)
    assert hit.subgoals.static == cold.subgoals.static
    assert pickle.loads(pickle.dumps(hit)) == cold


def test_key_depends_on_texts_and_search(domain, problem):
    d, p = read_pddl(domain), read_pddl(problem)
    keys = {
        cache_key(d, p, "astar-lmcut"),
        cache_key(d, p, "lama-first"),
        cache_key(d, p + " ", "astar-lmcut"),
        cache_key(d + " ", p, "astar-lmcut"),
    }
    assert len(keys) == 4
    assert cache_key(d, p, "astar-lmcut") == cache_key(d, p, "astar-lmcut")


def test_default_directory_comes_from_the_environment(domain, problem, tmp_path, monkeypatch):
    monkeypatch.setenv(CACHE_DIR_ENV, str(tmp_path / "from-env"))
    solve(domain, problem)
    assert len(list((tmp_path / "from-env").glob("*.json"))) == 1
    assert solve(domain, problem).from_cache


def test_no_cache_writes_nothing(domain, problem, tmp_path, monkeypatch):
    monkeypatch.setenv(CACHE_DIR_ENV, str(tmp_path / "unused"))
    assert not solve(domain, problem, cache_dir=False).from_cache
    assert not solve(domain, problem, cache_dir=False).from_cache
    assert not (tmp_path / "unused").exists()


def truncate(text: str) -> str:
    return text[: len(text) // 2]


def garble(text: str) -> str:
    return "{not json" + text[9:]


def change_cost(text: str) -> str:  # valid JSON, right key, but the payload no longer matches
    entry = json.loads(text)
    entry["payload"]["cost"] = 1
    return json.dumps(entry)


def other_format(text: str) -> str:
    return text.replace('"format": 1', '"format": 999', 1)


@pytest.mark.parametrize("damage", [truncate, garble, change_cost, other_format, lambda t: ""])
def test_damaged_entry_is_replanned_and_rewritten(domain, problem, cache_dir, damage, caplog):
    cold = solve(domain, problem, cache_dir=cache_dir)
    path = entry_path(cache_dir, domain, problem)
    good = path.read_text()
    path.write_text(damage(good))
    with caplog.at_level(logging.WARNING, logger="planshape.planning"):
        again = solve(domain, problem, cache_dir=cache_dir)
    assert not again.from_cache and again == cold
    assert "ignoring plan cache entry" in caplog.text and str(path) in caplog.text
    assert solve(domain, problem, cache_dir=cache_dir).from_cache  # rewritten


def test_entry_of_other_inputs_is_not_trusted(domain, problem, cache_dir, caplog):
    two = problem.parent / "delivery-two-items.pddl"
    solve(domain, two, cache_dir=cache_dir)
    # put the two-item entry where the one-item problem's entry belongs
    entry_path(cache_dir, domain, two).replace(entry_path(cache_dir, domain, problem))
    with caplog.at_level(logging.WARNING, logger="planshape.planning"):
        plan = solve(domain, problem, cache_dir=cache_dir)
    assert not plan.from_cache and plan.length == 4
    assert "key does not match" in caplog.text


def test_entry_is_readable_json(domain, problem, cache_dir):
    solve(domain, problem, cache_dir=cache_dir)
    entry = json.loads(entry_path(cache_dir, domain, problem).read_text())
    assert set(entry) == {"format", "key", "checksum", "payload"}
    payload = entry["payload"]
    assert payload["actions"][0] == "(go depot kitchen)"
    assert payload["cost"] == 4 and payload["search"] == "astar-lmcut"
    assert payload["fluents"][-1] == ["(at depot)", "(delivered cup)"]
    assert "(connected depot kitchen)" in payload["static"]
    assert not list(cache_dir.glob(".tmp-*"))  # the temporary file was renamed


def test_unwritable_cache_still_returns_the_plan(domain, problem, tmp_path, caplog):
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    with caplog.at_level(logging.WARNING, logger="planshape.planning"):
        plan = solve(domain, problem, cache_dir=blocker / "plans")
    assert plan.length == 4 and "could not write the plan cache" in caplog.text
