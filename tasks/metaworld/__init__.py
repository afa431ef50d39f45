"""MetaWorld v3 tasks: the environment wrapper, and one module per task with its classifiers,
subgoal geometry and PDDL model factories.

* :mod:`.env` — :class:`~.env.MetaWorldTask`: sparse/dense reward, seeding, ``success`` and
  ``distance`` in ``info``;
* :mod:`.observation` — the 39-dimensional observation's layout;
* :mod:`.geometry` — :class:`~.geometry.DisplacementGeometry`, the ``locate``/``positions``
  hooks for distance potentials;
* :mod:`.reach`, :mod:`.push`, :mod:`.pick_place`, :mod:`.door`, :mod:`.drawer`,
  :mod:`.button`, :mod:`.window`, :mod:`.handle` (handle-press), :mod:`.plate` (plate-slide),
  :mod:`.faucet` (faucet-open) — one task (or a pair) each.

Importing this package does not import MetaWorld; the registrations in
:mod:`planshape.tasks` name entry points as strings.
"""
