"""The package list, derived from the source folders (``pyproject.toml`` holds the rest).

Each entry of ``[tool.setuptools] package-dir`` maps an import name onto a top-level folder of
the repository (the layout ARCHITECTURE.md fixes); every folder below it with an
``__init__.py`` is a package of the wheel, found by setuptools' own discovery (every folder, in
a folder of data files without one). A folder mapped
on its own (``tasks/`` is ``planshape.tasks``) is named by its own mapping only.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

from setuptools import find_namespace_packages, find_packages, setup

ROOT = Path(__file__).resolve().parent


def mapped_packages(package_dir: dict[str, str]) -> list[str]:
    """Every package under the mapped folders, by its import name."""
    folders = {Path(folder) for folder in package_dir.values()}
    packages = []
    for name, folder in package_dir.items():
        root = Path(folder)
        packages.append(name)
        # a folder of data files (pddl/) has no __init__.py: its subfolders are namespace packages
        find = find_packages if (ROOT / root / "__init__.py").exists() else find_namespace_packages
        for found in find(where=str(ROOT / root), exclude=["*__pycache__*"]):
            path = root.joinpath(*found.split("."))
            if any(path == other or path.is_relative_to(other) for other in folders - {root}):
                continue  # a nested folder with a mapping of its own
            packages.append(f"{name}.{found}")
    return sorted(packages)


def package_dir() -> dict[str, str]:
    """``[tool.setuptools] package-dir`` of ``pyproject.toml``: import name -> folder."""
    return tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-dir"]


if __name__ == "__main__":  # setuptools' build backend runs this file as __main__
    setup(packages=mapped_packages(package_dir()))
