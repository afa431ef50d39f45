"""The stored row: its schema, defined once, and reading run files checked against it.

A run stores one row per evaluation point in ``<out>/runs/<run_id>.jsonl``, one JSON object a
line. :class:`StoredRow` is the row's schema: every field with its type and a sentence on
what it means. The runner (:mod:`planshape.harness.runner`) builds rows of that type, the
loader checks them against it, and the typed columns (:data:`INT_COLUMNS`,
:data:`FLOAT_COLUMNS`, ...) and the README's table of fields (:func:`schema_markdown`) are
derived from it, so neither can drift from the schema.

* :func:`validate_row` — one row checked, with numbers as ``int``/``float`` (``null`` metrics as
  NaN);
* :func:`read_run` — one run file, checked to be a whole run;
* :func:`load_rows` — every run file of a results folder.

Example:
    >>> COLUMNS[:3], INT_COLUMNS
    (('run_id', 'task', 'entry'), ('seed', 'step', 'budget', 'eval_episodes'))
    >>> "eval_protocol" in COLUMNS, "eval_protocol" in OPTIONAL_COLUMNS
    (False, True)
    >>> print(schema_markdown().splitlines()[2])
    | `run_id` | text | the run's id: a content hash of what determines its numbers; the run's file is `runs/<run_id>.jsonl` |
"""  # noqa: E501

import json
import math
import types
import typing
from collections.abc import Mapping
from pathlib import Path
from typing import Annotated, Any, Literal, NotRequired, TypedDict

from planshape.errors import ResultsError

__all__ = [
    "COLUMNS",
    "FIELDS",
    "FLOAT_COLUMNS",
    "INT_COLUMNS",
    "INVARIANCE_VERDICTS",
    "OPTIONAL_COLUMNS",
    "STR_COLUMNS",
    "Field",
    "Row",
    "StoredRow",
    "eval_protocol",
    "evaluation_text",
    "load_rows",
    "read_run",
    "schema_markdown",
    "validate_row",
]

Row = Mapping[str, Any]

#: the verdicts of the invariance check a row may carry
Invariance = Literal["preserved", "violated", "not-checked", "not-applicable"]


class StoredRow(TypedDict):
    """One evaluation point of one training run, as stored (JSON ``null`` floats read as NaN)."""

    run_id: Annotated[
        str,
        "the run's id: a content hash of what determines its numbers; the run's file is "
        "`runs/<run_id>.jsonl`",
    ]
    task: Annotated[str, "the task's gymnasium id, e.g. `planshape/Reach-v1`"]
    entry: Annotated[str, "the reward: `sparse`, `dense`, or a shaped entry `<potential>/<model>`"]
    potential: Annotated[
        str | None, "the potential family of a shaped entry; null for sparse and dense"
    ]
    model: Annotated[
        str | None,
        "the abstraction model of a shaped entry (e.g. `grid`); null for sparse and dense",
    ]
    algo: Annotated[
        str,
        "the learner, which names its backend: `PPO`, `SAC`, `SAC-default` (stable-baselines3), "
        "`SBX-PPO`, `SBX-SAC`, `SBX-TQC`, `SBX-CrossQ` (SBX)",
    ]
    seed: Annotated[int, "the training seed"]
    step: Annotated[int, "environment steps trained when this point was evaluated"]
    budget: Annotated[int, "environment steps of the whole run (positive)"]
    final: Annotated[
        bool, "whether this is the run's final evaluation point (exactly its last row)"
    ]
    success_rate: Annotated[
        float, "the fraction of evaluation episodes that end in the task's success"
    ]
    final_distance: Annotated[float, "the mean distance to the goal at the episodes' end (m)"]
    sparse_return: Annotated[float, "the mean undiscounted return under the task's sparse reward"]
    eval_episodes: Annotated[int, "evaluation episodes per point"]
    profile: Annotated[str, "the benchmark profile that ran the run (provenance)"]
    invariance: Annotated[
        Invariance,
        "the invariance check's verdict on the entry's potential "
        "(`not-applicable`: sparse and dense have none)",
    ]
    wall_time_s: Annotated[float, "the run's wall-clock time, training and evaluation (s)"]
    steps_per_s: Annotated[float, "training throughput: environment steps per second of training"]
    code_version: Annotated[
        str, "`git describe` of the code that ran it (`-dirty`: uncommitted changes)"
    ]
    packages: Annotated[dict[str, str], "the versions of the packages that determine the numbers"]
    hyperparameters: Annotated[
        dict[str, Any], "the learner's settings (`planshape.training.hyperparams`)"
    ]
    gamma: Annotated[float, "the discount γ of the learner and of the shaping"]
    eval_protocol: NotRequired[
        Annotated[int, "the evaluation protocol (absent in rows of protocol 1)"]
    ]
    evaluation: NotRequired[Annotated[str, "what one evaluation point measured, in words"]]
    success_any_rate: NotRequired[
        Annotated[
            float,
            "the fraction of evaluation episodes in which the task's success flag is set at some "
            "step, not only at the end (MetaWorld's own protocol); absent in rows stored before "
            "it was recorded",
        ]
    ]
    cpu: NotRequired[
        Annotated[
            str,
            "the CPU the run was trained on and its widest x86 vector extension "
            "(`planshape.harness.machine`; an SBX run's numbers depend on it); absent in rows "
            "stored before it was recorded",
        ]
    ]


class Field(typing.NamedTuple):
    """One field of :class:`StoredRow`: its name, its type (``int``, ``float``, ``str``,
    ``bool``, ``str | None``, a ``Literal`` or a ``dict``), its meaning and whether every
    row has it."""

    name: str
    type: Any
    doc: str
    required: bool


def _field(name: str, hint: Any) -> Field:
    required = typing.get_origin(hint) is not NotRequired
    if not required:
        (hint,) = typing.get_args(hint)
    kind, doc = typing.get_args(hint)
    return Field(name, kind, doc, required)


#: every field of :class:`StoredRow`, in the schema's order
FIELDS: tuple[Field, ...] = tuple(
    _field(name, hint)
    for name, hint in typing.get_type_hints(StoredRow, include_extras=True).items()
)


def _named(*kinds: Any) -> tuple[str, ...]:
    """The required fields whose type is one of ``kinds`` (a ``Literal`` counts as its values')."""

    def kind_of(f: Field) -> Any:
        literal = typing.get_origin(f.type) is Literal
        return type(typing.get_args(f.type)[0]) if literal else f.type

    return tuple(f.name for f in FIELDS if f.required and kind_of(f) in kinds)


#: the fields every row has (a row without one of them is an error); extra fields are kept
COLUMNS: tuple[str, ...] = tuple(f.name for f in FIELDS if f.required)
#: the fields rows carry from some version of the runner on
OPTIONAL_COLUMNS: tuple[str, ...] = tuple(f.name for f in FIELDS if not f.required)
INT_COLUMNS = _named(int)
FLOAT_COLUMNS = _named(float)
STR_COLUMNS = _named(str)
INVARIANCE_VERDICTS: tuple[str, ...] = typing.get_args(Invariance)
_OPTIONAL_FLOATS = tuple(f.name for f in FIELDS if not f.required and f.type is float)


def _type_name(kind: Any) -> str:
    """How the README names a field's JSON type."""
    if typing.get_origin(kind) is Literal:
        return " or ".join(f"`{v}`" for v in typing.get_args(kind))
    if isinstance(kind, types.UnionType):
        return " or ".join("null" if k is type(None) else _type_name(k) for k in kind.__args__)
    if typing.get_origin(kind) is dict:
        return "object"
    names = {int: "integer", float: "number (null: NaN)", str: "text", bool: "true or false"}
    return names[kind]


def schema_markdown() -> str:
    """The README's table of the row's fields (field, type, meaning), from :data:`FIELDS`."""
    lines = ["| Field | Type | Meaning |", "|---|---|---|"]
    for f in FIELDS:
        kind = _type_name(f.type) + ("" if f.required else "; optional")
        lines.append(f"| `{f.name}` | {kind} | {f.doc} |")
    return "\n".join(lines) + "\n"


def eval_protocol(row: Row) -> int:
    """The evaluation protocol of a row (see :mod:`planshape.harness.runner`); rows stored before
    the field existed were made with protocol 1.

    Example:
        >>> eval_protocol({}), eval_protocol({"eval_protocol": 2})
        (1, 2)
    """
    return int(row.get("eval_protocol", 1))


def evaluation_text(row: Row) -> str:
    """What a row's evaluation point measured.

    Example:
        >>> evaluation_text({"eval_episodes": 10})[:27]
        '10 deterministic episodes ('
    """
    if "evaluation" in row:
        return str(row["evaluation"])
    return (
        f"{row['eval_episodes']} deterministic episodes (protocol 1: recorded at the callback's "
        "step, for PPO before that rollout's update)"
    )


# --------------------------------------------------------------------------------------------
# Checking rows
# --------------------------------------------------------------------------------------------


class _RowProblem(ValueError):
    """Why a row is unusable; the caller adds where the row came from."""


def _integer(column: str, value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, int | float) or value != int(value):
        raise _RowProblem(f"column {column!r} must be an integer, got {value!r}")
    return int(value)


def _number(column: str, value: Any) -> float:
    if value is None:
        return math.nan
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise _RowProblem(f"column {column!r} must be a number, got {value!r}")
    return float(value)


def _checked(row: Any) -> dict[str, Any]:
    if not isinstance(row, Mapping):
        raise _RowProblem(f"a result row must be a JSON object, got {type(row).__name__}")
    missing = [c for c in COLUMNS if c not in row]
    if missing:
        raise _RowProblem(
            f"missing columns {', '.join(missing)}; rows written by an older planshape? "
            "Re-run those runs (delete their files under runs/)"
        )
    out = dict(row)
    out |= {column: _integer(column, out[column]) for column in INT_COLUMNS}
    out |= {column: _number(column, out[column]) for column in FLOAT_COLUMNS}
    out |= {column: _number(column, out[column]) for column in _OPTIONAL_FLOATS if column in out}
    for column in STR_COLUMNS:
        if not isinstance(out[column], str):
            raise _RowProblem(f"column {column!r} must be a string, got {out[column]!r}")
    if not isinstance(out["final"], bool):
        raise _RowProblem(f"column 'final' must be true or false, got {out['final']!r}")
    if out["invariance"] not in INVARIANCE_VERDICTS:
        raise _RowProblem(
            f"invariance {out['invariance']!r} is not one of {', '.join(INVARIANCE_VERDICTS)}"
        )
    if out["budget"] <= 0:
        raise _RowProblem(f"budget must be positive, got {out['budget']}")
    return out


def validate_row(row: Any, where: str = "row") -> dict[str, Any]:
    """Check that ``row`` has every column of :data:`COLUMNS` with a usable type.

    Returns a copy of the row (integers as ``int``, metrics as ``float``, ``null`` metrics as
    NaN); otherwise raises :class:`ResultsError` whose message starts with ``where``.

    Example:
        >>> validate_row({"task": "t"}, "runs/a.jsonl:1")  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        planshape.errors.ResultsError: runs/a.jsonl:1: missing columns run_id, entry, ...
    """
    try:
        return _checked(row)
    except _RowProblem as exc:
        raise ResultsError(f"{where}: {exc}") from None


# --------------------------------------------------------------------------------------------
# Reading run files
# --------------------------------------------------------------------------------------------

_REDO = "move the file out of runs/ (or delete it) and run the benchmark again to retrain it"


def _text(path: Path) -> str:
    try:
        return path.read_bytes().decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ResultsError(
            f"not UTF-8 text (byte {exc.start}): not a result file, or a damaged one; {_REDO}",
            path,
        ) from None
    except OSError as exc:
        raise ResultsError(f"cannot be read ({exc.strerror}); {_REDO}", path) from None


def _parsed(line: str, path: Path, number: int) -> dict[str, Any]:
    try:
        return _checked(json.loads(line))
    except json.JSONDecodeError as exc:
        raise ResultsError(
            f"not a JSON row ({exc.msg}, column {exc.colno}); {_REDO}", path, number
        ) from None
    except _RowProblem as exc:
        raise ResultsError(str(exc), path, number) from None


def _check_follows(rows: list[dict[str, Any]], row: Row, path: Path, number: int) -> None:
    """``row`` may follow ``rows`` in one run file: the same run, and no row after the final."""
    if rows and row["run_id"] != rows[0]["run_id"]:
        raise ResultsError(
            f"the row is of run {row['run_id']!r}, the file's first row of run "
            f"{rows[0]['run_id']!r}; {_REDO}",
            path,
            number,
        )
    if rows and rows[-1]["final"]:
        raise ResultsError(f"a row after the run's final row; {_REDO}", path, number)


def read_run(path: str | Path) -> list[dict[str, Any]]:
    """The rows of one stored run file, checked to be a whole run.

    A run file is finished only if it is UTF-8 JSON Lines, every row has every column of
    :data:`COLUMNS`, every row names the same run, and exactly its last row is
    ``final``: an empty file, or one cut short while it was written, is not a run. Anything
    else raises :class:`ResultsError` naming the file (and the line) and what to do.

    Example:
        >>> import tempfile, pathlib
        >>> path = pathlib.Path(tempfile.mkdtemp()) / "abc.jsonl"
        >>> _ = path.write_text("")
        >>> read_run(path)  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        planshape.errors.ResultsError: .../abc.jsonl: empty: ...
    """
    path = Path(path)
    rows: list[dict[str, Any]] = []
    last_line = 0
    for number, line in enumerate(_text(path).splitlines(), start=1):
        if not line.strip():
            continue
        row = _parsed(line, path, number)
        _check_follows(rows, row, path, number)
        rows.append(row)
        last_line = number
    if not rows:
        raise ResultsError(f"empty: no result rows, so not a finished run; {_REDO}", path)
    if not rows[-1]["final"]:
        raise ResultsError(
            f"truncated: the last row (step {rows[-1]['step']} of a budget of "
            f"{rows[-1]['budget']}) is not the run's final row; {_REDO}",
            path,
            last_line,
        )
    return rows


def load_rows(out_dir: str | Path) -> list[dict[str, Any]]:
    """Every result row under ``<out_dir>/runs/*.jsonl``, by file name, then line.

    Each file is read with :func:`read_run`, so a damaged or unfinished run file raises
    :class:`ResultsError` naming it (and the line; also in its ``file`` and ``line``
    attributes). Temporary files (``.*.tmp``, written while a run is being stored) are ignored.
    A missing ``runs/`` folder is an error; an empty one gives no rows.

    Example:
        >>> import tempfile, pathlib
        >>> out = pathlib.Path(tempfile.mkdtemp()); (out / "runs").mkdir()
        >>> _ = (out / "runs" / "a.jsonl").write_text("{not json\\n")
        >>> load_rows(out)  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        planshape.errors.ResultsError: .../runs/a.jsonl:1: not a JSON row (...); ...
    """
    runs = Path(out_dir) / "runs"
    if not runs.is_dir():
        raise ResultsError(f"no results folder {runs}; run `planshape bench --out {out_dir}` first")
    rows: list[dict[str, Any]] = []
    for path in sorted(runs.glob("*.jsonl")):
        if path.is_file():
            rows += read_run(path)
    return rows
