"""Results as data: every stored evaluation row as one tidy pandas DataFrame.

``load(DIR)`` reads ``DIR/runs/*.jsonl`` through the store's checks
(:func:`planshape.results.rows.load_rows`: a damaged or unfinished run file is an error naming
it) and returns one row per evaluation point, with nested fields flattened into dotted columns
(``hyperparameters.learning_rate``, ``packages.torch``) and typed columns: integers for ``seed``,
``step``, ``budget``, ``eval_episodes``; floats for the metrics; strings for ids; ``final`` a
boolean. Lists (``hyperparameters.policy_kwargs.net_arch``) are kept as JSON text, so the frame
writes to CSV and Parquet unchanged. ``planshape export DIR --to FILE`` writes it.

The aggregation works on the frame as on the stored rows: :func:`planshape.results.cells.
summarize` and :func:`~planshape.results.cells.aggregate` take either, and :func:`records`
turns a frame (all of it, or a selection of its rows) back into the rows it was made from.

Example:
    >>> frame = load("leaderboard/default-v0", final_only=True)  # doctest: +SKIP
    >>> frame.groupby(["task", "algo", "entry"])["success_rate"].mean()  # doctest: +SKIP
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from planshape.commands import Handler, subcommand
from planshape.errors import BadInputError
from planshape.results import rows as schema

__all__ = ["FLOAT_COLUMNS", "INT_COLUMNS", "export", "load", "records"]

#: the typed columns of a row (:data:`planshape.results.rows.FIELDS` of type ``int`` and
#: ``float``; optional ones too: the evaluation protocol, which rows carry from protocol 2 on,
#: and success at any step)
INT_COLUMNS = tuple(f.name for f in schema.FIELDS if f.type is int)
FLOAT_COLUMNS = tuple(f.name for f in schema.FIELDS if f.type is float)
#: the columns a frame starts with, in this order (the rest follow, sorted)
LEADING = ("run_id", "profile", "task", "entry", "algo", "potential", "model", "seed", "step")


def load(out_dir: str | Path, *, final_only: bool = False) -> Any:
    """The stored rows of ``out_dir`` as a DataFrame (one row per evaluation point, or with
    ``final_only`` each run's final point), sorted by run and step."""
    import pandas as pd

    rows = schema.load_rows(out_dir)
    if final_only:
        rows = [r for r in rows if r["final"]]
    flat = [_flatten(row) for row in rows]
    frame = pd.DataFrame.from_records(flat) if flat else pd.DataFrame(columns=list(LEADING))
    for column in INT_COLUMNS:
        if column in frame:
            frame[column] = pd.array(frame[column], dtype="Int64")
    for column in FLOAT_COLUMNS:
        if column in frame:
            frame[column] = pd.to_numeric(frame[column], errors="coerce").astype("float64")
    if "final" in frame:
        frame["final"] = frame["final"].astype(bool)
    for column in frame.columns:
        if frame[column].dtype == object:
            frame[column] = frame[column].astype("string")
    order = [c for c in LEADING if c in frame] + sorted(c for c in frame if c not in LEADING)
    frame = frame[order]
    if len(frame):
        frame = frame.sort_values(["run_id", "step"], kind="stable").reset_index(drop=True)
    return frame


def records(frame: Any) -> list[dict[str, Any]]:
    """The rows a :func:`load` frame was made from: missing values as ``None``, numbers as
    Python numbers, dotted columns nested again and JSON-text lists decoded.

    Example:
        >>> import pandas as pd
        >>> frame = pd.DataFrame({"seed": pd.array([1], dtype="Int64"),
        ...                       "hyperparameters.policy_kwargs.net_arch": ["[64, 64]"]})
        >>> records(frame)
        [{'seed': 1, 'hyperparameters': {'policy_kwargs': {'net_arch': [64, 64]}}}]
    """
    import pandas as pd

    # a missing text is NaN in pandas' string columns: None there, NaN only in float ones
    numeric = {c for c in frame.columns if pd.api.types.is_float_dtype(frame[c])}
    out = []
    for record in frame.to_dict("records"):
        row: dict[str, Any] = {}
        for name, value in record.items():
            if value is pd.NA or value is None or (name not in numeric and value != value):
                value = None
            elif hasattr(value, "item"):  # a numpy scalar
                value = value.item()
            *parents, leaf = name.split(".")
            if parents and isinstance(value, str) and value.startswith("["):
                value = json.loads(value)
            place = row
            for parent in parents:
                place = place.setdefault(parent, {})
            place[leaf] = value
        out.append(row)
    return out


def _flatten(row: dict[str, Any], prefix: str = "") -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, value in row.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            out.update(_flatten(value, f"{name}."))
        elif isinstance(value, list | tuple):
            out[name] = json.dumps(value)
        else:
            out[name] = value
    return out


def export(out_dir: str | Path, path: str | Path, *, final_only: bool = False) -> int:
    """Write :func:`load`'s frame to ``path`` (``.csv`` or ``.parquet``); return its rows."""
    path = Path(path)
    if path.suffix not in (".csv", ".parquet"):
        raise BadInputError(
            f"--to {path}: write a .csv or a .parquet file (the format follows the suffix)"
        )
    if path.exists() and path.is_dir():
        raise BadInputError(f"--to {path}: is a folder; name a file")
    frame = load(out_dir, final_only=final_only)
    path.parent.mkdir(parents=True, exist_ok=True)
    if path.suffix == ".csv":
        frame.to_csv(path, index=False)
    else:
        frame.to_parquet(path, index=False)
    return len(frame)


@subcommand("export", "write the stored results as one tidy table (CSV or Parquet)")
def _export(parser: argparse.ArgumentParser) -> Handler:
    parser.add_argument("out", type=Path, help="a results folder, e.g. leaderboard/default-v0")
    parser.add_argument("--to", type=Path, required=True, help="FILE.csv or FILE.parquet")
    parser.add_argument("--final-only", action="store_true", help="each run's final point only")
    return _run_export


def _run_export(args: argparse.Namespace) -> int:
    n = export(args.out, args.to, final_only=args.final_only)
    print(f"wrote {n} rows to {args.to}")
    return 0
