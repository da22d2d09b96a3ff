"""What the commands share: reading the body with the body options, and (re-exported
from their modules) the value types (:mod:`.types`), the shared options (:mod:`.options`),
the load options (:mod:`.loads`) and the JSON output (:mod:`.output`).

Every command module imports from here and from the library, never from another
command module. Only numpy and plumbob's reader load at import; the stability,
energy and dynamics code load when a command runs.
"""

from __future__ import annotations

import argparse
from collections.abc import Mapping
from typing import Any

from ..errors import ArgumentError
from ..loading import read
from ..reading import Reading
from . import loads as _loads
from . import options as _options
from . import output as _output
from . import types as _types
from ._notices import default_down, flush_notices, oriented, print_notices
from .loads import *  # noqa: F403  (re-exported: the commands import them from here)
from .options import *  # noqa: F403
from .options import parameter_overrides
from .output import *  # noqa: F403
from .types import *  # noqa: F403

__all__ = ["load_body", "open_body", "part_materials", "print_notices", "flush_notices", "default_down",
           *_types.__all__, *_options.__all__, *_loads.__all__, *_output.__all__]


def part_materials(given: list[str] | None) -> dict[str, str] | None:
    """``--part-material NAME=MATERIAL`` options as ``{name or glob: material}``, in order."""
    if not given:
        return None
    out: dict[str, str] = {}
    for item in given:
        name, sep, value = item.partition("=")
        if not sep or not name.strip() or not value.strip():
            raise ArgumentError(f"--part-material {item!r}: write NAME=MATERIAL, e.g. "
                                "--part-material 'post*=aluminium'")
        out[name.strip()] = value.strip()
    return out


def load_body(args: argparse.Namespace, *, path: str | None = None,
              parameters: Mapping[str, Any] | None = None) -> Reading:
    """Read ``path`` (default ``args.path``) with the body options of ``args``: ``--units``,
    ``--repair``, ``--set`` (or ``parameters``), ``--density`` / ``--material``,
    ``--part-material``, ``--shell`` / ``--infill``, all applied by
    :func:`plumbob.loading.read`."""
    if parameters is None:
        parameters = parameter_overrides(getattr(args, "parameters", None))
    return read(
        args.path if path is None else path, units=getattr(args, "units", None),
        repair=getattr(args, "repair", False), parameters=parameters,
        units_override=getattr(args, "units_override", False),
        allow_outside_files=getattr(args, "allow_outside_files", False),
        material=getattr(args, "material", None), density=getattr(args, "density", None),
        shell=getattr(args, "shell", None), infill=getattr(args, "infill", None),
        part_materials=part_materials(getattr(args, "part_material", None)), spelled="option",
    )


def open_body(args: argparse.Namespace) -> tuple:
    """(reading, mass properties, notes) for ``args.path``: the reader's notices go to
    stderr (and into the JSON), the body's own notes (assumed densities, faceted
    booleans) start the report's notes."""
    reading = load_body(args)
    print_notices(reading, oriented=oriented(args))
    props = reading.body.mass_properties()
    return reading, props, list(props.notes)

