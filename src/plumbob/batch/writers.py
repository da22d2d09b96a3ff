"""Results files written as the run goes, so an interrupted run loses nothing.

Each writer appends a row the moment its file is done (one ``write`` and a flush per
row), can read back the rows a previous run left (``--resume``) and, at the end,
rewrites the file in input order, so the final table does not depend on which worker
finished first. The rewrite reuses each row's text as it was first written (rows are
not changed once written): the end of a run is the one part no worker shares, and
formatting 4,000 rows again took about 0.4 s of it. JSON Lines and CSV are their own
journal; Parquet cannot be appended to, so rows go to ``OUT.partial.jsonl`` until the
run ends and the Parquet file is written (pyarrow, from the batch extra).
"""

from __future__ import annotations

import csv
import io
import json
import os
from typing import Any

from ..errors import PlumbobError
from .columns import Field, cell_types, flat_names, flatten, parse_cell, unflatten
from .extra import require

__all__ = ["open_writer", "FORMATS", "Writer"]

#: output extension → writer class name
FORMATS = {".jsonl": "jsonl", ".ndjson": "jsonl", ".csv": "csv", ".parquet": "parquet"}

Row = dict[str, Any]


def _replace(path: str, write) -> None:
    """Write a whole file through a temporary one and rename it over ``path`` (atomic)."""
    temporary = f"{path}.tmp"
    with open(temporary, "w", encoding="utf-8", newline="") as handle:
        write(handle)
    os.replace(temporary, path)


def _complete_text(path: str) -> str:
    """The file's text up to its last newline (a row cut off by a kill is dropped)."""
    with open(path, encoding="utf-8", newline="") as handle:
        text = handle.read()
    return text[: text.rfind("\n") + 1]


class Writer:
    """JSON Lines: one row per line, as the single-file command's JSON."""

    #: whether :meth:`finish` writes the rows' texts (else it formats them its own way)
    _keeps_texts = True

    def __init__(self, path: str, fields: list[Field]) -> None:
        self.path = path
        self.fields = fields
        self.keys = [f.key for f in fields]
        self._handle = None
        self._written: dict[int, tuple[Row, str]] = {}  # id(row) -> (row, its text)

    def _mismatch(self) -> PlumbobError:
        return PlumbobError("the rows there were written with other options (other columns); "
                            "use the same options or drop --resume", path=self.path)

    # ---------------------------------------------------------------- reading
    def read(self) -> list[Row]:
        """The complete rows already in the file ([] when there is none)."""
        if not os.path.exists(self.path):
            return []
        rows = [json.loads(line) for line in _complete_text(self.path).splitlines() if line]
        if any(list(r) != self.keys for r in rows):
            raise self._mismatch()
        return rows

    # ---------------------------------------------------------------- writing
    def _text(self, row: Row) -> str:
        return json.dumps({k: row.get(k) for k in self.keys}, ensure_ascii=False,
                          allow_nan=False) + "\n"

    def _head(self) -> str:
        return ""

    def _write_text(self, row: Row) -> str:
        """``row``'s text, remembered for :meth:`finish` (the row is held with it, so its
        ``id`` cannot be reused by another row meanwhile)."""
        text = self._text(row)
        if self._keeps_texts:
            self._written[id(row)] = (row, text)
        return text

    def _final_text(self, row: Row) -> str:
        kept = self._written.get(id(row))
        return kept[1] if kept is not None and kept[0] is row else self._text(row)

    def start(self, rows: list[Row]) -> None:
        """Begin the file with ``rows`` (those kept from a previous run) and open it."""
        _replace(self.path,
                 lambda h: h.write(self._head() + "".join(map(self._write_text, rows))))
        self._handle = open(self.path, "a", encoding="utf-8", newline="")

    def append(self, row: Row) -> None:
        self._handle.write(self._write_text(row))
        self._handle.flush()

    def close(self) -> None:
        if self._handle is not None:
            self._handle.close()
            self._handle = None

    def finish(self, rows: list[Row]) -> None:
        """The final file: every row, in input order."""
        self.close()
        _replace(self.path,
                 lambda h: h.write(self._head() + "".join(map(self._final_text, rows))))
        self._written.clear()


class CsvWriter(Writer):
    """CSV: flat cells (see :mod:`plumbob.batch.columns`), a header fixed by the options."""

    def __init__(self, path: str, fields: list[Field]) -> None:
        super().__init__(path, fields)
        self.names = flat_names(fields)
        self.types = cell_types(fields)

    def _line(self, cells: list[Any]) -> str:
        buffer = io.StringIO()
        csv.writer(buffer, lineterminator="\n").writerow(["" if c is None else c for c in cells])
        return buffer.getvalue()

    def _text(self, row: Row) -> str:
        flat = flatten(row, self.fields)
        return self._line([flat[n] for n in self.names])

    def _head(self) -> str:
        return self._line(self.names)

    def read(self) -> list[Row]:
        if not os.path.exists(self.path):
            return []
        records = list(csv.reader(io.StringIO(_complete_text(self.path), newline="")))
        if not records:
            return []
        if records[0] != self.names:
            raise self._mismatch()
        return [unflatten({n: parse_cell(c, self.types[n]) for n, c in zip(self.names, r)},
                          self.fields) for r in records[1:] if len(r) == len(self.names)]


class ParquetWriter(Writer):
    """Parquet: rows journalled as JSON Lines beside it until :meth:`finish`."""

    _keeps_texts = False  # the journal's lines are not the final file's

    def __init__(self, path: str, fields: list[Field]) -> None:
        require("pyarrow", "writing Parquet")
        super().__init__(f"{path}.partial.jsonl", fields)
        self.target = path

    def read(self) -> list[Row]:
        if os.path.exists(self.path) or not os.path.exists(self.target):
            return super().read()
        table = require("pyarrow.parquet", "reading Parquet").read_table(self.target)
        if table.column_names != flat_names(self.fields):
            raise PlumbobError("the rows there were written with other options (other "
                               "columns); use the same options or drop --resume",
                               path=self.target)
        return [unflatten(r, self.fields) for r in table.to_pylist()]

    def finish(self, rows: list[Row]) -> None:
        self.close()
        pq = require("pyarrow.parquet", "writing Parquet")
        temporary = f"{self.target}.tmp"
        pq.write_table(arrow_table(rows, self.fields), temporary)
        os.replace(temporary, self.target)
        os.remove(self.path)


def arrow_table(rows: list[Row], fields: list[Field]):
    """A pyarrow table of the flat rows with the column types the fields give: floats,
    integers (``poses``, ``file_size``), booleans (``exact``, ``stands``), text, and
    lists of text (``notes``, ``notices``), which a CSV keeps as JSON text."""
    pa = require("pyarrow", "an Arrow table")
    kinds = {"float": pa.float64(), "int": pa.int64(), "bool": pa.bool_(), "str": pa.string(),
             "strings": pa.list_(pa.string())}
    types = {name: f.type for f in fields for name in f.names()}
    schema = pa.schema([(n, kinds[types[n]]) for n in flat_names(fields)])
    lists = [f.key for f in fields if f.type == "strings"]
    flat = [{**flatten(r, fields), **{k: r.get(k) or None for k in lists}} for r in rows]
    return pa.Table.from_pylist(flat, schema=schema)


def open_writer(path: str, fields: list[Field]) -> Writer:
    """The writer for ``path``'s extension (.jsonl, .csv or .parquet)."""
    kind = FORMATS.get(os.path.splitext(path)[1].lower())
    if kind is None:
        raise PlumbobError("the results file must end in .csv, .jsonl or .parquet", path=path)
    return {"jsonl": Writer, "csv": CsvWriter, "parquet": ParquetWriter}[kind](path, fields)
