"""button-press-topdown-v3 and button-press-v3: line the gripper up with the button, press it.

``obs[4:7]`` is the button's face (its top for topdown, its front for the wall-mounted one);
the goal is the depth it must be pressed to. Stages: ``(hand-above gripper button)`` →
``(pressed button)`` (topdown), ``(hand-in-front gripper button)`` → ``(pressed button)``.
Thresholds:

* ``hand-above``: the hand is within ``ABOVE_XY`` = 4 cm of the button horizontally and not below
  its top (the topdown expert's own alignment radius);
* ``hand-in-front``: the hand is in front of the button (smaller y) and its x and z are within
  ``FRONT_XZ`` = 3 cm of the button's plus ``FRONT_OFFSET`` = (0, 0, −7) cm (where the front
  expert lines the hand up; it accepts 2 cm);
* ``pressed``: the button's face is within ``TOPDOWN_DEPTH`` = 2.4 cm (height) or
  ``FRONT_DEPTH`` = 2 cm (y) of the goal: MetaWorld's success tests.

Two geometries place ``(hand-above)`` for the plan-distance potentials. ``stages`` places only
the hand's horizontal offset from the button, so its target is not a place where the predicate
holds: the hand starts 11 cm below the button's top, and moved straight towards the button's x
and y it stops 13.6 cm short of it against the button's box, below its top, where no horizontal
move brings it nearer. ``stages-above`` places the hand at ``ABOVE_OFFSET`` = (0, 0, 4.5) cm from
the button's top, where MetaWorld's scripted expert holds it while it presses (hand minus
button (0.00, 0.01, 0.045) m at its success, seeds 0–2), so the predicate holds at the target
and the offset stays put while the button goes down.

Example:
    >>> import numpy as np
    >>> from planshape.tasks.metaworld import observation as o
    >>> obs = np.zeros(o.OBS_DIM); obs[o.HAND] = (0.0, 0.8, 0.35); obs[o.OBJECT] = (0.01, 0.8, 0.3)
    >>> obs[o.GOAL] = (0.0, 0.8, 0.215)
    >>> bool(hand_above(obs, "gripper", "button")), bool(pressed_down(obs, "button"))
    (True, False)
    >>> obs[o.HAND] = obs[o.OBJECT] + ABOVE_OFFSET  # the target of ``stages-above``
    >>> bool(hand_above(obs, "gripper", "button")), hand_to_above_top(obs).tolist()
    (True, [0.0, 0.0, 0.0])
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from planshape.shaping.registration import AbstractModel
from planshape.tasks.common import pddl_file
from planshape.tasks.displacement import DisplacementGeometry
from planshape.tasks.metaworld.observation import distance, goal, hand, main_object

ABOVE_XY = 0.04
FRONT_XZ = 0.03
FRONT_OFFSET = np.array([0.0, 0.0, -0.07])
ABOVE_OFFSET = np.array([0.0, 0.0, 0.045])
TOPDOWN_DEPTH = 0.024
FRONT_DEPTH = 0.02


def hand_above(obs: np.ndarray, _hand: str, _button: str) -> np.ndarray:
    """``(hand-above ?h ?b)``: over the button (within ``ABOVE_XY``) and not below its top."""
    over = distance(hand(obs)[..., :2], main_object(obs)[..., :2]) <= ABOVE_XY
    return over & (hand(obs)[..., 2] >= main_object(obs)[..., 2])


def hand_in_front(obs: np.ndarray, _hand: str, _button: str) -> np.ndarray:
    """``(hand-in-front ?h ?b)``: lined up with the button (x and z within ``FRONT_XZ``) and in
    front of it."""
    offset = hand_to_front(obs)
    lined_up = np.all(np.abs(offset[..., [0, 2]]) <= FRONT_XZ, axis=-1)
    return lined_up & (offset[..., 1] <= 0.0)


def pressed_down(obs: np.ndarray, _button: str) -> np.ndarray:
    """topdown ``(pressed ?b)``: the button's top is within ``TOPDOWN_DEPTH`` of the goal's
    height."""
    return np.abs(button_height_to_goal(obs)[..., 0]) <= TOPDOWN_DEPTH


def pressed_in(obs: np.ndarray, _button: str) -> np.ndarray:
    """front ``(pressed ?b)``: the button's face is within ``FRONT_DEPTH`` of the goal's y."""
    return np.abs(button_depth_to_goal(obs)[..., 0]) <= FRONT_DEPTH


def hand_over_button(obs: np.ndarray) -> np.ndarray:
    """Hand minus button, horizontally."""
    return hand(obs)[..., :2] - main_object(obs)[..., :2]


def hand_to_above_top(obs: np.ndarray) -> np.ndarray:
    """Hand minus the point ``ABOVE_OFFSET`` over the button's top (where the topdown expert
    presses from)."""
    return hand(obs) - (main_object(obs) + ABOVE_OFFSET)


def hand_to_front(obs: np.ndarray) -> np.ndarray:
    """Hand minus the point where the front expert lines the hand up."""
    return hand(obs) - (main_object(obs) + FRONT_OFFSET)


def button_height_to_goal(obs: np.ndarray) -> np.ndarray:
    """The button's height minus the goal's (a 1-vector)."""
    return main_object(obs)[..., 2:] - goal(obs)[..., 2:]


def button_depth_to_goal(obs: np.ndarray) -> np.ndarray:
    """The button face's y minus the goal's (a 1-vector)."""
    return main_object(obs)[..., 1:2] - goal(obs)[..., 1:2]


def topdown_stages() -> AbstractModel:
    """button-press-topdown: move over the button, press it down (the hand placed horizontally
    only)."""
    return _topdown("hand-over-button", hand_over_button, (0.0, 0.0))


def topdown_stages_above() -> AbstractModel:
    """button-press-topdown: move over the button, press it down, the hand placed in three
    dimensions above the button's top (the same PDDL and classifiers as ``stages``)."""
    return _topdown("hand-to-above-top", hand_to_above_top, (0.0, 0.0, 0.0))


def _topdown(
    hand_entity: str, hand_displacement: Callable[[np.ndarray], np.ndarray], at: tuple[float, ...]
) -> AbstractModel:
    """button-press-topdown's model with ``(hand-above)`` placed by ``hand_displacement``."""
    return AbstractModel(
        domain=pddl_file("metaworld", "button-press-topdown", "domain.pddl"),
        problem=pddl_file("metaworld", "button-press-topdown", "stages.pddl"),
        classifiers={"hand-above": hand_above, "pressed": pressed_down},
        geometry=DisplacementGeometry(
            displacements={hand_entity: hand_displacement, "button-to-goal": button_height_to_goal},
            targets={
                "hand-above": (hand_entity, at),
                "pressed": ("button-to-goal", (0.0,)),
            },
        ),
    )


def front_stages() -> AbstractModel:
    """button-press: line up in front of the button, push it in."""
    return AbstractModel(
        domain=pddl_file("metaworld", "button-press", "domain.pddl"),
        problem=pddl_file("metaworld", "button-press", "stages.pddl"),
        classifiers={"hand-in-front": hand_in_front, "pressed": pressed_in},
        geometry=DisplacementGeometry(
            displacements={"hand-to-front": hand_to_front, "button-to-goal": button_depth_to_goal},
            targets={
                "hand-in-front": ("hand-to-front", (0.0, 0.0, 0.0)),
                "pressed": ("button-to-goal", (0.0,)),
            },
        ),
    )
