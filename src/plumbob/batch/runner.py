"""A batch from start to end: find the files, keep what a previous run finished, send
the rest to the local pool or a Dask cluster, write each row as it comes, and put the
table in input order at the end."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any

from ..arguments import count
from ..errors import ArgumentError
from ..limits import MAX_PARTS
from .columns import Field, flat_names, flatten, pose_fields, result_fields
from .extra import require
from .inputs import discover
from .options import Options
from .progress import Progress, Summary
from .writers import arrow_table, open_writer

__all__ = ["BatchResult", "run", "default_jobs"]

Row = dict[str, Any]


@dataclass
class BatchResult:
    """The rows of a batch (one per file, input order), every pose when asked, and the
    summary. ``to_pandas()``/``to_arrow()`` give the flat table (as the CSV)."""

    rows: list[Row]
    pose_rows: list[Row] = field(default_factory=list)
    summary: Summary = field(default_factory=Summary)
    fields: list[Field] = field(default_factory=list)

    def _table(self, poses: bool) -> tuple[list[Row], list[Field]]:
        return (self.pose_rows, pose_fields()) if poses else (self.rows, self.fields)

    def to_pandas(self, poses: bool = False):
        """A pandas DataFrame of the flat table (``poses=True``: the pose table)."""
        pandas = require("pandas", "a pandas table")
        rows, fields = self._table(poses)
        return pandas.DataFrame([flatten(r, fields) for r in rows], columns=flat_names(fields))

    def to_arrow(self, poses: bool = False):
        """A pyarrow Table of the flat table (``poses=True``: the pose table)."""
        return arrow_table(*self._table(poses))


def default_jobs() -> int:
    """Every core this process may use."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def _same_file(row: Row, by: str) -> bool:
    """Is the file at ``row['path']`` still the one the row measured?"""
    from .rows import file_identity

    path = row.get("path")
    try:
        stat = os.stat(path)
    except (OSError, TypeError):
        return row.get("file_size") is None
    if by == "hash":
        return row.get("file_sha256") == file_identity(path)["file_sha256"]
    return row.get("file_size") == stat.st_size and row.get("file_mtime_ns") == stat.st_mtime_ns


def _normal(row: Row, fields: list[Field]) -> Row:
    return {f.key: row.get(f.key) for f in fields}


def run(inputs, options: Options | None = None, *, out: str | None = None,
        pose_out: str | None = None, jobs: int | None = None,
        threads_per_job: int | None = None, scheduler: Any = None,
        resume: bool = False, resume_by: str = "mtime", progress: bool | None = None,
        **values: Any) -> BatchResult:
    """Measure every file the inputs name; see :mod:`plumbob.batch`."""
    if options is None:
        pose_table = values.pop("pose_table", False) or bool(pose_out)
        options = Options(pose_table=pose_table, **values)
    elif values:
        raise ArgumentError("give options or keyword options, not both")
    if pose_out and not options.pose_table:
        raise ArgumentError("pose_out needs options with pose_table=True")
    if resume_by not in ("mtime", "hash"):
        raise ArgumentError("resume_by is 'mtime' (path, size and time) or 'hash' (content)")
    if isinstance(inputs, (str, bytes, os.PathLike)) or not hasattr(inputs, "__iter__"):
        raise ArgumentError(f"inputs must be a list of files, folders or globs, not {inputs!r}")
    jobs = None if jobs is None else count(jobs, "jobs", MAX_PARTS, minimum=1)
    if threads_per_job is not None:
        threads_per_job = count(threads_per_job, "threads_per_job", MAX_PARTS, minimum=1)
    fields, pfields = result_fields(options), pose_fields()
    writer = open_writer(out, fields) if out else None
    pose_writer = open_writer(pose_out, pfields) if pose_out else None
    outputs = [w.path for w in (writer, pose_writer) if w] + [p for p in (out, pose_out) if p]
    files = discover(inputs, exclude=outputs)

    kept: dict[str, Row] = {}
    kept_poses: list[Row] = []
    if resume and writer:
        previous = writer.read()
        poses_lost = pose_writer is not None and not (
            os.path.exists(pose_writer.path) or os.path.exists(pose_out))
        wanted = set(files)
        if not poses_lost:
            kept = {r["path"]: r for r in previous if r.get("path") in wanted
                    and _same_file(r, resume_by)}
        if pose_writer:
            kept_poses = [r for r in pose_writer.read() if r.get("path") in kept]

    summary = Summary(files=len(files))
    rows: dict[int, Row] = {}
    pose_rows: dict[int, list[Row]] = {}
    tasks = []
    for index, path in enumerate(files):
        if path in kept:
            rows[index] = _normal(kept[path], fields)
            summary.add(rows[index], computed=False)
            pose_rows[index] = [r for r in kept_poses if r["path"] == path]
        else:
            tasks.append((index, path, path))
    for w, start in ((writer, [rows[i] for i in sorted(rows)]),
                     (pose_writer, [r for i in sorted(pose_rows) for r in pose_rows[i]])):
        if w:
            w.start(start)

    import time

    began = time.monotonic()
    try:
        if scheduler is not None:
            from .dask import run_dask

            results = run_dask(tasks, options, scheduler, threads_per_job or 1)
        else:
            from .pool import run_pool

            results = run_pool(tasks, options, jobs or default_jobs(), threads_per_job)
        with Progress(len(tasks), progress) as bar:
            for index, result in results:
                row = _normal(result.row, fields)
                poses_of = [_normal(p, pfields) for p in result.pose_rows]
                if pose_writer:  # poses first: a row on disk means its poses are too
                    for p in poses_of:
                        pose_writer.append(p)
                if writer:
                    writer.append(row)
                rows[index] = row
                pose_rows[index] = poses_of
                summary.add(row)
                bar.advance()
    finally:
        summary.seconds = time.monotonic() - began
        for w in (writer, pose_writer):
            if w:
                w.close()
    ordered = [rows[i] for i in sorted(rows)]
    ordered_poses = [r for i in sorted(pose_rows) for r in pose_rows[i]]
    if writer:
        writer.finish(ordered)
    if pose_writer:
        pose_writer.finish(ordered_poses)
    return BatchResult(ordered, ordered_poses, summary, fields)
