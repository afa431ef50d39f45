"""A JAX run's numbers must not depend on how many CPUs its process started with (rule 6:
a run is reproducible from its key and code version, on any machine with two or more cores).

XLA's CPU client sizes its intra-op pool by the process's CPU affinity, and the pool's size
changes float results; :func:`planshape.training.threads.fix_compute_threads` fixes the
affinity before JAX loads.
"""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from planshape.training.threads import XLA_CPU_THREADS, cpus_for_xla, fix_compute_threads

#: a jitted computation whose float result depends on XLA's intra-op pool size (a reduction
#: over 8,192 rows, as in a gradient over a batch), printed as a digest of its bytes
_DIGEST = """
import hashlib, sys
import numpy as np
if sys.argv[1] == "fixed":
    from planshape.training.threads import fix_compute_threads
    fix_compute_threads("sbx")
import jax, jax.numpy as jnp
rng = np.random.default_rng(0)
x = jnp.asarray(rng.standard_normal((8192, 256), dtype=np.float32))
y = jnp.asarray(rng.standard_normal((8192, 256), dtype=np.float32))
f = jax.jit(lambda a, b: (a.T @ b).sum(axis=0) + jnp.tanh(a @ b[:256].T).sum())
print(hashlib.sha256(np.asarray(f(x, y)).tobytes()).hexdigest())
"""

needs_two_cpus = pytest.mark.skipif(
    not hasattr(os, "sched_setaffinity") or len(os.sched_getaffinity(0)) < XLA_CPU_THREADS,
    reason=f"needs {XLA_CPU_THREADS} CPUs and sched_setaffinity",
)


def _digest(mode: str, cpus: set[int]) -> str:
    """The computation's digest in a fresh process started on ``cpus``."""
    done = subprocess.run(
        [sys.executable, "-c", _DIGEST, mode],
        preexec_fn=lambda: os.sched_setaffinity(0, cpus),
        env={**os.environ, "JAX_PLATFORMS": "cpu"},
        capture_output=True,
        text=True,
        timeout=300,
        check=True,
    )
    return done.stdout.strip()


@needs_two_cpus
def test_a_jax_result_is_the_same_whether_the_process_started_on_one_cpu_or_two():
    two = set(sorted(os.sched_getaffinity(0))[:XLA_CPU_THREADS])
    one = {min(two)}
    # the premise: left alone, XLA computes different bits on one CPU than on two
    assert _digest("free", one) != _digest("free", two)
    # fixed before JAX loads, both processes compute on two
    assert _digest("fixed", one) == _digest("fixed", two) == _digest("free", two)


def test_parallel_workers_get_different_cpus_and_a_small_machine_all_of_its():
    assert cpus_for_xla(range(8), slot=0) == [0, 1]
    assert cpus_for_xla(range(8), slot=3) == [6, 7]
    assert cpus_for_xla(range(8), slot=4) == [0, 1]  # wraps round
    assert cpus_for_xla([3, 5, 9], slot=1) == [3, 9]
    assert cpus_for_xla([0, 1], slot=7) == [0, 1]
    assert cpus_for_xla([4], slot=0) == [4]


@needs_two_cpus
def test_a_pytorch_run_leaves_the_affinity_as_it_is():
    before = os.sched_getaffinity(0)
    fix_compute_threads("stable-baselines3")
    assert os.sched_getaffinity(0) == before
