"""faucet-open-v3: put the hand against the faucet's handle, swing the handle round to open.

``obs[4:7]`` is MetaWorld's ``handleStartOpen`` site lowered by 1 cm; MetaWorld's reward and
success measure the point ``HANDLE_END`` = (−4, 0, 3) cm from it (its ``obj``), which the
scripted expert also aims the hand at before it pushes. The goal is where that point ends up
with the faucet open (the faucet's base plus the handle's length along x, 12.5 cm up).
Stages: ``(hand-at gripper handle)`` → ``(open faucet)``. Thresholds
(``sawyer_faucet_open_v3.py`` and its scripted expert):

* ``hand-at``: the hand within ``HAND_AT`` = 4 cm of that point (the expert's hand is
  1.7–4.2 cm from it while the handle swings and 2.2–2.8 cm at success, seeds 0–9; it starts
  at least 24 cm away);
* ``open``: the point within ``OPEN_RADIUS`` = 7 cm of the goal: MetaWorld's success test
  (``target_to_obj <= 0.07``, computed from ``obs[4:7]`` and ``_target_pos``, so the
  classifier holds exactly when ``info["success"]`` does).

MetaWorld's ``obj_to_target`` is that distance, so ``info["distance"]`` needs no entry in
:data:`~.env.DISTANCES`.

Example:
    >>> import numpy as np
    >>> from planshape.tasks.metaworld import observation as o
    >>> obs = np.zeros(o.OBS_DIM)
    >>> obs[o.OBJECT] = (0.16, 0.77, 0.095); obs[o.GOAL] = (0.175, 0.8, 0.125)
    >>> obs[o.HAND] = obs[o.OBJECT] + HANDLE_END
    >>> bool(hand_at(obs, "gripper", "handle")), bool(is_open(obs, "faucet"))
    (True, True)
"""

from __future__ import annotations

import numpy as np

from planshape.shaping.registration import AbstractModel
from planshape.tasks.common import pddl_file
from planshape.tasks.displacement import DisplacementGeometry
from planshape.tasks.metaworld.observation import goal, hand, main_object

HANDLE_END = np.array([-0.04, 0.0, 0.03])
HAND_AT = 0.04
OPEN_RADIUS = 0.07


def handle_end(obs: np.ndarray) -> np.ndarray:
    """The point MetaWorld's success measures: ``obs[4:7]`` plus ``HANDLE_END``."""
    return main_object(obs) + HANDLE_END


def hand_to_handle(obs: np.ndarray) -> np.ndarray:
    """Hand minus the handle's end."""
    return hand(obs) - handle_end(obs)


def handle_to_goal(obs: np.ndarray) -> np.ndarray:
    """The handle's end minus the goal."""
    return handle_end(obs) - goal(obs)


def hand_at(obs: np.ndarray, _hand: str, _handle: str) -> np.ndarray:
    """``(hand-at ?h ?k)``: the hand is within ``HAND_AT`` of the handle's end."""
    return np.linalg.norm(hand_to_handle(obs), axis=-1) <= HAND_AT


def is_open(obs: np.ndarray, _faucet: str) -> np.ndarray:
    """``(open ?f)``: the handle's end is within ``OPEN_RADIUS`` of the goal (MetaWorld's
    success)."""
    return np.linalg.norm(handle_to_goal(obs), axis=-1) <= OPEN_RADIUS


def stages() -> AbstractModel:
    """Reach the handle, swing it open."""
    return AbstractModel(
        domain=pddl_file("metaworld", "faucet-open", "domain.pddl"),
        problem=pddl_file("metaworld", "faucet-open", "stages.pddl"),
        classifiers={"hand-at": hand_at, "open": is_open},
        geometry=DisplacementGeometry(
            displacements={"hand-to-handle": hand_to_handle, "handle-to-goal": handle_to_goal},
            targets={
                "hand-at": ("hand-to-handle", (0.0, 0.0, 0.0)),
                "open": ("handle-to-goal", (0.0, 0.0, 0.0)),
            },
        ),
    )
