"""The row schema, defined once: the typed columns derive from it, synthetic and stored rows
fit it, and the README documents exactly its fields."""

from __future__ import annotations

import math
import typing
from pathlib import Path

import pytest

from planshape.errors import ResultsError
from planshape.results import frame, rows
from planshape.results.rows import (
    COLUMNS,
    FIELDS,
    FLOAT_COLUMNS,
    INT_COLUMNS,
    OPTIONAL_COLUMNS,
    StoredRow,
    load_rows,
    schema_markdown,
    validate_row,
)
from tests.results.synthetic import make_run

README = Path(__file__).resolve().parents[2] / "README.md"
#: the README subsection that holds :func:`schema_markdown`'s table
SCHEMA_HEADING = "### The row schema"


def test_every_field_has_a_type_and_a_meaning():
    assert [f.name for f in FIELDS] == list(typing.get_type_hints(StoredRow))
    assert all(f.doc and not f.doc.endswith(".") for f in FIELDS)
    assert set(COLUMNS) | set(OPTIONAL_COLUMNS) == set(StoredRow.__annotations__)
    assert set(OPTIONAL_COLUMNS) == StoredRow.__optional_keys__


def test_the_typed_columns_derive_from_the_schema():
    assert INT_COLUMNS == ("seed", "step", "budget", "eval_episodes")
    assert FLOAT_COLUMNS == (
        "success_rate", "final_distance", "sparse_return", "wall_time_s", "steps_per_s", "gamma",
    )  # fmt: skip
    assert (*INT_COLUMNS, "eval_protocol") == frame.INT_COLUMNS  # optional ones typed too
    assert (*FLOAT_COLUMNS, "success_any_rate") == frame.FLOAT_COLUMNS


def test_synthetic_rows_fit_the_schema():
    for row in make_run():
        assert set(COLUMNS) <= set(validate_row(row))


@pytest.mark.parametrize("folder", ["leaderboard", "leaderboard/default-v0"])
def test_stored_rows_have_no_field_outside_the_schema(folder):
    root = README.parent / folder
    assert (root / "runs").is_dir(), f"the committed results of {folder} are missing"
    fields = set(COLUMNS) | set(OPTIONAL_COLUMNS)
    assert {key for row in load_rows(root) for key in row} <= fields


def test_the_schema_table_has_a_line_per_field():
    lines = schema_markdown().splitlines()
    assert len(lines) == 2 + len(FIELDS)
    for line, f in zip(lines[2:], FIELDS, strict=True):
        assert line.startswith(f"| `{f.name}` | ")


def test_the_readme_documents_the_row_schema():
    """The README's section on the row schema holds exactly :func:`schema_markdown`'s table
    (paste ``python -c "from planshape.results.rows import schema_markdown as s;
    print(s())"`` under the heading after changing :class:`StoredRow`)."""
    text = README.read_text(encoding="utf-8")
    assert SCHEMA_HEADING in text, (
        f"README.md has no {SCHEMA_HEADING!r} section; add it with the table of "
        "planshape.results.rows.schema_markdown()"
    )
    section = text.split(SCHEMA_HEADING, 1)[1].split("\n#", 1)[0]
    table = "\n".join(line for line in section.splitlines() if line.startswith("|")) + "\n"
    assert table == schema_markdown(), "README's row schema differs from StoredRow; regenerate it"


def test_the_module_names_its_parts():
    assert {"StoredRow", "validate_row", "read_run", "load_rows"} <= set(rows.__all__)


def test_success_at_any_step_is_optional_and_checked_as_a_number():
    row = make_run()[0]
    assert "success_any_rate" not in validate_row(row)
    assert math.isnan(validate_row({**row, "success_any_rate": None})["success_any_rate"])
    with pytest.raises(ResultsError, match="'success_any_rate' must be a number"):
        validate_row({**row, "success_any_rate": "high"})
