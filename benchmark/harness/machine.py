"""The CPU a run was trained on, recorded with its rows.

A run is a pure function of its spec on one machine (rule 6), but not across CPU types: XLA
compiles the SBX learners' updates for the instruction set of the CPU it runs on, and the
last-digit differences this makes grow, over thousands of gradient steps, into a different run
(measured: README, *Across CPU types an SBX run does not re-execute*). PyTorch's learners
re-execute number for number across the CPUs measured. So each row records the CPU's model
name and the widest x86 vector extension it has, the one that decides which code XLA
generates; a run that does not re-execute elsewhere can then be traced to the machine that
made it.

Example:
    >>> cpu_text("AMD EPYC", {"fpu", "sse4_2", "avx", "avx2", "fma"})
    'AMD EPYC (avx2)'
    >>> cpu_text("Intel(R) Xeon(R) Platinum 8481C", {"avx2", "avx512f", "avx512_bf16"})
    'Intel(R) Xeon(R) Platinum 8481C (avx512f)'
    >>> cpu_text("", set())
    'unknown'
"""

from __future__ import annotations

import platform
from functools import cache
from pathlib import Path

__all__ = ["VECTOR_EXTENSIONS", "cpu_description", "cpu_text"]

#: x86 vector extensions from the widest down: the first a CPU has is the one recorded
VECTOR_EXTENSIONS = ("avx512f", "avx2", "avx", "sse4_2")


def cpu_text(model: str, flags: set[str]) -> str:
    """``model`` with the widest of :data:`VECTOR_EXTENSIONS` in ``flags`` (``'unknown'``
    when neither is known)."""
    widest = next((ext for ext in VECTOR_EXTENSIONS if ext in flags), None)
    if not model:
        return widest or "unknown"
    return f"{model} ({widest})" if widest else model


@cache
def cpu_description(cpuinfo: Path = Path("/proc/cpuinfo")) -> str:
    """This machine's CPU as :func:`cpu_text` words it, read from ``cpuinfo`` (Linux); where that
    names no model (no such file, or an ARM CPU's, which has no ``model name``) the platform's
    processor or architecture name."""
    model, flags = "", set()
    try:
        for line in cpuinfo.read_text().splitlines():
            name, _, value = line.partition(":")
            name = name.strip()
            if name == "model name" and not model:
                model = value.strip()
            elif name == "flags" and not flags:
                flags = set(value.split())
    except OSError:
        pass
    return cpu_text(model or platform.processor() or platform.machine(), flags)
