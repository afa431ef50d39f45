"""The learners a benchmark run can name: an algorithm id, the library (backend) that
implements it, and the hyperparameter table it shares.

==============  ==================  ==========  ==========================================
algorithm id    backend             class       hyperparameter table
==============  ==================  ==========  ==========================================
``PPO``         stable-baselines3   ``PPO``     ``PPO``
``SAC``         stable-baselines3   ``SAC``     ``SAC``
``SAC-default`` stable-baselines3   ``SAC``     ``SAC-default`` (the library's defaults)
``SBX-PPO``     sbx (JAX)           ``PPO``     ``PPO``
``SBX-SAC``     sbx (JAX)           ``SAC``     ``SAC``
``SBX-TQC``     sbx (JAX)           ``TQC``     ``SAC``
``SBX-CrossQ``  sbx (JAX)           ``CrossQ``  ``SAC``
==============  ==================  ==========  ==========================================

SBX (``sbx-rl``) is stable-baselines3's algorithms in JAX by the same maintainers, with the
same API, VecEnvs and buffers, so :func:`planshape.training.algorithm.make_algorithm` builds either.
An algorithm id names its backend, so a leaderboard cell (task × entry × algorithm) never
mixes them; the backend's version is in every run's provenance.

Example:
    >>> learner("SBX-SAC").backend, learner("SBX-SAC").table
    ('sbx', 'SAC')
    >>> learner("SAC").cls
    'SAC'
"""

from __future__ import annotations

import gc
import importlib
import os
import sys
from dataclasses import dataclass
from typing import Any

from planshape.errors import UnknownIdError

#: the package each backend is distributed as (for provenance)
BACKEND_PACKAGES = {"stable-baselines3": ("stable-baselines3", "torch"), "sbx": ("sbx-rl", "jax")}

#: XLA flags asking for one thread (set before JAX loads). jax 0.10 still sizes its intra-op
#: pool by the CPUs the process may use; :mod:`planshape.training.threads` fixes that number,
#: on which SBX's numbers depend. The flags stay: every stored SBX run was made with them.
XLA_SINGLE_THREAD = "--xla_cpu_multi_thread_eigen=false intra_op_parallelism_threads=1"


@dataclass(frozen=True)
class Learner:
    """One algorithm of one backend.

    Attributes:
        id: the algorithm id in run keys and on the leaderboard.
        backend: ``"stable-baselines3"`` (PyTorch) or ``"sbx"`` (JAX).
        module: the Python module that holds the class.
        cls: the algorithm class's name in ``module``.
        table: the algorithm whose hyperparameter table it uses
        (:mod:`planshape.training.hyperparams`).
    """

    id: str
    backend: str
    module: str
    cls: str
    table: str

    def load(self) -> type:
        """The algorithm class (importing its backend; JAX on one thread)."""
        if self.backend == "sbx":
            os.environ.setdefault("XLA_FLAGS", XLA_SINGLE_THREAD)
            os.environ.setdefault("JAX_PLATFORMS", "cpu")
        return getattr(importlib.import_module(self.module), self.cls)


LEARNERS: dict[str, Learner] = {
    learner.id: learner
    for learner in (
        Learner("PPO", "stable-baselines3", "stable_baselines3", "PPO", "PPO"),
        Learner("SAC", "stable-baselines3", "stable_baselines3", "SAC", "SAC"),
        Learner("SAC-default", "stable-baselines3", "stable_baselines3", "SAC", "SAC-default"),
        Learner("SBX-PPO", "sbx", "sbx", "PPO", "PPO"),
        Learner("SBX-SAC", "sbx", "sbx", "SAC", "SAC"),
        Learner("SBX-TQC", "sbx", "sbx", "TQC", "SAC"),
        Learner("SBX-CrossQ", "sbx", "sbx", "CrossQ", "SAC"),
    )
}


def learner(algo: str) -> Learner:
    """The learner of algorithm id ``algo``; an unknown id lists the known ones."""
    if algo not in LEARNERS:
        raise UnknownIdError("algorithm", algo, LEARNERS)
    return LEARNERS[algo]


def make(algo: str, env: Any, **settings: Any) -> Any:
    """The learner ``algo`` on ``env`` with ``settings``, its γ checked against the shaping's
    (:func:`planshape.training.algorithm.make_algorithm`)."""
    from planshape.training.algorithm import make_algorithm

    return make_algorithm(learner(algo).load(), env, **settings)


def release_compiled() -> None:
    """Free what the learners trained so far in this process compiled.

    JAX keeps every SBX model's compiled functions for the life of the process, and the next
    model compiles its own (its networks are new objects): about 480 memory mappings per
    SBX-SAC run. A process that trains one run after another, as a benchmark worker does,
    reaches the kernel's limit on mappings (``vm.max_map_count``, 65,530) after some 130 runs
    and dies with "LLVM compilation error: Cannot allocate memory". Called after each run, this
    keeps a process's mappings flat; since no compiled function is reused by the next model,
    no run gets slower, and none changes a number (a test trains one run twice around it).
    Without JAX loaded it does nothing.

    Example:
        >>> release_compiled()
    """
    jax = sys.modules.get("jax")
    if jax is not None:
        jax.clear_caches()
        gc.collect()
