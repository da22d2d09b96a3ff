"""plumbob: mass properties, stability and energy from geometry alone.

The public API, imported lazily so ``plumbob mass part.stl`` pays only for numpy::

    import plumbob
    body = plumbob.load("shapes/l_shape.toml")
    props = plumbob.mass_properties(body)
    props.center_of_mass            # array([0.8333..., 0.8333...])
    plumbob.check(body).verdict     # 'stands'
    plumbob.lift(body).lift_energy  # J to raise its material into place

Every result has ``as_dict()`` (the keys of the CLI's ``--json``) and a one-line repr.
Every verb is a callable here: ``load``, ``mass_properties``, ``check``, ``poses``,
``drop_poses``, ``lift``, ``balance``, ``batch``, ``collide`` (``balance`` and ``batch``
are also rooms: ``plumbob.balance.hollow``, ``plumbob.batch.Options``).

>>> import plumbob
>>> plumbob.__version__
'0.2.0'
>>> all(callable(getattr(plumbob, verb)) for verb in
...     ("load", "check", "poses", "lift", "balance", "batch", "collide"))
True
"""

from __future__ import annotations

from importlib import import_module
from typing import Any

from .gravity import SEED_GRAVITY
from .version import __version__  # noqa: F401 (the release: plumbob/version.py)

__all__ = [
    "load",
    "read",
    "mass_properties",
    "MassProperties",
    "PlumbobError",
    "primitives",
    "union",
    "difference",
    "intersection",
    "Assembly",
    "ParticleSystem",
    "Lamina",
    "MeshSolid",
    "material",
    "check",
    "Force",
    "Hang",
    "Push",
    "Press",
    "poses",
    "drop_poses",
    "lift",
    "collide",
    "balance",
    "batch",
]

#: public name → (module, attribute; None for the module itself), imported on first use
_LAZY = {
    "read": ("plumbob.loading", "read"),
    "MassProperties": ("plumbob.massprops", "MassProperties"),
    "PlumbobError": ("plumbob.errors", "PlumbobError"),
    "primitives": ("plumbob.bodies.primitives", None),
    "union": ("plumbob.bodies.csg", "union"),
    "difference": ("plumbob.bodies.csg", "difference"),
    "intersection": ("plumbob.bodies.csg", "intersection"),
    "Assembly": ("plumbob.bodies.csg", "Assembly"),
    "ParticleSystem": ("plumbob.bodies.particles", "ParticleSystem"),
    "Lamina": ("plumbob.bodies.lamina", "Lamina"),
    "MeshSolid": ("plumbob.bodies.solid", "MeshSolid"),
    "material": ("plumbob.materials", "material"),
    "Force": ("plumbob.loads", "Force"),
    "Hang": ("plumbob.loads", "Hang"),
    "Push": ("plumbob.loads", "Push"),
    "Press": ("plumbob.loads", "Press"),
    "drop_poses": ("plumbob.stability", "drop_poses"),
    "collide": ("plumbob.dynamics.collisions", "collide"),
    "balance": ("plumbob.balance", None),
    "batch": ("plumbob.batch", None),
}


def load(path: str, *, units: str | None = None, material: str | None = None,
         density: float | None = None, repair: bool = False, **unknown: Any):
    """The body described by a file: a shape spec, a mesh or an outline.

    Parameters
    ----------
    path : str or os.PathLike
        A shape spec (``.toml``), a mesh (STL, OBJ, PLY, OFF, 3MF, GLB/glTF) or an
        outline (GeoJSON, WKT, WKB, SVG, DXF, CSV); the extension picks the reader.
    units : str, optional
        The length unit of the file's coordinates (``m``, ``cm``, ``mm``, ``km``,
        ``in``, ``ft``, or spelled out: ``"millimetre"``, ``"inch"``); default the
        file's own, else metres.
    material : str, optional
        A material from ``plumbob materials`` (``"pla"``, ``"steel"``): its density
        for every part of the file that gives none.
    density : float, optional
        The same as a number: kg/m³ for a solid, kg/m² for a lamina.
    repair : bool
        Close small holes and fix the winding of meshes (said in the body's notes).

    Returns
    -------
    Body
        A lamina, solid, set of particles or assembly, in metres.

    Raises
    ------
    PlumbobError
        For a missing, empty or unreadable file, an unknown extension or a bad shape
        (the message names the file); for a material or density that cannot apply
        (every part gives its own) or both given at once.

    Examples
    --------
    >>> import os, tempfile
    >>> path = os.path.join(tempfile.mkdtemp(), "plate.wkt")
    >>> _ = open(path, "w").write("POLYGON ((0 0, 2 0, 2 1, 0 1, 0 0))")
    >>> load(path).kind
    'lamina'
    >>> load(path, units="mm").mass_properties().center_of_mass
    array([0.001 , 0.0005])
    >>> load(path, density=3.0).mass_properties().mass
    6.0
    >>> import trimesh
    >>> cube = os.path.join(tempfile.mkdtemp(), "cube.stl")
    >>> trimesh.creation.box(extents=(10, 10, 10)).export(cube)  # doctest: +ELLIPSIS
    b'...'
    >>> round(load(cube, units="mm", material="pla").mass_properties().mass, 12)  # 1 cm³ of PLA
    0.00124
    >>> load(path + ".png")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    plumbob.errors.InputFileError: ...unknown file type '.png'...
    """
    from .errors import ArgumentError
    from .loading import read

    if unknown:
        raise ArgumentError(f"load() takes the options units, material, density and repair, "
                            f"not {sorted(unknown)[0]!r}")
    return read(path, units=units, repair=repair, material=material, density=density).body


_LOADING = ("units", "material", "density", "repair")


def _opened(body, options: dict):
    """(body, reading or None): a file name read with the ``load`` options popped from
    ``options``; a body as it is (load options then refused)."""
    from os import PathLike

    load_options = {k: options.pop(k) for k in _LOADING if k in options}
    if isinstance(body, (str, PathLike)):
        from .loading import read

        reading = read(body, **load_options)
        return reading.body, reading
    if load_options:
        from .errors import ArgumentError

        raise ArgumentError(f"{sorted(load_options)[0]}= reads a file: give a file name, or "
                            "set it on the body")
    return body, None


def check(body, *args, g: float = SEED_GRAVITY, **options):
    """Will it stand on a horizontal plane?

    Parameters
    ----------
    body : Body or str
        A plumbob body, or a file name (read as :func:`load` reads it, with the options
        ``units``, ``material``, ``density``, ``repair``; the file's up axis gives the
        default down, as on the command line).
    *args, **options
        Those of :func:`plumbob.stability.check`: ``down``, ``g``, ``tilt_deg``,
        ``toward_deg``, ``friction``, ``require_tilt_deg``, ``margin``, ``loads``, ….

    Returns
    -------
    Verdict
        Given a file, ``str(verdict)`` is what ``plumbob check FILE`` prints: in the part's
        units (mm and g for a part in mm), with its notes.

    Examples
    --------
    >>> import plumbob
    >>> plumbob.check(plumbob.primitives.box(1, 1, 4, density=1000.0)).verdict
    'stands'
    """
    from .stability import check as checked

    options["g"] = g
    body, reading = _opened(body, options)
    if reading is None:
        return checked(body, *args, **options)
    props = body.mass_properties()
    if not args and options.get("down") is None and options.get("requirement") is None:
        options["down"] = reading.default_down()  # the file's up axis, as the CLI takes it
    return checked(body, *args, props=props, **options).described(reading.source(props))


def poses(body, *, g: float = SEED_GRAVITY, **options):
    """The stable resting poses and how likely a random drop lands in each.

    Parameters
    ----------
    body : Body or str
        A plumbob body, or a file name (read with the :func:`load` options ``units``,
        ``material``, ``density``, ``repair``).
    **options
        Those of :func:`plumbob.stability.resting_poses` (``g``, ``tolerance``, …).

    Returns
    -------
    Poses
        Given a file, ``str(poses)`` is what ``plumbob poses FILE`` prints.

    Examples
    --------
    >>> import plumbob
    >>> len(plumbob.poses(plumbob.primitives.box(1, 1, 4)))
    6
    """
    from .stability import resting_poses
    from .stability.support import body_size

    options["g"] = g
    body, reading = _opened(body, options)
    if reading is None:
        return resting_poses(body, **options)
    props = body.mass_properties()
    return resting_poses(body, props=props, **options).described(
        reading.source(props, body_size(body)))


def lift(body, *, g: float = SEED_GRAVITY, **options):
    """The energy to raise a structure's material into place, M g z_G.

    Parameters
    ----------
    body : Body or str
        A plumbob body, or a file name (read with the :func:`load` options ``units``,
        ``material``, ``density``, ``repair``).
    **options
        Those of :func:`plumbob.energy.lift_energy` (``datum``, ``g``, ``down``).

    Returns
    -------
    LiftEnergy
        Given a file, ``str(lift)`` is what ``plumbob lift FILE`` prints.

    Examples
    --------
    >>> import plumbob
    >>> plumbob.lift(plumbob.primitives.box(2, 2, 10, density=1.0), g=10.0).lift_energy
    2000.0
    """
    from .energy import lift_energy

    options["g"] = g
    body, reading = _opened(body, options)
    if reading is None:
        return lift_energy(body, **options)
    props = body.mass_properties()
    return lift_energy(body, props=props, **options).described(reading.source(props))


def mass_properties(body, **options):
    """Mass, size, centre of mass and inertia of a body.

    Parameters
    ----------
    body : Body or str
        A plumbob body, or the path of a file to :func:`load` (in metres, or in the
        unit the file declares); with a path, the ``load`` options ``units``,
        ``material``, ``density`` and ``repair``, and ``str(props)`` is the table
        ``plumbob mass FILE`` prints, in the part's units.

    Returns
    -------
    MassProperties
        SI units; the inertia tensor about the centre of mass. A body that gives no
        density is taken at density 1 (``notes`` says so).

    Examples
    --------
    >>> from plumbob import primitives
    >>> mass_properties(primitives.box(1, 1, 4, density=1000.0))
    MassProperties(dim=3, mass=4000 kg, volume=4 m³, center_of_mass=[0.5, 0.5, 2] m, \
principal_moments=[666.667, 5666.67, 5666.67] kg·m², exact=True)
    >>> mass_properties(primitives.box(1, 1, 1)).notes[0].startswith("no density given")
    True

    A path is loaded first:

    >>> import os, tempfile
    >>> path = os.path.join(tempfile.mkdtemp(), "plate.wkt")
    >>> _ = open(path, "w").write("POLYGON ((0 0, 2 0, 2 1, 0 1, 0 0))")
    >>> mass_properties(path).area
    2.0
    """
    from .arguments import answering

    body, reading = _opened(body, options)
    if options:
        from .errors import ArgumentError

        raise ArgumentError(f"mass_properties() takes the load options {', '.join(_LOADING)}, "
                            f"not {sorted(options)[0]!r}")
    props = answering(body, "body", "mass_properties", kind="a plumbob body or a file name"
                      ).mass_properties()
    return props if reading is None else props.described(reading.source(props))


def __getattr__(name: str):
    if name not in _LAZY:
        raise AttributeError(f"module 'plumbob' has no attribute {name!r}")
    module, attribute = _LAZY[name]
    value = import_module(module)
    return value if attribute is None else getattr(value, attribute)


def __dir__() -> list[str]:
    """The public API (what ``dir(plumbob)`` and tab completion list)."""
    return sorted(__all__)
