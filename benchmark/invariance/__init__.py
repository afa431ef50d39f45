"""Mechanical checks that a shaping keeps the optimal policy, by exact solution of toy MDPs.

``check_potential("plan-based")`` runs a potential on every toy MDP (tabular reach, maze-reach,
push and random MDPs, bound to their PDDL models and classifiers) in every setting the theory
covers, and returns an :class:`InvarianceReport` with one JSON-serializable verdict per MDP and
setting; ``planshape check-invariance`` is its command line.

Modules, one job each: :mod:`~planshape.invariance.mdp` (the tabular MDP type),
:mod:`~planshape.invariance.solve` (value iteration, backward induction),
:mod:`~planshape.invariance.augment` (the (s, max_idx) MDP), :mod:`~planshape.invariance.shaped`
(the wrapper's shaping term per transition), :mod:`~planshape.invariance.settings` (what is
solved and what the theory says), :mod:`~planshape.invariance.verdict` (tolerance, comparison,
results), :mod:`~planshape.invariance.toys` and :mod:`~planshape.tasks.planar.toys` (the toy
MDPs), :mod:`~planshape.invariance.controls` (negative controls that must fail),
:mod:`~planshape.invariance.check` (running it all) and :mod:`~planshape.invariance.command`.

Example:
    >>> from planshape.invariance import check_potential
    >>> check_potential("time-varying", mdps=["random-continuing"]).preserved
    True
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

#: public name -> module; imported on first use, so that ``planshape --help`` (which imports
#: the ``check-invariance`` command) does not load the solvers.
_EXPORTS = {
    "check_potential": "check",
    "check_shaping": "check",
    "TabularMDP": "mdp",
    "DEFAULT_PRESETS": "settings",
    "PRESETS": "settings",
    "Setting": "settings",
    "PotentialBased": "shaped",
    "Shaping": "shaped",
    "Step": "shaped",
    "ToyProblem": "toys",
    "make_toy": "toys",
    "register_toy": "registry",
    "toy_names": "registry",
    "RELATIVE_TOLERANCE": "verdict",
    "Counterexample": "verdict",
    "InvarianceReport": "verdict",
    "MdpVerdict": "verdict",
}

__all__ = [
    "DEFAULT_PRESETS",
    "PRESETS",
    "RELATIVE_TOLERANCE",
    "Counterexample",
    "InvarianceReport",
    "MdpVerdict",
    "PotentialBased",
    "Setting",
    "Shaping",
    "Step",
    "TabularMDP",
    "ToyProblem",
    "check_potential",
    "check_shaping",
    "make_toy",
    "register_toy",
    "toy_names",
]

if TYPE_CHECKING:
    from planshape.invariance.check import check_potential, check_shaping
    from planshape.invariance.mdp import TabularMDP
    from planshape.invariance.registry import register_toy, toy_names
    from planshape.invariance.settings import DEFAULT_PRESETS, PRESETS, Setting
    from planshape.invariance.shaped import PotentialBased, Shaping, Step
    from planshape.invariance.toys import ToyProblem, make_toy
    from planshape.invariance.verdict import (
        RELATIVE_TOLERANCE,
        Counterexample,
        InvarianceReport,
        MdpVerdict,
    )


def __getattr__(name: str) -> Any:
    if name not in _EXPORTS:
        raise AttributeError(f"module 'planshape.invariance' has no attribute {name!r}")
    return getattr(importlib.import_module(f"planshape.invariance.{_EXPORTS[name]}"), name)
