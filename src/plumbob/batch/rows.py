"""One file → one row (and its poses): the work every worker does.

Each row kind is built by ONE function from the public library results, with the keys
and values of the single-file command's ``--json`` output: :func:`mass_row`
(``plumbob mass``), :func:`check_row` (``plumbob check``), :func:`poses_row` and
:func:`pose_table_rows` (``plumbob poses``), :func:`inertial_row` (``plumbob mass
--format``). :func:`process_file` runs them for one file and never raises: a file
that cannot be read or measured is a row with ``status`` and a one-line ``reason``.
"""

from __future__ import annotations

import hashlib
import os
import time
import warnings
from dataclasses import dataclass, field
from stat import S_ISREG
from typing import Any

from ..errors import PlumbobError
from .options import Options

__all__ = ["FileResult", "process_file", "read_body", "mass_row", "check_row", "poses_row",
           "pose_table_rows", "inertial_row", "failure", "file_identity", "lost_row"]


@dataclass
class FileResult:
    """What one file gave: its row, its poses (long format, when asked) and the time."""

    row: dict[str, Any]
    pose_rows: list[dict[str, Any]] = field(default_factory=list)
    seconds: float = 0.0


def read_body(path: str, options: Options):
    """The file's :class:`~plumbob.reading.Reading`, with ``--density``/``--material``
    applied to parts that give none, by the library's one reader
    (:func:`plumbob.loading.read`), as the single-file commands read it."""
    from ..loading import read

    return read(path, units=options.units, repair=options.repair, material=options.material,
                density=options.density, spelled="option")


def _plain(values: dict[str, Any]) -> dict[str, Any]:
    from ..results import jsonable

    return jsonable(values)


def mass_row(reading, props) -> dict[str, Any]:
    """The mass columns, equal to the keys of ``plumbob mass FILE --json``."""
    from .columns import MASS_KEYS

    out = props.as_dict(reading.body.kind)
    row = {k: out.get(k) for k in ("kind", *(k.name for k in MASS_KEYS), "notes")}
    from ..bodies.measures import size_keys  # the body's sizes, as plumbob mass gives them

    row.update(size_keys(reading.body, props))
    row["name"] = getattr(reading.body, "name", None) or None
    row["notices"] = list(reading.notices) or None
    return _plain(row)


def check_row(reading, props, options: Options) -> dict[str, Any]:
    """The verdict columns, equal to the keys of ``plumbob check FILE --json`` (``slope``'s
    keys with a ``slope_`` prefix)."""
    from ..results import keyed
    from ..stability import check
    from .columns import CHECK_KEYS, LOAD_KEYS, REQUIRE_KEYS, SLOPE_KEYS

    v = check(reading.body, requirement=options.requirement(reading), props=props)
    row = keyed(v, CHECK_KEYS)
    if v.slope is not None:
        row.update(keyed(v, SLOPE_KEYS))
    if v.required_tilt_deg is not None:
        row.update(keyed(v, REQUIRE_KEYS))
    if v.loaded is not None:
        row.update(keyed(v, LOAD_KEYS))
    if options.standard is not None:
        from ..stability.standards import run_standard

        std = run_standard(reading.body, options.standard, v.requirement.replace(loads=()),
                           extendables=reading.extendables, props=props)
        row["standard_passes"] = std.passes
        for test in std.tests:
            key = f"std_{test.name}"
            row[f"{key}_passes"] = row.get(f"{key}_passes", True) and test.passes
            row[f"{key}_margin"] = min(row.get(f"{key}_margin", float("inf")), test.margin)
    return _plain(row)


def _resting_poses(reading, props, options: Options):
    """The file's poses; a row shows the first only, so only the first gets a rocking
    pose's critical tilt (its rocker swept), unless the pose table shows them all."""
    from ..stability import resting_poses

    return resting_poses(reading.body, g=options.g, props=props,
                         critical_tilts=None if options.pose_table else 1)


def poses_row(result) -> dict[str, Any]:
    """The pose summary columns: how many stable poses, and the most probable one (the
    first of ``poses`` in ``plumbob poses FILE --json``)."""
    from ..results import keyed
    from .columns import POSE_KEYS

    return _plain({"poses": len(result), "poses_method": result.method,
                   **keyed(result.poses[0], POSE_KEYS)})


def pose_table_rows(path: str, name: str | None, result) -> list[dict[str, Any]]:
    """Every pose of one file, most probable first (``pose`` counts from 1, as
    ``plumbob check --pose K``)."""
    from ..results import keyed
    from .columns import POSE_TABLE_KEYS

    return [_plain({"path": path, "name": name, "pose": k, **keyed(p, POSE_TABLE_KEYS)})
            for k, p in enumerate(result.poses, 1)]


def inertial_row(props, formats: tuple[str, ...]) -> dict[str, Any]:
    """The simulator inertial blocks, as ``plumbob mass FILE --format F`` prints them."""
    from ..export.inertial import inertial_xml

    return {f"{fmt}_inertial": inertial_xml(props, fmt) for fmt in formats}


def failure(error: BaseException, status: str | None = None) -> dict[str, Any]:
    """``status`` (``failed`` for refused input, ``error`` for anything unexpected), the
    error's class and its message on one line."""
    if isinstance(error, PlumbobError):
        status, reason = status or "failed", str(error)
    elif isinstance(error, MemoryError):
        status, reason = status or "failed", "too large to measure in memory"
    elif isinstance(error, RuntimeWarning):  # numpy's overflow: as the CLI says it
        status, reason = status or "failed", (
            f"a number left double precision's range ({error}): the file's lengths, "
            "densities or positions are too large or too small to compute with")
    else:
        status, reason = status or "error", f"{type(error).__name__}: {error}"
    return {"status": status, "error": type(error).__name__, "reason": " ".join(reason.split())}


def file_identity(path: str) -> dict[str, Any]:
    """Size, modification time and SHA-256 of the file, by which ``--resume`` knows it."""
    try:
        stat = os.stat(path)
        if not S_ISREG(stat.st_mode):  # a pipe or device: never block on it here
            return {"file_size": None, "file_mtime_ns": None, "file_sha256": None}
        digest = hashlib.sha256()
        with open(path, "rb") as handle:
            while chunk := handle.read(1 << 20):
                digest.update(chunk)
    except OSError:
        return {"file_size": None, "file_mtime_ns": None, "file_sha256": None}
    return {"file_size": stat.st_size, "file_mtime_ns": stat.st_mtime_ns,
            "file_sha256": digest.hexdigest()}


def lost_row(path: str, shown: str, options: Options, status: str, reason: str) -> FileResult:
    """The row of a file whose worker ran out of time or died: the file, and why."""
    row = {"path": shown, "status": status, "units": options.units,
           "error": "Timeout" if status == "timeout" else "WorkerDied", "reason": reason,
           **file_identity(path)}
    return FileResult(row)


def process_file(path: str, options: Options, shown: str | None = None) -> FileResult:
    """Read and measure one file; never raises, never warns: a numpy ``RuntimeWarning``
    (numbers beyond double precision) fails the file's row, as it fails the command, and
    no warning text reaches a worker's standard error.

    path: where this process finds the file; shown: the path the row reports (the one
    the user gave, when ``path`` was made absolute for a remote worker).
    """
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        warnings.simplefilter("error", RuntimeWarning)
        return _process_file(path, options, shown)


def _process_file(path: str, options: Options, shown: str | None) -> FileResult:
    start = time.perf_counter()
    shown = path if shown is None else shown
    row: dict[str, Any] = {"path": shown, "status": "ok", "units": options.units}
    row.update(file_identity(path))
    pose_rows: list[dict[str, Any]] = []
    try:
        reading = read_body(path, options)
        props = reading.body.mass_properties()
        row.update(mass_row(reading, props))
        if options.inertial:
            row.update(inertial_row(props, options.inertial))
    except Exception as error:  # one bad file never stops a batch
        row.update(failure(error))
        reading = None
    # The check and the poses each stand alone: a body that cannot stand on its default
    # down (a flat particle system) still has its mass columns and, maybe, its poses.
    reasons = []
    if reading is not None and options.check:
        try:
            row.update(check_row(reading, props, options))
        except Exception as error:
            reasons.append(("check", failure(error)))
    if reading is not None and options.poses:
        try:
            result = _resting_poses(reading, props, options)
            row.update(poses_row(result))
            if options.pose_table:
                pose_rows = pose_table_rows(shown, row.get("name"), result)
        except Exception as error:
            reasons.append(("poses", failure(error)))
    if reasons:
        row.update(reasons[0][1])
        row["reason"] = "; ".join(f"{step}: {f['reason']}" for step, f in reasons)
    if shown != path and row.get("reason"):
        row["reason"] = row["reason"].replace(path, shown)
    return FileResult(row, pose_rows, time.perf_counter() - start)
