"""The sweep's output folder: the bodies it evaluates, the rows as they finish, the final tables.

* ``sweep.json`` - what was asked (scene, study, population) and the per-body columns;
* ``bodies.jsonl`` - one body (parameters and SASS overrides) per line, in index order;
* ``rows.partial.csv`` - finished rows **appended as they come** (flushed and synced per chunk), so
  an interrupted sweep keeps every finished row and ``--resume`` evaluates only the rest;
* ``bodies.csv`` (and ``bodies.parquet`` with pyarrow) - the per-body table in index order,
  written atomically once every body is done.

Numbers are written with ``repr`` (shortest round-trip form), so tables from different executors
compare byte for byte.
"""

from __future__ import annotations

import csv
import io
import json
import os
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from jackpy.atomic import atomic_write_bytes, atomic_write_text
from jackpy.errors import JackpyError
from jackpy.population.generate import Body

MANIFEST = "sweep.json"
BODIES = "bodies.jsonl"
PARTIAL = "rows.partial.csv"
TABLE = "bodies.csv"
PARQUET = "bodies.parquet"


class SweepError(JackpyError):
    """An output folder that does not hold the sweep being resumed, or a sweep that cannot run."""

    exit_code = 2


def format_value(v: Any) -> str:
    return repr(float(v)) if isinstance(v, float) else str(v)


def parse_value(column: str, text: str) -> Any:
    if column in ("sex", "label"):
        return text
    if column == "index" or text.lstrip("-").isdigit():
        return int(text)
    return float(text)


class Journal:
    """Reading and writing one sweep's output folder."""

    def __init__(self, folder: str | os.PathLike) -> None:
        self.folder = Path(folder)

    def start(self, manifest: dict[str, Any], bodies: list[Body]) -> None:
        """A new sweep: write the manifest and bodies, and an empty partial table with its header."""
        self.folder.mkdir(parents=True, exist_ok=True)
        atomic_write_text(self.folder / MANIFEST, json.dumps(manifest, indent=1) + "\n")
        atomic_write_text(self.folder / BODIES, "".join(json.dumps(b.to_dict()) + "\n" for b in bodies))
        atomic_write_text(self.folder / PARTIAL, ",".join(manifest["columns"]) + "\n")

    def manifest(self) -> dict[str, Any]:
        path = self.folder / MANIFEST
        if not path.exists():
            raise SweepError(f"{self.folder}: no sweep to resume (no {MANIFEST})")
        return json.loads(path.read_text(encoding="utf-8"))

    def bodies(self) -> list[Body]:
        lines = (self.folder / BODIES).read_text(encoding="utf-8").splitlines()
        return [Body.from_dict(json.loads(line)) for line in lines if line.strip()]

    def finished(self, columns: list[str]) -> dict[int, dict[str, Any]]:
        """Rows already in the partial table (a torn last line, from a kill mid-write, is dropped)."""
        path = self.folder / PARTIAL
        if not path.exists():
            return {}
        rows: dict[int, dict[str, Any]] = {}
        text = path.read_text(encoding="utf-8")
        complete = text if text.endswith("\n") else text[:text.rfind("\n") + 1]
        reader = csv.reader(io.StringIO(complete))
        header = next(reader, None)
        if header != columns:
            raise SweepError(f"{path}: its columns are not this sweep's")
        for fields in reader:
            if len(fields) == len(columns):
                row = {c: parse_value(c, f) for c, f in zip(columns, fields)}
                rows[row["index"]] = row
        if complete != text:  # drop the torn line so appends start on a fresh line
            atomic_write_text(path, complete)
        return rows

    def append(self, columns: list[str], rows: Iterable[dict[str, Any]]) -> None:
        """Append finished rows to the partial table (flushed and synced)."""
        buf = io.StringIO()
        writer = csv.writer(buf, lineterminator="\n")
        for row in rows:
            writer.writerow([format_value(row[c]) for c in columns])
        with open(self.folder / PARTIAL, "a", encoding="utf-8") as f:
            f.write(buf.getvalue())
            f.flush()
            os.fsync(f.fileno())

    def write_table(self, columns: list[str], rows: list[dict[str, Any]]) -> list[Path]:
        """The per-body table in index order (CSV; Parquet too when pyarrow is installed)."""
        buf = io.StringIO()
        writer = csv.writer(buf, lineterminator="\n")
        writer.writerow(columns)
        for row in sorted(rows, key=lambda r: r["index"]):
            writer.writerow([format_value(row[c]) for c in columns])
        atomic_write_text(self.folder / TABLE, buf.getvalue())
        written = [self.folder / TABLE]
        try:
            import pyarrow as pa
            import pyarrow.parquet as pq
        except ImportError:
            return written
        ordered = sorted(rows, key=lambda r: r["index"])
        table = pa.table({c: [r[c] for r in ordered] for c in columns})
        sink = pa.BufferOutputStream()
        pq.write_table(table, sink)
        atomic_write_bytes(self.folder / PARQUET, sink.getvalue().to_pybytes())
        return written + [self.folder / PARQUET]
