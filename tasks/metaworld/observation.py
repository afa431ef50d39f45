"""The layout of MetaWorld v3's 39-dimensional observation, and the points classifiers read.

Checked against ``metaworld/sawyer_xyz_env.py`` (``_get_curr_obs_combined_no_goal`` and
``_get_obs``) for metaworld 3.1.1::

    0:3    hand position (the ``hand`` body, above the fingers)
    3      gripper opening, 1 = open … about 0.3 = closed on nothing (≈ 0.45 on the puck)
    4:7    first object position (the task's main object: puck, door or drawer handle, button)
    7:11   first object quaternion
    11:18  second object position and quaternion (zero-padded when there is none)
    18:36  the same 18 numbers one step earlier (frame stacking)
    36:39  goal position (zero in MetaWorld's goal-hidden variants; planshape's tasks make it
           visible, as MetaWorld's MT1 benchmark does)

Every function here accepts leading batch axes.

Example:
    >>> import numpy as np
    >>> obs = np.zeros(OBS_DIM); obs[HAND] = (0.0, 0.6, 0.2); obs[GOAL] = (0.0, 0.6, 0.155)
    >>> round(float(distance(tcp(obs), goal(obs))), 6)
    0.0
"""

from __future__ import annotations

import numpy as np

from planshape.tasks.common import distance

OBS_DIM = 39
HAND = slice(0, 3)
GRIPPER = 3
OBJECT = slice(4, 7)
OBJECT_QUAT = slice(7, 11)
PREVIOUS = slice(18, 36)
GOAL = slice(36, 39)
__all__ = ["distance", "goal", "gripper_opening", "hand", "main_object", "tcp"]

#: The fingertip centre (MetaWorld's ``tcp_center``, which its success tests use) relative to
#: the hand position in the observation: 4.5 cm below, within about 1 cm horizontally while
#: the arm moves (measured along the scripted experts' trajectories).
TCP_OFFSET = np.array([0.0, 0.0, -0.045])


def hand(obs: np.ndarray) -> np.ndarray:
    """The hand position, ``obs[..., 0:3]``."""
    return obs[..., HAND]


def tcp(obs: np.ndarray) -> np.ndarray:
    """The fingertip centre, estimated as the hand position plus :data:`TCP_OFFSET`."""
    return obs[..., HAND] + TCP_OFFSET


def gripper_opening(obs: np.ndarray) -> np.ndarray:
    """How far apart the fingers are, normalised to [0, 1] (``obs[..., 3]``)."""
    return obs[..., GRIPPER]


def main_object(obs: np.ndarray) -> np.ndarray:
    """The first object's position, ``obs[..., 4:7]``."""
    return obs[..., OBJECT]


def goal(obs: np.ndarray) -> np.ndarray:
    """The goal position, ``obs[..., 36:39]``."""
    return obs[..., GOAL]
