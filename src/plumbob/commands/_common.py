"""What the commands share: reading the body with the body options, and (re-exported
from their modules) the value types (:mod:`.types`), the shared options (:mod:`.options`)
and the JSON output (:mod:`.output`).

Every command module imports from here and from the library, never from another
command module. Only numpy and plumbob's reader load at import; the stability,
energy and dynamics code load when a command runs.
"""

from __future__ import annotations

import argparse
from collections.abc import Mapping
from typing import Any

from ..loading import read
from ..reading import Reading
from ._notices import default_down, flush_notices, oriented, print_notices
from .loads import add_load_arguments, force_option, hang_option, option_loads
from .options import (  # re-exported: the commands import them from here
    add_body_arguments,
    add_orientation_arguments,
    add_report_units_argument,
    add_stability_arguments,
    parameter_overrides,
    pose_down,
    report_units,
    requirement,
)
from .output import (  # re-exported
    dump_json,
    header,
    print_json,
    require_finite,
)
from .types import (  # re-exported
    assignment,
    count,
    direction,
    length,
    length_unit,
    material_name,
    non_negative,
    number,
    number_option,
    parse_vector,
    part_materials,
    positive,
    tilt_limit,
)

__all__ = [
    "number",
    "positive",
    "count",
    "non_negative",
    "length",
    "parse_vector",
    "direction",
    "material_name",
    "tilt_limit",
    "number_option",
    "length_unit",
    "assignment",
    "force_option",
    "hang_option",
    "part_materials",
    "add_body_arguments",
    "add_report_units_argument",
    "report_units",
    "parameter_overrides",
    "add_stability_arguments",
    "add_orientation_arguments",
    "pose_down",
    "add_load_arguments",
    "option_loads",
    "requirement",
    "header",
    "require_finite",
    "dump_json",
    "print_json",
    "load_body",
    "open_body",
    "print_notices",
    "flush_notices",
    "default_down",
]


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

