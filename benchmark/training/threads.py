"""The compute threads a training run uses, fixed so that its numbers do not depend on the machine.

PyTorch runs on one thread (``torch.set_num_threads(1)``). JAX (the SBX learners) cannot be
told its thread count: XLA's CPU client sizes its intra-op pool by the CPUs the process may
run on, and ``XLA_FLAGS`` (``--xla_cpu_multi_thread_eigen=false
intra_op_parallelism_threads=1``) does not change that in jax 0.10. The pool's size changes the
numbers: SBX-SAC on MetaWorld-drawer-close, 6,000 steps, ends with different actor parameters
when the process sees one CPU than when it sees two (each setting reproducible bit for bit).
So a benchmark process that is about to load JAX restricts itself to
:data:`XLA_CPU_THREADS` CPUs first (``os.sched_setaffinity``): every stored SBX run was made
on a 2-core machine, where a worker sees exactly two, so two on any machine repeats them, and
a machine with more cores runs its workers on different pairs.

Example:
    >>> cpus_for_xla([0, 1, 2, 3], slot=1)
    [2, 3]
    >>> cpus_for_xla([0, 1], slot=5)
    [0, 1]
"""

from __future__ import annotations

import contextlib
import os
import re
from collections.abc import Sequence

#: the CPUs (and so XLA intra-op threads) a JAX run is given: what every stored SBX run had
XLA_CPU_THREADS = 2


def cpus_for_xla(available: Sequence[int], slot: int, threads: int = XLA_CPU_THREADS) -> list[int]:
    """``threads`` consecutive CPUs of ``available`` for the worker in ``slot`` (wrapping round),
    so that parallel workers on a many-core machine take different CPUs; all of ``available``
    when it has fewer than ``threads``."""
    cpus = sorted(available)
    if len(cpus) <= threads:
        return cpus
    start = (slot * threads) % len(cpus)
    return sorted(cpus[(start + i) % len(cpus)] for i in range(threads))


def worker_slot() -> int:
    """This process's index among the benchmark's parallel workers (pytest-xdist's ``gwN``;
    the process id elsewhere)."""
    match = re.fullmatch(r"gw(\d+)", os.environ.get("PYTEST_XDIST_WORKER", ""))
    return int(match.group(1)) if match else os.getpid()


def fix_compute_threads(backend: str) -> None:
    """Fix the threads of a run of ``backend`` (``"stable-baselines3"`` or ``"sbx"``) before
    it loads: PyTorch on one thread; for JAX, the process on :data:`XLA_CPU_THREADS` CPUs (it
    may widen a narrower affinity, e.g. ``taskset -c 0``, when the system allows). Call it
    before JAX is first used in the process: XLA sizes its pool once. A one-core machine keeps
    its one CPU, and its SBX numbers then differ from the stored runs'."""
    import torch

    torch.set_num_threads(1)
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    if backend != "sbx" or not hasattr(os, "sched_setaffinity"):
        return
    current = sorted(os.sched_getaffinity(0))
    candidates = current if len(current) >= XLA_CPU_THREADS else range(os.cpu_count() or 1)
    with contextlib.suppress(OSError):  # no CPU of the set allowed: keep what the process has
        os.sched_setaffinity(0, cpus_for_xla(candidates, worker_slot()))
