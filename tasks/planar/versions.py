"""The versions of the planar tasks: which geometry and physics each ``-vN`` id simulates.

Gymnasium's rule applies: a change of behaviour is a new version, and old versions stay
registered so that stored runs stay readable.

=======  =========================================================================
version  what it is
=======  =========================================================================
``v0``   reach without a wall, push with a square box (half side 0.03 m, 0.1 kg)
``v1``   the source paper's tasks as its ``main.py`` ran them: reach behind the wall
         (moves that touch it are undone), push with a cylinder (radius 0.05 m,
         1 kg, friction 0.9), and the paper's subgoal-based dense rewards for reach
         and maze-reach
=======  =========================================================================

Example:
    >>> VERSIONS["v1"].geometry.object_radius, VERSIONS["v0"].geometry.object_radius
    (0.05, None)
    >>> planar_version("v1").physics.box_mass
    1.0
"""

from __future__ import annotations

from dataclasses import dataclass

from planshape.errors import UnknownIdError
from planshape.tasks.planar.geometry import GEOMETRY, PAPER_GEOMETRY, PlanarGeometry
from planshape.tasks.planar.model import PAPER_PHYSICS, PHYSICS, PlanarPhysics


@dataclass(frozen=True)
class PlanarVersion:
    """The geometry and physics of one version of the planar tasks."""

    geometry: PlanarGeometry
    physics: PlanarPhysics


VERSIONS: dict[str, PlanarVersion] = {
    "v0": PlanarVersion(GEOMETRY, PHYSICS),
    "v1": PlanarVersion(PAPER_GEOMETRY, PAPER_PHYSICS),
}


def planar_version(name: str) -> PlanarVersion:
    """The version called ``name``; an unknown name lists the known ones."""
    if name not in VERSIONS:
        raise UnknownIdError("planar task version", name, VERSIONS)
    return VERSIONS[name]
