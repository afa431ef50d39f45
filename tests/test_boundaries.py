"""The engine never imports a specific task or baseline (ARCHITECTURE.md): tasks and baselines
register themselves with ``"module:attr"`` strings, and the engine reaches them through its
registries. Only the package's ``__init__`` imports the two packages, to run their
registrations. Docstring examples may import them; code may not."""

from __future__ import annotations

import ast
from pathlib import Path

ENGINE = Path(__file__).resolve().parents[1] / "benchmark"
FORBIDDEN = ("planshape.tasks", "planshape.baselines")


def _imports(tree: ast.AST) -> list[tuple[int, str]]:
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module:
            found.append((node.lineno, node.module))
            if node.module == "planshape":
                found += [(node.lineno, f"planshape.{alias.name}") for alias in node.names]
    return found


def test_the_engine_imports_no_task_and_no_baseline():
    offenders = []
    for path in sorted(ENGINE.rglob("*.py")):
        if path == ENGINE / "__init__.py":
            continue
        for line, module in _imports(ast.parse(path.read_text())):
            if module.startswith(FORBIDDEN):
                offenders.append(f"{path.relative_to(ENGINE.parent)}:{line} imports {module}")
    assert not offenders, "\n".join(offenders)


def test_the_check_sees_an_import():
    assert _imports(ast.parse("from planshape.tasks.planar import toys"))[0][1].startswith(
        FORBIDDEN
    )
