"""The run harness: what a benchmark run is, which runs a profile holds, and where they are kept.

* :mod:`~planshape.harness.runner` — a run's spec and id, training it and evaluating its
  policy on the task's own success;
* :mod:`~planshape.harness.profiles` — the profiles (blocks of tasks × entries × algorithms ×
  seeds at budgets from measured learning curves);
* :mod:`~planshape.harness.store` — one atomic ``runs/<run_id>.jsonl`` per finished run;
* :mod:`~planshape.harness.bench` — ``planshape bench``: run what a profile is missing;
* :mod:`~planshape.harness.estimate` — the wall-time estimate of a selection of runs;
* :mod:`~planshape.harness.probe` — ``planshape probe``: a learning curve, to choose budgets;
* :mod:`~planshape.harness.catalog` — ``planshape tasks``: what is registered.
"""
