"""The performance figures of the engine and the tasks (``python -m planshape.perf`` runs all).

Each module is a script of its own (``python -m planshape.perf.shaping`` and so on) that prints
figures, measured side by side in one process, and never fails on a missed goal.
"""
