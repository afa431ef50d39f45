"""Scripted oracle controllers of the planar tasks: stateless feedback policies
``oracle(obs, goal=..., geometry=...) -> action`` that solve a task from the paper's start,
and :func:`run_oracle`, which rolls one out and reports when it first succeeded.

They prove that a task is solvable within a horizon and give the horizons in
``RECOMMENDED_HORIZONS``; they also reach and then hold the goal, as the tasks require.

Example:
    >>> from planshape.tasks.planar import ReachEnv
    >>> run = run_oracle(ReachEnv(), max_steps=40)
    >>> run.first_success, run.final_success
    (27, True)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import gymnasium
import numpy as np

from planshape.tasks.planar.geometry import GEOMETRY, Disc, PlanarGeometry, Rect

Oracle = Callable[..., np.ndarray]

# Extra clearance (m) the oracles keep from walls and from the box while going around it.
_CLEARANCE = 0.005
# Largest sideways/forward ratio of a push that the box follows without slipping off.
_MAX_SIDEWAYS = 0.5


def _toward(
    pos: Sequence[float], target: Sequence[float], step: float, keep_direction: bool = True
) -> np.ndarray:
    """The action moving ``pos`` towards ``target``, exact when it is within one step.

    Farther away: with ``keep_direction``, straight at full speed (the largest component at
    ±1); without, each component clipped on its own (a diagonal first, then straight: the
    fewest steps when every axis moves 0.02 per step).
    """
    vx = (float(target[0]) - float(pos[0])) / step
    vy = (float(target[1]) - float(pos[1])) / step
    if keep_direction:
        scale = max(1.0, abs(vx), abs(vy))
        return np.array((vx / scale, vy / scale), dtype=np.float32)
    return np.array((min(max(vx, -1.0), 1.0), min(max(vy, -1.0), 1.0)), dtype=np.float32)


def segment_clear(
    a: Sequence[float], b: Sequence[float], walls: Sequence[Rect], clearance: float
) -> bool:
    """Whether the end effector can go straight from ``a`` to ``b`` clear of ``walls``."""
    points = (_along(a, b, k / 24) for k in range(25))
    return not any(_blocked(p, walls, clearance) for p in points)


def _along(a: Sequence[float], b: Sequence[float], fraction: float) -> tuple[float, float]:
    return (
        float(a[0]) + fraction * (float(b[0]) - float(a[0])),
        float(a[1]) + fraction * (float(b[1]) - float(a[1])),
    )


def reach_oracle(
    obs: np.ndarray,
    goal: Sequence[float] = GEOMETRY.reach_goal,
    geometry: PlanarGeometry = GEOMETRY,
) -> np.ndarray:
    """To the goal in the fewest steps (diagonal, then straight), then hold it.

    With a wall in the way (v1), first to the corner of the wall's nearer end on the goal's
    side (the end that makes the shorter way), then to the goal; every move is cut down to its
    x or y part when it would touch the wall.
    """
    pos = (float(obs[0]), float(obs[1]))
    walls, step = geometry.reach_walls, geometry.step_size
    clear = geometry.ee_radius + _CLEARANCE
    target: Sequence[float] = goal
    blocking = [w for w in walls if not segment_clear(pos, goal, (w,), clear)]
    if blocking:
        wall = blocking[0]
        y = wall.high[1] + clear if goal[1] > wall.center[1] else wall.low[1] - clear
        corners = [(wall.low[0] - clear, y), (wall.high[0] + clear, y)]
        target = min(corners, key=lambda c: math.dist(pos, c) + math.dist(c, goal))
    action = _toward(pos, target, step, keep_direction=False)
    return _avoid_walls(pos, action, walls, geometry) if walls else action


def _blocked(pos: Sequence[float], walls: Sequence[Rect], clearance: float) -> bool:
    return any(wall.distance(pos) < clearance for wall in walls)


def _avoid_walls(
    pos: Sequence[float], action: np.ndarray, walls: Sequence[Rect], geometry: PlanarGeometry
) -> np.ndarray:
    """The action if its move stays clear of the walls, else its x-only or y-only part."""
    clearance = geometry.ee_radius + 0.4 * _CLEARANCE  # less than the waypoints keep
    x, y = float(pos[0]), float(pos[1])
    for candidate in (action, np.array((action[0], 0.0)), np.array((0.0, action[1]))):
        nxt = (x + geometry.step_size * candidate[0], y + geometry.step_size * candidate[1])
        if not _blocked(nxt, walls, clearance):
            return candidate.astype(np.float32)
    return np.zeros(2, dtype=np.float32)


def maze_reach_oracle(
    obs: np.ndarray,
    goal: Sequence[float] = GEOMETRY.maze_goal,
    geometry: PlanarGeometry = GEOMETRY,
) -> np.ndarray:
    """Around the U of walls and in from the top.

    Assumes the geometry's three walls (bottom, left, right) form a U open at the top with the
    goal inside. Waypoints by region: inside the U's channel, straight to the goal; in the
    nearer side corridor or above the walls, over the wall into the channel; anywhere else,
    to that corridor. Every move is checked against the walls and cut down to its x or y part
    when it would touch one.
    """
    bottom, left, right = geometry.maze_walls
    clear = geometry.ee_radius + _CLEARANCE
    step = geometry.step_size
    x, y = float(obs[0]), float(obs[1])
    channel_lo, channel_hi = left.high[0] + clear, right.low[0] - clear
    top = max(left.high[1], right.high[1]) + clear
    corridor_left, corridor_right = left.low[0] - clear, right.high[0] + clear
    nearer_left = abs(x - corridor_left) <= abs(x - corridor_right)
    corridor = corridor_left if nearer_left else corridor_right
    above_channel = (min(max(float(goal[0]), channel_lo), channel_hi), top + 0.005)
    if channel_lo - 0.003 <= x <= channel_hi + 0.003 and y > bottom.high[1]:
        target: Sequence[float] = goal
    elif y >= top - 0.003 or abs(x - corridor) < 0.003:
        # Above the walls, or up the corridor: head for the channel over the wall; near the
        # wall's top the wall check below turns the diagonal into a straight climb.
        target = above_channel
    else:
        target = (corridor, top + 0.005)
    action = _toward((x, y), target, step, keep_direction=False)
    return _avoid_walls((x, y), action, geometry.maze_walls, geometry)


def push_oracle(
    obs: np.ndarray,
    goal: Sequence[float] = GEOMETRY.box_goal,
    geometry: PlanarGeometry = GEOMETRY,
) -> np.ndarray:
    """The push oracle of the geometry's object: :func:`push_cylinder_oracle` for the paper's
    cylinder (v1), :func:`push_box_oracle` for the square box (v0)."""
    if geometry.object_radius is not None:
        return push_cylinder_oracle(obs, goal, geometry)
    return push_box_oracle(obs, goal, geometry)


def push_cylinder_oracle(
    obs: np.ndarray,
    goal: Sequence[float] = GEOMETRY.box_goal,
    geometry: PlanarGeometry = GEOMETRY,
) -> np.ndarray:
    """Get behind the cylinder on the line from the goal through its centre, then push towards
    the goal, steering back onto that line (re-read every step); hold once the object is
    within half the success threshold.

    A sphere pushes a cylinder along the line of their centres, so a push off that line sends
    the object sideways; the steering term moves the end effector back behind the centre.
    Starting elsewhere, the end effector goes around the object, keeping clear of it.
    """
    step, contact = geometry.step_size, geometry.contact_distance
    ee = np.array(obs[:2], dtype=float)
    obj = np.array(obs[2:4], dtype=float)
    error = np.asarray(goal, dtype=float) - obj
    gap = float(np.hypot(*error))
    if gap < 0.5 * geometry.success_threshold:
        return np.zeros(2, dtype=np.float32)
    u = error / gap
    normal = np.array([-u[1], u[0]])
    rel = ee - obj
    along, across = float(rel @ u), float(rel @ normal)
    if along < -0.5 * contact and abs(across) < 0.012:  # behind the object: push
        push = u + normal * (-across / step) * 0.8 + u * min(0.0, -(along + contact)) / step
        return (push / max(1.0, float(np.abs(push).max()))).astype(np.float32)
    behind = obj - (contact + 0.01) * u
    if along < -0.5 * contact:  # behind but off the line: slide sideways onto it
        return _toward(ee, behind, step, keep_direction=True)
    # beside or in front: go around, on the side the end effector is on
    side = 1.0 if across >= 0 else -1.0
    around = contact + 0.02
    waypoint = obj + side * around * normal - around * u * (1.0 if along < 0.5 * contact else 0.0)
    return _toward(ee, waypoint, step, keep_direction=True)


def push_box_oracle(
    obs: np.ndarray,
    goal: Sequence[float] = GEOMETRY.box_goal,
    geometry: PlanarGeometry = GEOMETRY,
) -> np.ndarray:
    """Get to the middle of the box face that looks away from the goal, then push towards the
    goal at full speed; hold once the box is within half the success threshold.

    The box translates without rotating and sticks to the end effector by friction, so it
    follows the end effector's motion even when that is not normal to the face, up to a
    sideways/forward ratio of 0.5: the push needs no aiming, only a direction, re-read from the
    box position every step. The pushed face is the one whose normal is closest to the goal
    direction, kept while the goal stays within a ratio of 2 of its normal (so that a push
    near 45° does not flip between faces). Starting beside or in front of the box, the end
    effector first goes around it.
    """
    step, r, h = geometry.step_size, geometry.ee_radius, geometry.box_half_size
    ee = (float(obs[0]), float(obs[1]))
    box = (float(obs[2]), float(obs[3]))
    error = (float(goal[0]) - box[0], float(goal[1]) - box[1])
    if math.hypot(*error) < 0.5 * geometry.success_threshold:
        return np.zeros(2, dtype=np.float32)
    contact = h + r  # centre-to-centre distance along the normal when the sphere touches a face

    def pushing_face(axis: int) -> bool:
        """Whether the end effector is at the middle of the face pushing along ``axis``."""
        depth = (box[axis] - ee[axis]) * math.copysign(1.0, error[axis])
        return (
            contact - 0.01 <= depth <= contact + 0.015
            and abs(ee[1 - axis] - box[1 - axis]) <= h - _CLEARANCE
        )

    # k: the axis pushed along; j: the other one.
    for k in (0, 1):
        j = 1 - k
        if pushing_face(k) and abs(error[k]) >= 0.5 * abs(error[j]):
            push = [0.0, 0.0]
            push[k] = math.copysign(1.0, error[k])
            ratio = error[j] / abs(error[k])
            push[j] = min(max(ratio, -_MAX_SIDEWAYS), _MAX_SIDEWAYS)
            return np.array(push, dtype=np.float32)

    k = 0 if abs(error[0]) >= abs(error[1]) else 1
    j = 1 - k
    sign = math.copysign(1.0, error[k])
    depth = (box[k] - ee[k]) * sign  # how far behind the box centre the end effector is, along k
    offset = ee[j] - box[j]
    behind = [0.0, 0.0]
    behind[k] = box[k] - sign * (contact + 0.01)
    behind[j] = box[j]
    if depth >= contact - 0.01:  # behind the face (or on it, off centre): to its middle
        return _toward(ee, behind, step, keep_direction=False)
    around = h + r + 0.01
    target = [0.0, 0.0]
    if abs(offset) >= around - _CLEARANCE:  # beside the box: back off along k
        target[k], target[j] = behind[k], ee[j]
    else:  # in front of the box: step aside along j
        target[k], target[j] = ee[k], box[j] + (around if offset >= 0 else -around)
    return _toward(ee, target, step, keep_direction=False)


ORACLES: dict[str, Oracle] = {
    "reach": reach_oracle,
    "push": push_oracle,
    "maze-reach": maze_reach_oracle,
}
"""The oracle of each planar task, by the environment's ``task`` name."""


@dataclass(frozen=True)
class OracleRun:
    """What one oracle rollout did.

    Attributes:
        first_success: the step (1-based) at which ``info["success"]`` first held, or None.
        steps: steps taken.
        final_success: ``info["success"]`` at the last step.
        final_distance: ``info["distance"]`` at the last step.
        observations: every observation, the reset one first.
    """

    first_success: int | None
    steps: int
    final_success: bool
    final_distance: float
    observations: tuple[np.ndarray, ...]


def run_oracle(
    env: gymnasium.Env,
    max_steps: int,
    *,
    seed: int | None = None,
    options: dict[str, Any] | None = None,
) -> OracleRun:
    """Reset ``env`` (a planar environment, wrapped or not) and run its task's oracle for
    ``max_steps`` steps or until the episode is truncated."""
    obs, info = env.reset(seed=seed, options=options)
    base = env.unwrapped
    policy = ORACLES[base.task]
    goal, geometry = base.goal, base.geometry
    observations = [obs]
    first: int | None = 0 if info["success"] else None
    steps = 0
    for steps in range(1, max_steps + 1):
        obs, _, terminated, truncated, info = env.step(policy(obs, goal=goal, geometry=geometry))
        observations.append(obs)
        if first is None and info["success"]:
            first = steps
        if terminated or truncated:
            break
    return OracleRun(
        first, steps, bool(info["success"]), float(info["distance"]), tuple(observations)
    )


def route(
    start: Sequence[float],
    target: Sequence[float],
    walls: Sequence[Rect],
    clearance: float,
    workspace: Rect,
    pitch: float = 0.01,
) -> list[tuple[float, float]]:
    """Waypoints from ``start`` to ``target`` (the last one) along which the end effector stays
    ``clearance`` from every wall: ``[target]`` when the straight segment is clear, else the
    shortest 8-connected path on a lattice of ``pitch`` anchored at ``start``, shortened to the
    points where it turns (breadth-first search; the workspace has a few thousand lattice
    points).

    Example:
        >>> wall = Rect.from_center((0.5, 0.0), (0.01, 0.1))
        >>> way = route((0.4, 0.0), (0.6, 0.0), [wall], 0.02, Rect((0.2, -0.3), (0.8, 0.3)))
        >>> len(way) > 1 and way[-1] == (0.6, 0.0)
        True
    """
    goal = (float(target[0]), float(target[1]))
    if segment_clear(start, goal, walls, clearance):
        return [goal]
    x0, y0 = float(start[0]), float(start[1])

    def point(node: tuple[int, int]) -> tuple[float, float]:
        return (x0 + pitch * node[0], y0 + pitch * node[1])

    def free(node: tuple[int, int]) -> bool:
        p = point(node)
        # a millimetre inside the workspace: a move onto its bound may round to just outside
        return workspace.contains(p, margin=-0.001) and not _blocked(p, walls, clearance)

    origin = (0, 0)
    parent: dict[tuple[int, int], tuple[int, int] | None] = {origin: None}
    frontier, end = [origin], None
    while frontier and end is None:
        following = []
        for node in frontier:
            if segment_clear(point(node), goal, walls, clearance):
                end = node
                break
            for dx in (-1, 0, 1):
                for dy in (-1, 0, 1):
                    nxt = (node[0] + dx, node[1] + dy)
                    if nxt not in parent and free(nxt):
                        mid = _along(point(node), point(nxt), 0.5)
                        if not _blocked(mid, walls, clearance):
                            parent[nxt] = node
                            following.append(nxt)
        frontier = following
    if end is None:
        return [goal]  # no way around: head straight (the walls will stop the end effector)
    path: list[tuple[int, int]] = []
    node: tuple[int, int] | None = end
    while node is not None:
        path.append(node)
        node = parent[node]
    points = [point(n) for n in reversed(path)] + [goal]
    # keep only the points where the path must turn (string pulling)
    kept, i = [], 0
    while i < len(points) - 1:
        j = len(points) - 1
        while j > i + 1 and not segment_clear(points[i], points[j], walls, clearance):
            j -= 1
        kept.append(points[j])
        i = j
    return kept


def walk_plan(
    env: gymnasium.Env,
    max_steps: int,
    *,
    seed: int | None = 0,
    options: dict[str, Any] | None = None,
) -> tuple[list[int], bool]:
    """Walk a shaped planar environment through its plan's subgoal locations, in order.

    ``env`` must be shaped (``reward="shaped"``): for each subgoal of the plan in turn, the
    controller asks the task's ``locate`` hook where the end effector must be and heads there
    until it is within a millimetre: straight when the subgoal moves the box (a push), else by
    the shortest way (:func:`route`) around the walls and the box.

    ``seed`` and ``options`` go to ``reset`` (e.g. ``{"instance": k}``). Returns the shaping
    wrapper's progress after every step and whether the task's own success held at the end.
    This is the check that a PDDL model and its classifiers agree with the world: the plan,
    executed through the classifiers, must reach the goal.
    """
    obs, info = env.reset(seed=seed, options=options)
    # read after the reset: a task-instance distribution shapes each episode with its own plan
    shaping = env.get_wrapper_attr("progress")
    geometry = env.get_wrapper_attr("geometry")
    base = env.unwrapped
    g = base.geometry
    step, clear = g.step_size, g.ee_radius + 0.002
    progress = [info["progress"]]
    subgoal, waypoints = 1, []
    for _ in range(max_steps):
        target = np.asarray(geometry.locate(shaping.subgoals[subgoal])["ee"], dtype=float)
        here = np.asarray(obs[:2], dtype=float)
        while np.abs(target - here).max() < 1e-3 and subgoal < shaping.final:
            subgoal += 1
            target = np.asarray(geometry.locate(shaping.subgoals[subgoal])["ee"], dtype=float)
            waypoints = []
        if not waypoints:
            # a place on the workspace's bound (the paper's (0.23, 0.15)) is aimed at from a
            # tenth of a millimetre inside: a move onto the bound may round to just outside
            (lx, ly), (hx, hy) = g.workspace.low, g.workspace.high
            target = np.clip(target, (lx + 1e-4, ly + 1e-4), (hx - 1e-4, hy - 1e-4))
            before, after = (geometry.locate(shaping.subgoals[i]) for i in (subgoal - 1, subgoal))
            pushing = "box" in after and not np.array_equal(before.get("box"), after["box"])
            obstacles = list(base.walls)
            if base.has_box and not pushing:  # keep clear of the box (a few mm of slack)
                box = (float(obs[2]), float(obs[3]))
                if g.object_radius is None:
                    half = g.box_half_size - 0.005
                    obstacles.append(Rect.from_center(box, (half, half)))
                else:
                    obstacles.append(Disc(box, g.object_radius - 0.005))
            waypoints = (
                [tuple(target)] if pushing else route(here, target, obstacles, clear, g.workspace)
            )
        while len(waypoints) > 1 and np.abs(np.asarray(waypoints[0]) - here).max() < 1e-3:
            waypoints.pop(0)
        obs, _, terminated, truncated, info = env.step(_toward(here, waypoints[0], step))
        progress.append(info["progress"])
        if terminated or truncated:
            break
    return progress, bool(info["success"])
