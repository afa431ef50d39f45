"""A broken submission gets one clear message and exit 2, wherever it is used: a module that
does not import (syntax error, an exception at import, a missing dependency) and a potential
that returns something other than one finite number."""

from __future__ import annotations

import re
import sys
import textwrap

import gymnasium
import numpy as np
import pytest

import planshape  # noqa: F401  (registers the tasks)
from planshape.cli import main
from planshape.errors import BadInputError, PotentialValueError

HEADER = "from planshape.shaping.potentials import Potential\n"
MODULES = {
    "syntax_error": (HEADER + "class P(Potential)\n    pass\n", "syntax_error.py:2: SyntaxError"),
    "raises_on_import": ("x = 1 / 0\n", "raised ZeroDivisionError: division by zero"),
    "missing_dependency": ("import no_such_dependency\n", "imports 'no_such_dependency'"),
}
RETURNS = {
    "nothing": ("None", "returned NoneType None"),
    "text": ("'1.5'", "returned str '1.5'"),
    "vector": ("np.ones(2)", "returned ndarray of shape (2,)"),
    "nan": ("float('nan')", "returned nan"),
}


@pytest.fixture
def submissions(tmp_path, monkeypatch):
    for name, (source, _) in MODULES.items():
        (tmp_path / f"{name}.py").write_text(source)
    lines = [HEADER, "import numpy as np\n"]
    for name, (expression, _) in RETURNS.items():
        lines.append(
            textwrap.dedent(f"""
            class {name.title()}(Potential):
                def potential(self, ctx):
                    return {expression}
            """)
        )
    (tmp_path / "returns.py").write_text("".join(lines))
    monkeypatch.chdir(tmp_path)
    monkeypatch.syspath_prepend(str(tmp_path))
    yield tmp_path
    for name in [*MODULES, "returns"]:
        sys.modules.pop(name, None)


@pytest.mark.parametrize("module", sorted(MODULES))
@pytest.mark.parametrize("command", ["check-invariance", "bench"])
def test_a_module_that_does_not_import_exits_2_naming_it(submissions, capsys, module, command):
    argv = [command, "--potential", f"{module}:P"]
    if command == "bench":
        argv += ["--profile", "smoke", "--out", str(submissions / "out")]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert MODULES[module][1] in err and f"{module}:P" in err, err
    assert "Traceback" not in err
    assert not (submissions / "out").exists()


@pytest.mark.parametrize("name", sorted(RETURNS))
def test_a_potential_returning_no_number_is_named_by_the_checker_and_the_env(
    submissions, capsys, name
):
    reference = f"returns:{name.title()}"
    assert main(["check-invariance", "--potential", reference]) == 2
    err = capsys.readouterr().err
    assert reference in err and RETURNS[name][1] in err and "Traceback" not in err, err
    env = gymnasium.make(
        "planshape/Reach-v1", reward="shaped", potential=reference, model="grid", gamma=0.99
    )
    with pytest.raises(PotentialValueError, match=re.escape(RETURNS[name][1])) as caught:
        env.reset(seed=0)
    assert reference in str(caught.value) and isinstance(caught.value, BadInputError)


def test_numbers_of_any_numeric_type_are_accepted():
    from planshape.shaping.potentials import Potential, ShapingContext

    class Numpy(Potential):
        def potential(self, ctx):
            return np.float32(0.5) if ctx.progress else np.array(0.25)

    ctx = ShapingContext(obs=None, progress=0, t=0, subgoals=(frozenset(),) * 2)
    assert Numpy()(ctx) == 0.25
