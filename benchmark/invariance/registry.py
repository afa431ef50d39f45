"""The registry of toy MDPs: name -> ``"module:attr"`` entry point and a one-line description.

Light on purpose (nothing is imported or built here): a task family registers its toys next
to its Gymnasium registrations (:mod:`planshape.tasks`), and :func:`planshape.invariance.toys.
make_toy` builds one when the checker asks for it.

Example:
    >>> register_toy("doc-chain", "planshape.invariance.toys:random_episodic", "a doc example")
    >>> "doc-chain" in toy_names(), toy_description("doc-chain")
    (True, 'a doc example')
    >>> del TOYS["doc-chain"]
"""

from __future__ import annotations

__all__ = ["TOYS", "default_toys", "register_toy", "toy_description", "toy_names"]

#: name -> (entry point, description), in registration order
TOYS: dict[str, tuple[str, str]] = {}


def register_toy(name: str, entry_point: str, description: str = "") -> None:
    """Register a toy: ``entry_point`` (``"module:attr"``) builds its
    :class:`~planshape.invariance.toys.ToyProblem`."""
    TOYS[name] = (entry_point, description)


def toy_names() -> list[str]:
    """The registered toys, in registration order."""
    return list(TOYS)


def default_toys() -> list[str]:
    """The toys :func:`planshape.invariance.check_potential` runs on: all of them."""
    return toy_names()


def toy_description(name: str) -> str:
    """The one-line description a toy was registered with ("" if it is unknown)."""
    return TOYS[name][1] if name in TOYS else ""
