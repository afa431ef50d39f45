"""Learners: the algorithms a run trains, their hyperparameters and the training loop's seams.

* :mod:`~planshape.training.learners` — the algorithm ids and their backends
  (stable-baselines3 with torch, SBX with JAX);
* :mod:`~planshape.training.hyperparams` — one hyperparameter table per algorithm and task
  family, serialised into each run's identity;
* :mod:`~planshape.training.algorithm` — :func:`make_algorithm`, which builds a learner on
  shaped environments and checks that the learner's γ is the shaping γ;
* :mod:`~planshape.training.threads` — the compute threads of a run, fixed so that its
  numbers do not depend on the machine's core count;
* :mod:`~planshape.training.tensorboard_logs` — optional live logs of a run.
"""
