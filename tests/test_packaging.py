"""The wheel ships every module: each folder of the source tree that is a package is listed in
``pyproject.toml``'s ``packages`` under its mapped import name.

``tox`` tests the built wheel, where a folder missing from the list is simply absent; this
test reads the source tree, so it fails on the commit that adds an unlisted folder.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_every_source_package_is_in_the_wheel():
    setuptools = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    listed = set(setuptools["packages"])
    mapping: dict[str, str] = setuptools["package-dir"]
    expected = set()
    for name, folder in mapping.items():
        base = ROOT / folder
        for init in base.rglob("__init__.py"):
            parts = init.parent.relative_to(base).parts
            expected.add(".".join((name, *parts)))
    # a package nested inside another mapped folder is named by its own mapping
    nested = {
        ".".join((outer, *Path(inner_folder).relative_to(outer_folder).parts))
        for outer, outer_folder in mapping.items()
        for inner, inner_folder in mapping.items()
        if inner != outer and Path(inner_folder).is_relative_to(outer_folder)
    }
    missing = sorted(expected - nested - listed)
    assert not missing, (
        f"add these packages to pyproject.toml [tool.setuptools] packages: {missing}"
    )
    assert "planshape.tasks.planar" in listed
