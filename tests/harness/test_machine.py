"""The CPU a run records (``planshape.harness.machine``): the model and the widest x86 vector
extension, read from /proc/cpuinfo."""

from __future__ import annotations

from pathlib import Path

from planshape.harness.machine import cpu_description, cpu_text


def test_the_widest_vector_extension_is_named(tmp_path: Path) -> None:
    cpuinfo = tmp_path / "cpuinfo"
    cpuinfo.write_text(
        "processor\t: 0\nmodel name\t: Intel(R) Xeon(R) CPU @ 2.20GHz\n"
        "flags\t\t: fpu sse4_2 avx avx2 avx512f avx512bw\n\n"
        "processor\t: 1\nmodel name\t: Intel(R) Xeon(R) CPU @ 2.20GHz\nflags\t\t: fpu\n"
    )
    assert cpu_description.__wrapped__(cpuinfo) == "Intel(R) Xeon(R) CPU @ 2.20GHz (avx512f)"


def test_a_cpu_without_an_x86_extension_is_named_by_its_model() -> None:
    assert cpu_text("ARMv8 Processor rev 1", {"fp", "asimd"}) == "ARMv8 Processor rev 1"
    assert cpu_text("AMD EPYC", {"sse4_2", "avx"}) == "AMD EPYC (avx)"


def test_an_unreadable_cpuinfo_falls_back_to_the_platform(tmp_path: Path) -> None:
    assert cpu_description.__wrapped__(tmp_path / "missing") != ""


def test_a_cpuinfo_without_a_model_name_falls_back_to_the_platform(tmp_path: Path) -> None:
    cpuinfo = tmp_path / "cpuinfo"
    cpuinfo.write_text("processor\t: 0\nFeatures\t: fp asimd\nCPU implementer\t: 0x41\n")
    assert cpu_description.__wrapped__(cpuinfo) == cpu_description.__wrapped__(tmp_path / "no")
