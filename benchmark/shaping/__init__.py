"""The shaped step: from an observation to F = γ·φ(s') − φ(s).

* :mod:`~planshape.shaping.abstraction` — predicates and their classifiers: which atoms of the
  PDDL model hold in an observation;
* :mod:`~planshape.shaping.progress` — the plan progress max_idx: the furthest subgoal of the
  plan reached so far, never decreasing within an episode;
* :mod:`~planshape.shaping.potentials` — the :class:`Potential` extension point, the context it
  sees and the registry of potential ids;
* :mod:`~planshape.shaping.wrapper` — :class:`PotentialShaping`, the ``gymnasium.Wrapper`` that
  computes F from the stored φ(s) and the new φ(s');
* :mod:`~planshape.shaping.registration` — a task's registration (its models, classifiers,
  hooks) and :func:`shape`, which plans with Fast Downward and wraps an environment.
"""
