"""The MuJoCo model of the planar tasks, built in code from :class:`PlanarGeometry`.

A spherical end effector slides in the x-y plane on two slide joints, driven by two position
servos; an optional object (a square box, or the paper's cylinder) slides (without rotating) on
its own two slide joints, with viscous damping so that it stops within millimetres when it is no
longer pushed; optional walls are static boxes. Gravity is off: nothing moves out of the plane,
so no table is needed.

qpos layout: ``[ee_x, ee_y]`` and, with a box, ``[box_x, box_y]`` after them; because every
body's frame is the world origin, qpos holds world coordinates.

Example:
    >>> import mujoco
    >>> from planshape.tasks.planar.geometry import GEOMETRY
    >>> model = mujoco.MjModel.from_xml_string(planar_mjcf(GEOMETRY, box=True))
    >>> model.nq, model.nu, model.opt.timestep
    (4, 2, 0.00625)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

from planshape.tasks.planar.geometry import PlanarGeometry, Rect


@dataclass(frozen=True)
class PlanarPhysics:
    """Simulation constants, tuned so that one environment step moves the free end effector by
    ``step_size · action`` (to within 0.2 %), pushes the box smoothly without kicking it, and
    stays cheap (8 substeps).

    Attributes:
        timestep: MuJoCo step (s). At 0.01 s the servo drives the sphere several millimetres
            into the box within one substep and the soft contact then launches the box;
            0.00625 s resolves the contact (pushes move the box smoothly) at 8 substeps.
        frame_skip: substeps per environment step (one step lasts 0.05 s).
        ee_mass: mass of the end effector (kg); only the servo's ``kp / mass`` matters.
        servo_omega: natural frequency of the position servo (rad/s): ``kp = m ω²``.
        servo_zeta: damping ratio of the servo: ``kv = 2 ζ m ω``. With the discrete-time
            integration, 1.03 moves the free end effector by 0.02 m ± 0.2 % per unit action
            without overshooting the target (which could leave the workspace).
        box_mass: mass of the box (kg).
        box_frictionloss: dry friction of each box slide joint (N); 0 by default: per-joint
            dry friction is anisotropic (a diagonal push would need as much tangential as
            normal force, and the box would slip off the end effector) and adds constraint
            rows to every substep.
        box_damping: viscous damping of each box slide joint (N·s/m): the box's resistance,
            proportional to its velocity vector, so a diagonal push sticks. The box stops
            within about 2.5 mm (time constant m/c ≈ 17 ms) once nothing pushes it, and
            nothing moves it when nothing touches it.
        box_friction: sliding friction between the end effector and the box: with it the box
            follows the end effector's motion along the face it pushes (the box does not
            rotate). End effector-wall contacts are frictionless (the end effector slides
            along walls instead of sticking).
        wall_height: half-height of walls and box along z (only needs to cover the sphere).
    """

    timestep: float = 0.00625
    frame_skip: int = 8
    ee_mass: float = 0.1
    servo_omega: float = 100.0
    servo_zeta: float = 1.03
    box_mass: float = 0.1
    box_frictionloss: float = 0.0
    box_damping: float = 6.0
    box_friction: float = 1.0
    wall_height: float = 0.05

    @property
    def servo_kp(self) -> float:
        return self.ee_mass * self.servo_omega**2

    @property
    def servo_kv(self) -> float:
        return 2.0 * self.servo_zeta * self.ee_mass * self.servo_omega

    @property
    def control_dt(self) -> float:
        """Duration of one environment step (s)."""
        return self.timestep * self.frame_skip


PHYSICS = PlanarPhysics()
"""The physics of the ``-v0`` planar tasks."""

PAPER_PHYSICS = replace(PHYSICS, ee_mass=1.0, box_mass=1.0, box_damping=60.0, box_friction=0.9)
"""The physics of the ``-v1`` planar tasks: the paper's object mass (1 kg) and friction (0.9).
The end effector's mass and the object's damping are scaled with the object's mass (×10), so
the servo's ``kp / m`` and the object's stopping time ``m / c`` are those of :data:`PHYSICS`:
the end effector moves exactly as in v0, and the object still stops within millimetres."""


def _wall_xml(index: int, wall: Rect, height: float) -> str:
    (cx, cy), (hx, hy) = wall.center, wall.half_extents
    return (
        f'<geom name="wall{index}" type="box" pos="{cx!r} {cy!r} 0" '
        f'size="{hx!r} {hy!r} {height!r}" condim="1" rgba="0.5 0.5 0.5 1"/>'
    )


def planar_mjcf(
    geometry: PlanarGeometry,
    *,
    box: bool = False,
    walls: Sequence[Rect] = (),
    physics: PlanarPhysics = PHYSICS,
) -> str:
    """MJCF text of a planar scene: the end effector, optionally the box and some walls.

    Args:
        geometry: sizes (environments set positions themselves on reset).
        box: add the pushable box.
        walls: static walls that block the end effector (and the box).
        physics: simulation constants.
    """
    p = physics
    # Contacts use the stiffest reference the timestep allows (time constant 2·dt) and a high
    # impedance, so that walls leave only a few millimetres of penetration under the servo.
    solref = f"{2 * p.timestep!r} 1"
    parts = [
        f'<mujoco model="planshape-planar{"-box" if box else ""}{"-walls" if walls else ""}">',
        '  <compiler angle="radian" autolimits="true"/>',
        f'  <option timestep="{p.timestep!r}" gravity="0 0 0" integrator="implicitfast"/>',
        "  <default>",
        f'    <geom solref="{solref}" solimp="0.99 0.99 0.001"/>',
        "  </default>",
        "  <worldbody>",
    ]
    parts += [f"    {_wall_xml(i, w, p.wall_height)}" for i, w in enumerate(walls)]
    parts += [
        '    <body name="ee">',
        '      <joint name="ee_x" type="slide" axis="1 0 0"/>',
        '      <joint name="ee_y" type="slide" axis="0 1 0"/>',
        f'      <geom name="ee" type="sphere" size="{geometry.ee_radius!r}" '
        f'mass="{p.ee_mass!r}" condim="1" friction="0 0 0" rgba="0.2 0.4 0.9 1"/>',
        "    </body>",
    ]
    if box:
        joint = f'damping="{p.box_damping!r}"'
        if p.box_frictionloss > 0:
            joint += f' frictionloss="{p.box_frictionloss!r}"'
        if geometry.object_radius is None:
            h = geometry.box_half_size
            shape = f'type="box" size="{h!r} {h!r} {min(h, p.wall_height)!r}"'
        else:
            shape = f'type="cylinder" size="{geometry.object_radius!r} {p.wall_height!r}"'
        parts += [
            '    <body name="box">',
            f'      <joint name="box_x" type="slide" axis="1 0 0" {joint}/>',
            f'      <joint name="box_y" type="slide" axis="0 1 0" {joint}/>',
            f'      <geom name="box" {shape} '
            f'mass="{p.box_mass!r}" condim="3" friction="{p.box_friction!r} 0.005 0.0001" '
            'rgba="1 0.6 0.6 1"/>',
            "    </body>",
        ]
    parts += [
        "  </worldbody>",
        "  <actuator>",
        f'    <position name="ee_x" joint="ee_x" kp="{p.servo_kp!r}" kv="{p.servo_kv!r}"/>',
        f'    <position name="ee_y" joint="ee_y" kp="{p.servo_kp!r}" kv="{p.servo_kv!r}"/>',
        "  </actuator>",
        "</mujoco>",
    ]
    return "\n".join(parts)
