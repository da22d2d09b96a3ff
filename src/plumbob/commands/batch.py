"""``plumbob batch INPUT... --out results.csv``: many files, one table.

Only the standard library is imported here; the batch machinery loads when it runs.
"""

from __future__ import annotations

import argparse
import sys

from ..errors import printable
from ..units import SEED_GRAVITY
from ._common import (
    count,
    direction,
    force_option,
    hang_option,
    length_unit,
    material_name,
    non_negative,
    number,
    positive,
    tilt_limit,
)

__all__ = ["register", "run"]

DESCRIPTION = """\
Mass properties (and with --check the verdict as it stands, with --poses the resting
poses) of every file INPUT names: files, folders (searched recursively for the
extensions plumbob reads) and glob patterns. One row per file, written to --out
(.csv, .jsonl or .parquet) as each file finishes; its values are those of 'plumbob
mass/check/poses FILE --json'. A file that cannot be read, measured or finished in
--timeout seconds is a row with its status and a one-line reason; the run goes on.
--resume keeps the rows of files unchanged since an interrupted run. All cores by
default (--jobs), or a Dask cluster (--scheduler). Exit status 0 when every file is
ok, 1 when some file failed (or failed --require-tilt), 2 on bad usage."""


def _formats(text: str) -> tuple[str, ...]:
    from ..batch.options import INERTIAL_FORMATS

    formats = tuple(f.strip().lower() for f in text.split(",") if f.strip())
    bad = [f for f in formats if f not in INERTIAL_FORMATS]
    if bad or not formats:
        raise argparse.ArgumentTypeError(f"expected some of {','.join(INERTIAL_FORMATS)}, "
                                         f"not {text!r}")
    return formats



def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "batch", help="many files: one table of mass properties, verdicts and poses",
        description=DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("inputs", nargs="+", metavar="INPUT", help="files, folders or globs")
    parser.add_argument("--out", required=True, metavar="FILE",
                        help="the results table: .csv, .jsonl or .parquet")
    what = parser.add_argument_group("what to measure")
    what.add_argument("--check", action="store_true",
                      help="the verdict as it stands: verdict, margin, critical tilt")
    what.add_argument("--poses", action="store_true",
                      help="the number of stable poses and the most probable one")
    what.add_argument("--pose-table", metavar="FILE",
                      help="also every pose of every file, one row each (implies --poses)")
    what.add_argument("--inertial", type=_formats, default=(), metavar="urdf,sdf,mjcf",
                      help="add the simulators' inertial blocks as columns")
    body = parser.add_argument_group("options applied to every file")
    density = body.add_mutually_exclusive_group()
    density.add_argument("--density", type=positive, metavar="RHO",
                         help="density in kg/m³ (kg/m² for a lamina) for parts that give none")
    density.add_argument("--material", type=material_name, metavar="NAME",
                         help="a material from 'plumbob materials' for parts that give none")
    body.add_argument("--units", type=length_unit, metavar="UNIT",
                      help="length unit of the files' coordinates: m, cm, mm, km, in or ft, "
                      "any case or spelled out (default: each file's own, else m)")
    body.add_argument("--repair", action="store_true", help="repair small mesh defects")
    body.add_argument("--down", type=direction, metavar="X,Y,Z",
                      help="direction of gravity for --check (default -z; -y for a lamina)")
    body.add_argument("--tilt", type=non_negative, metavar="DEG",
                      help="--check also on a plane tilted DEG degrees")
    body.add_argument("--toward", type=number, metavar="DEG",
                      help="the tilted plane descends toward this direction (default: worst)")
    body.add_argument("--require-tilt", type=tilt_limit, metavar="DEG",
                      help="design check: it must not topple when tilted DEG degrees")
    body.add_argument("--force", type=force_option, action="append", dest="load_options",
                      metavar="FX,FY,FZ@X,Y,Z", help="--check under a force (N) at a point "
                                                      "(in each file's unit); repeatable")
    body.add_argument("--hang", type=hang_option, action="append", dest="load_options",
                      metavar="M@X,Y,Z", help="--check with M kg hung at a point; repeatable")
    body.add_argument("--standard", metavar="NAME",
                      help="a column per test of a standard (docs/standards.md)")
    body.add_argument("--g", type=positive, default=SEED_GRAVITY, metavar="G",
                      help=f"gravitational acceleration, m/s² (default {SEED_GRAVITY})")
    harness = parser.add_argument_group("running")
    harness.add_argument("--timeout", type=_timeout, metavar="S",
                         help="seconds allowed per file (default: no limit)")
    harness.add_argument("--jobs", type=count, metavar="N",
                         help="worker processes (default: every core)")
    harness.add_argument("--threads-per-job", type=count, metavar="N",
                         help="BLAS/OpenMP, manifold3d and plumbob threads in each worker "
                              "(default: 1 with several jobs, whatever the environment says; "
                              "every core with --jobs 1)")
    harness.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                         help="run on this Dask distributed cluster (pip install "
                              "'plumbob[batch]')")
    harness.add_argument("--resume", action="store_true",
                         help="keep the rows --out already holds for unchanged files")
    harness.add_argument("--resume-by", choices=("mtime", "hash"), default="mtime",
                         help="a file is unchanged if its path, size and modification time "
                              "match (mtime, default) or its content hash (hash)")
    harness.add_argument("--quiet", action="store_true", help="no progress bar, no summary")
    parser.set_defaults(func=run)


#: The longest --timeout, s (a week): beyond it a time limit is no limit, and the
#: process pool's clocks overflow.
MAX_TIMEOUT = 7 * 24 * 3600.0


def _timeout(text: str) -> float:
    value = positive(text)
    if value > MAX_TIMEOUT:
        raise argparse.ArgumentTypeError(f"at most {MAX_TIMEOUT:g} s (a week), not {text}; "
                                         "leave --timeout out for no limit")
    return value


def _writable(path: str | None, option: str) -> None:
    """An output's folder must exist: said before any file is measured, not after."""
    import os

    from ..errors import InputFileError

    if path is not None and not os.path.isdir(os.path.dirname(os.path.abspath(path))):
        raise InputFileError(f"cannot write {option} {path}: its folder does not exist")


def run(args: argparse.Namespace) -> int:
    from ..batch import Options
    from ..batch import run as run_batch

    _writable(args.out, "--out")
    _writable(args.pose_table, "--pose-table")

    options = Options(
        units=args.units, material=args.material, density=args.density, repair=args.repair,
        check=args.check, down=args.down, tilt=args.tilt, toward=args.toward,
        require_tilt=args.require_tilt, g=args.g, poses=args.poses or bool(args.pose_table),
        pose_table=bool(args.pose_table), inertial=args.inertial, timeout=args.timeout,
        load_options=tuple(args.load_options or ()), standard=args.standard)
    result = run_batch(args.inputs, options, out=args.out, pose_out=args.pose_table,
                       jobs=args.jobs, threads_per_job=args.threads_per_job,
                       scheduler=args.scheduler, resume=args.resume,
                       resume_by=args.resume_by, progress=False if args.quiet else None)
    if not args.quiet:
        print("\n".join(map(printable, result.summary.text().splitlines())), file=sys.stderr)
    failed = not result.summary.ok or any(r.get("passes") is False for r in result.rows)
    return 1 if failed else 0
