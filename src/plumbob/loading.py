"""Reading any file plumbob understands: a TOML spec, a mesh or an outline.

:func:`read` chooses by the file's extension: ``.toml`` goes to the spec reader
(:mod:`plumbob.spec`), every other known extension to the file-format readers
(:mod:`plumbob.formats`). Living above both, this dispatcher lets spec read its mesh
files through io while io never imports spec.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace

from . import formats
from .arguments import file_path
from .errors import ArgumentError, DensityError, PlumbobError, SpecError
from .formats.parts import require_part_densities, with_file_materials, with_part_materials
from .reading import Reading

__all__ = ["read", "with_default_density", "SUFFIXES"]

#: file extension → reader family: specs, and every format :mod:`plumbob.formats` reads
SUFFIXES = {".toml": "spec", **formats.SUFFIXES}


def read(path: str, *, parameters: Mapping[str, float | str] | None = None,
         units: str | None = None, repair: bool = False,
         allow_outside_files: bool = False, material: str | None = None,
         density: float | None = None, units_override: bool = False,
         shell: str | None = None, infill: str | None = None,
         part_materials: Mapping[str, str] | None = None, spelled: str = "keyword") -> Reading:
    """Read the body in ``path``: a shape or simulation spec (``.toml``), a mesh or an
    outline file, chosen by the extension.

    Parameters
    ----------
    path : str or os.PathLike
        The file; its extension chooses the reader.
    units : str, optional
        The length unit of a mesh's or outline's coordinates (``mm``, ``cm``, ``m``,
        ``in``, ``ft``); None uses the unit the file declares, else metres (with a
        notice). For a spec that sets no ``units``, its unit; for one that sets
        the same, a notice; for one that sets another, an error (``docs/shapes.md``).
        A unit that contradicts the one a file declares (3MF, glTF, DXF, a spec's
        ``units``) is an error, unless ``units_override``.
    units_override : bool
        Use ``units`` even where the file declares another unit (with a notice).
    repair : bool
        Close small holes in open meshes, a spec's mesh files included (reported in
        the notices; a notice when there is nothing to repair).
    parameters : mapping of str to float or str, optional
        Values for a spec's ``[parameters]`` entries, by name, replacing the spec's
        own (``--set name=value``): a number, an expression over the parameters
        before it, or a number with a length unit (``"30 cm"``, converted into the
        spec's unit). A name the spec does not define is an error listing the known
        ones; parameters given for a file that is not a spec are an error.
    allow_outside_files : bool
        Let a spec read files outside its own folder (an absolute path, ``..``);
        refused by default, so a spec from elsewhere cannot read any file you can.
    material, density : optional
        A material name (``"pla"``) or a density (kg/m³ for solids, kg/m² for laminas)
        for every part that gives none (:func:`with_default_density`); at most one.
    shell, infill : str, optional
        The body as printed: walls ``shell`` thick (``"1.2mm"``; a bare number in
        ``units``) at full density around an interior filled to ``infill`` (``"20%"``,
        ``0.2``); both or neither (:func:`plumbob.bodies.printed.printed_from_options`).
    spelled : str
        How messages name these options: ``"keyword"`` (``material='oak'``) or
        ``"option"``, as the command line (``--material oak``) and a batch run give them.
    part_materials : mapping of str to str, optional
        ``{name or glob: material}``: a material name (or a density, kg/m³) for the
        parts of an assembly whose names match (:func:`with_part_materials`), applied
        before ``material``/``density``. The parts of a CAD assembly (STEP) must each
        get a density, from here or from ``material``/``density``: else one error lists
        those without.

    Returns
    -------
    Reading
        The body (in metres) and the notices a user should see.

    Raises
    ------
    PlumbobError
        Every failure, naming the file.

    Examples
    --------
    >>> reading = read("shapes/l_shape.toml")
    >>> reading.body.kind, reading.body.mass_properties().center_of_mass.round(4).tolist()
    ('lamina', [0.8333, 0.8333])
    >>> read("shapes/l_shape.toml", parameters={"a": 2}).body.mass_properties().area
    12.0
    >>> read("shapes/l_shape.toml", density=2.0).body.mass_properties().mass  # kg/m², 3 m²
    6.0
    >>> read("shapes/block.toml", material="oak")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    plumbob.errors.DensityError: shapes/block.toml: material='oak' does not apply: every part ...
    >>> read("missing.stl")
    Traceback (most recent call last):
    ...
    plumbob.errors.InputFileError: missing.stl: no such file
    """
    path = file_path(path)
    if units is not None:  # one spelling from here on: "Millimetre" and "MM" are "mm"
        from .units import unit_symbol

        try:
            units = unit_symbol(units)
        except PlumbobError as error:
            raise ArgumentError(f"units: {error.message}", path=path) from None
    if units_override and units is None:
        raise ArgumentError("units_override (--units-override) needs units (--units): the unit "
                            "to read the file in", path=path)
    if material is not None and density is not None:
        raise DensityError("give a material or a density, not both", path=path)
    if formats.file_family(path, SUFFIXES) == "spec":
        from .spec.loader import load_spec  # the spec builders are needed only for specs

        reading = load_spec(path, parameters=parameters, units=units, repair=repair,
                            allow_outside_files=allow_outside_files,
                            units_override=units_override)
    elif parameters:
        raise SpecError(f"parameters ({', '.join(parameters)}) apply only to a TOML spec; "
                        "this file is not one", path=path)
    else:
        reading = formats.read(path, units=units, repair=repair, units_override=units_override)
    option = spelled == "option"
    if part_materials:
        reading = with_part_materials(reading, part_materials,
                                      "--part-material" if option else "part_materials")
    reading = with_file_materials(reading)  # what the file names, for the other parts
    if material is not None:
        from .materials import material as named

        reading = with_default_density(reading, named(material).density,
                                       f"--material {material}" if option
                                       else f"material={material!r}")
    elif density is not None:
        from .arguments import check_density

        name = "--density" if option else "density"
        reading = with_default_density(reading, check_density(density, name), name)
    reading = require_part_densities(reading, "--part-material NAME=MATERIAL" if option
                                     else "part_materials={NAME: MATERIAL}")
    if shell is not None or infill is not None:
        from .bodies.printed import printed_from_options
        from .units import length_scale

        body = printed_from_options(reading.body, shell, infill, scale=length_scale(units),
                                    where="--shell/--infill" if option else "shell/infill")
        reading = replace(reading, body=body)
    return reading


def with_default_density(reading: Reading, density: float, option: str) -> Reading:
    """``reading`` with ``density`` for every part that gives none (``--density``,
    ``--material``; ``option`` names it in messages).

    An option that cannot apply is never ignored: when every part gives its own
    density (or the body is particles, whose masses are given) it is an error —
    unless every part already has that very density, which is only a notice.

    >>> from plumbob.bodies.primitives import box
    >>> with_default_density(Reading(box(1, 1, 1)), 2.0, "--density").body.mass_properties().mass
    2.0
    >>> with_default_density(Reading(box(1, 1, 1, density=5.0), (), "a.toml"), 2.0, "--density")
    Traceback (most recent call last):
    ...
    plumbob.errors.DensityError: a.toml: --density does not apply: every part gives its own \
density (5 kg/m³); remove the option, or a density from the file
    """
    own = reading.body.densities()
    if None in own:
        return replace(reading, body=reading.body.with_default_density(density))
    if not own:
        raise DensityError(f"{option} does not apply: a body of particles has its masses "
                           "given; remove the option", path=reading.path)
    if own == {density}:
        note = f"{option}: every part already has this density; the option changes nothing"
        return replace(reading, notices=reading.notices + (note,))
    unit = "kg/m²" if reading.body.kind == "lamina" else "kg/m³"
    given = ", ".join(sorted(f"{d:g} {unit}" if isinstance(d, float) else "a density field"
                             for d in own))
    raise DensityError(f"{option} does not apply: every part gives its own density "
                       f"({given}); remove the option, or a density from the file",
                       path=reading.path)
