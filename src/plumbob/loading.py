"""Reading any file plumbob understands: a TOML spec, a mesh or an outline.

:func:`read` chooses by the file's extension: ``.toml`` goes to the spec reader
(:mod:`plumbob.spec`), every other known extension to the file-format readers
(:mod:`plumbob.io`). Living above both, this dispatcher lets spec read its mesh
files through io while io never imports spec.
"""

from __future__ import annotations

import os
from collections.abc import Mapping

from . import io
from .errors import SpecError
from .reading import Reading

__all__ = ["read", "SUFFIXES"]

#: file extension → reader family: specs, and every format :mod:`plumbob.io` reads
SUFFIXES = {".toml": "spec", **io.SUFFIXES}


def read(path: str, *, parameters: Mapping[str, float | str] | None = None,
         units: str | None = None, repair: bool = False) -> Reading:
    """Read the body in ``path``: a shape or simulation spec (``.toml``), a mesh or an
    outline file, chosen by the extension.

    Parameters
    ----------
    path : str or os.PathLike
        The file; its extension chooses the reader.
    units : str, optional
        The length unit of a mesh's or outline's coordinates (``mm``, ``cm``, ``m``,
        ``in``, ``ft``); None uses the unit the file declares, else metres (with a
        notice). A spec gives its own units.
    repair : bool
        Close small holes in open meshes (reported in the notices).
    parameters : mapping of str to float or str, optional
        Values for a spec's ``[parameters]`` entries, by name, replacing the spec's
        own (``--set name=value``): a number, an expression over the parameters
        before it, or a number with a length unit (``"30 cm"``, converted into the
        spec's unit). A name the spec does not define is an error listing the known
        ones; parameters given for a file that is not a spec are an error.

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
    >>> read("missing.stl")
    Traceback (most recent call last):
    ...
    plumbob.errors.InputFileError: missing.stl: no such file
    """
    path = os.fspath(path)
    if io.file_family(path, SUFFIXES) == "spec":
        from .spec.loader import load_spec  # the spec builders are needed only for specs

        return load_spec(path, parameters=parameters)
    if parameters:
        raise SpecError(f"parameters ({', '.join(parameters)}) apply only to a TOML spec; "
                        "this file is not one", path=path)
    return io.read(path, units=units, repair=repair)
