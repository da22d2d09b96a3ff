"""The load options every command that checks under loads shares — ``--force``,
``--hang``, ``--push``, ``--press`` — in one place: their text (``FX,FY,FZ@X,Y,Z``,
``M@X,Y,Z``, ``F[@H]``), their declaration and the loads they make
(:func:`plumbob.loads.loads_from_options`, points in the file's own length unit).
"""

from __future__ import annotations

import argparse
import math

from ..reading import Reading
from ..units import length_scale

__all__ = ["force_option", "hang_option", "search_option", "add_load_arguments",
           "option_loads"]


def _numbers(text: str, what: str, dims: tuple[int, ...]) -> list[float]:
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{what}: expected numbers separated by commas, not "
                                         f"{text!r}") from None
    if len(values) not in dims:
        raise argparse.ArgumentTypeError(f"{what}: expected {' or '.join(map(str, dims))} "
                                         f"numbers, not {len(values)} ({text!r})")
    if not all(math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError(f"{what}: expected finite numbers, not {text!r}")
    return values


def _at(text: str, option: str, example: str) -> tuple[str, str]:
    head, sep, tail = text.partition("@")
    if not sep or not head.strip() or not tail.strip():
        raise argparse.ArgumentTypeError(f"expected {example} (an @ before the point), not "
                                         f"{text!r}")
    return head, tail


def force_option(text: str) -> tuple:
    """An argparse type: ``FX,FY,FZ@X,Y,Z`` (``--force``): N at a point (the body's unit)."""
    head, tail = _at(text, "--force", "FX,FY,FZ@X,Y,Z")
    force = _numbers(head, "the force", (2, 3))
    at = _numbers(tail, "the point", (2, 3))
    if len(force) != len(at):
        raise argparse.ArgumentTypeError(f"the force has {len(force)} components but the point "
                                         f"{len(at)} coordinates: {text!r}")
    return ("force", force, at)


def hang_option(text: str) -> tuple:
    """An argparse type: ``M@X,Y,Z`` (``--hang``): kg hung at a point (the body's unit)."""
    head, tail = _at(text, "--hang", "M@X,Y,Z")
    mass = _numbers(head, "the mass", (1,))[0]
    if mass < 0:
        raise argparse.ArgumentTypeError(f"a hung mass must be ≥ 0 kg, not {mass:g}")
    return ("hang", mass, _numbers(tail, "the point", (2, 3)))


def search_option(kind: str, text: str) -> tuple:
    head, sep, tail = text.partition("@")
    force = _numbers(head, "the force", (1,))[0]
    if force < 0:
        raise argparse.ArgumentTypeError(f"a {kind}'s force must be ≥ 0 N, not {force:g}")
    height = _numbers(tail, "the highest point", (1,))[0] if sep else None
    if height is not None and height <= 0:
        raise argparse.ArgumentTypeError(f"a {kind}'s highest point must be above the floor, "
                                         f"not {height:g}")
    return (kind, force, height)


def add_load_arguments(parser: argparse.ArgumentParser) -> None:
    """--force, --hang, --push, --press: applied loads (repeatable), points in the body's
    own length unit (like every coordinate of its file)."""
    group = parser.add_argument_group("applied loads (see docs/loads.md)")
    group.add_argument("--force", type=force_option, action="append", dest="load_options",
                       metavar="FX,FY,FZ@X,Y,Z",
                       help="a force in newtons at a point (in the body's own length unit); "
                            "repeatable")
    group.add_argument("--hang", type=hang_option, action="append", dest="load_options",
                       metavar="M@X,Y,Z", help="a mass in kg hung at a point (pulls along "
                                               "gravity); repeatable")
    group.add_argument("--push", type=lambda t: search_option("push", t), action="append",
                       dest="load_options", metavar="F[@H]",
                       help="a horizontal force of F newtons at the worst point and direction, "
                            "no higher than H (the body's unit)")
    group.add_argument("--press", type=lambda t: search_option("press", t), action="append",
                       dest="load_options", metavar="F[@H]",
                       help="a downward force of F newtons at the worst point of its top, no "
                            "higher than H")


def option_loads(args: argparse.Namespace, reading: Reading) -> tuple:
    """The loads of the options (``--force``, ``--hang``, ``--push``, ``--press``) with the
    spec's ``[[load]]`` tables, points and heights scaled to metres by the body's unit."""
    from ..loads import loads_from_options

    made = loads_from_options(getattr(args, "load_options", None),
                              length_scale(reading.length_unit))
    return tuple(reading.loads) + tuple(made)
