"""The wheel ships every module: the package list is derived from the source folders
(``setup.py``), and the wheel ``tox`` builds and tests holds every source file.

Under ``tox`` (``package = wheel``) the installed distribution is the built wheel, so the second
test reads its file list; from an editable install there is no wheel to read and it skips.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _setup_module():
    spec = importlib.util.spec_from_file_location("planshape_setup", ROOT / "setup.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)  # defines the helpers; setup() runs only as __main__
    return module


def _source_files() -> dict[str, Path]:
    """Every file of the source tree the wheel must ship, by its path inside the wheel."""
    files: dict[str, Path] = {}
    for name, folder in _setup_module().package_dir().items():
        base = ROOT / folder
        target = Path(*name.split("."))
        for path in base.rglob("*"):
            if path.suffix in {".py", ".pddl"} and "__pycache__" not in path.parts:
                files.setdefault((target / path.relative_to(base)).as_posix(), path)
    return files


def test_the_package_list_is_every_folder_with_an_init():
    setup = _setup_module()
    packages = set(setup.mapped_packages(setup.package_dir()))
    for expected in ("planshape.shaping", "planshape.harness", "planshape.tasks.planar"):
        assert expected in packages
    folders = {
        "planshape." + ".".join(p.parent.relative_to(ROOT / "benchmark").parts)
        for p in (ROOT / "benchmark").rglob("__init__.py")
        if p.parent != ROOT / "benchmark"
    }
    assert folders <= packages


def test_the_installed_wheel_holds_every_source_file():
    # the RECORD next to the imported package (importlib.metadata would find the source tree's
    # planshape.egg-info first when the tests run from the repository root)
    import planshape

    site = Path(planshape.__file__).resolve().parents[1]
    records = sorted(site.glob("planshape-*.dist-info/RECORD"))
    if not records:
        pytest.skip("planshape is imported from the source tree (editable): no wheel to read")
    shipped = {line.split(",", 1)[0] for line in records[0].read_text().splitlines()}
    assert "planshape/cli.py" in shipped
    missing = sorted(set(_source_files()) - shipped)
    assert not missing, f"the wheel lacks {missing}: is a folder missing its __init__.py?"
