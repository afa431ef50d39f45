"""The layout of MetaWorld v3's 39-dimensional observation, and the points classifiers read.

Checked against ``metaworld/sawyer_xyz_env.py`` (``_get_curr_obs_combined_no_goal`` and
``_get_obs``) for metaworld 3.1.1::

    0:3    hand position (the ``hand`` body, above the fingers)
    3      gripper opening, 1 = open … about 0.3 = closed on nothing (≈ 0.45 on the puck)
    4:7    first object position (the task's main object: puck, door or drawer handle, button)
    7:11   first object quaternion
    11:18  second object position and quaternion; in MetaWorld zero-padded when there is none,
           and a task made with ``observe_tcp=True`` (MetaWorld-reach-v4) writes the fingertip
           centre into 11:14 (see :data:`TCP`)
    18:36  the same 18 numbers one step earlier (frame stacking)
    36:39  goal position (zero in MetaWorld's goal-hidden variants; planshape's tasks make it
           visible, as MetaWorld's MT1 benchmark does)

The fingertip centre, MetaWorld's ``tcp_center`` (the midpoint of the two fingers'
``*EndEffector`` sites), is what MetaWorld's success and ``near_object`` tests measure from. It
is not a function of the other 36 numbers: it hangs 4.5 cm below the hand, but the hand tilts
on its soft weld to the mocap body, which moves it by up to 1.5 cm horizontally, and the
hand's orientation is not observed. :func:`tcp` estimates it as a fixed offset from the hand,
which made reach-v3's ``hand-at`` hold 2–5 steps after MetaWorld's success; so
``MetaWorldTask(observe_tcp=True)`` puts ``tcp_center`` itself into the observation, in the
second object's unused slot, the way it makes the goal visible, and :func:`observed_tcp` reads
it (reach-v4).

Every function here accepts leading batch axes.

Example:
    >>> import numpy as np
    >>> obs = np.zeros(OBS_DIM); obs[HAND] = (0.0, 0.6, 0.2); obs[GOAL] = (0.0, 0.6, 0.155)
    >>> round(float(distance(tcp(obs), goal(obs))), 6)
    0.0
    >>> obs[TCP] = (0.0, 0.6, 0.155); round(float(distance(observed_tcp(obs), goal(obs))), 6)
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
#: MetaWorld's ``tcp_center``, written by :class:`~.env.MetaWorldTask` into the first three
#: numbers of the (unused) second object's slot; ``obs[29:32]`` holds it one step earlier.
TCP = slice(11, 14)
PREVIOUS = slice(18, 36)
GOAL = slice(36, 39)
__all__ = ["distance", "goal", "gripper_opening", "hand", "main_object", "observed_tcp", "tcp"]

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


def observed_tcp(obs: np.ndarray) -> np.ndarray:
    """The fingertip centre, MetaWorld's ``tcp_center``, as a task made with
    ``observe_tcp=True`` observes it: ``obs[..., 11:14]`` (:data:`TCP`)."""
    return obs[..., TCP]


def gripper_opening(obs: np.ndarray) -> np.ndarray:
    """How far apart the fingers are, normalised to [0, 1] (``obs[..., 3]``)."""
    return obs[..., GRIPPER]


def main_object(obs: np.ndarray) -> np.ndarray:
    """The first object's position, ``obs[..., 4:7]``."""
    return obs[..., OBJECT]


def goal(obs: np.ndarray) -> np.ndarray:
    """The goal position, ``obs[..., 36:39]``."""
    return obs[..., GOAL]
