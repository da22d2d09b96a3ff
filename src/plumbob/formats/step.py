"""STEP (and IGES, BREP) CAD files: exact solids read from their B-rep by OpenCASCADE.

:func:`read_step` gives one :class:`~plumbob.bodies.brep.BRepSolid` per instance of
each part of the file's product structure (an :class:`~plumbob.bodies.csg.Assembly`
of them, named after the file, when there are several): each part keeps its name
and placement, and its mass properties come from the B-rep's surfaces
(OpenCASCADE's ``BRepGProp``), not from a faceting. Hulls, contact, pictures and
mesh exports use a tessellation of the B-rep within a stated deviation.

The file is checked before OpenCASCADE sees it — its size, the ISO-10303-21 header
and trailer (a truncated file), the number of entities, references to external
files, the declared length unit and how deep the assembly nests — so a hostile
file is refused in bounded time and memory. OpenCASCADE then runs in a child
process (:mod:`plumbob.formats.step_worker`) under a memory and time limit: a crash
of the C++ library costs one line naming the file, never this process.

OpenCASCADE comes from the optional extra ``plumbob[cad]`` (the
``cadquery-ocp-novtk`` wheel).
"""

from __future__ import annotations

import os
import pickle
import re
import sys
import tempfile

import numpy as np

from .. import limits
from ..errors import FormatError, InputFileError, LimitError, PlumbobError
from ..files import require_regular_file
from ..reading import Reading
from ..units import units_scale
from .cad_child import ChildFailed, ChildTimedOut, read_in_child

__all__ = ["STEP_SUFFIXES", "read_step", "step_unit", "require_ocp", "DEVIATION"]

from .parts import CAD_SUFFIXES as STEP_SUFFIXES

#: the tessellation's deviation from the B-rep, as a fraction of each part's size
DEVIATION = 1e-4
#: the B-rep integration's stated relative error: the bound OpenCASCADE's estimate is
#: raised to (tested on closed-form solids: cylinder, sphere, cone, torus, box with holes)
GPROP_ERROR_FLOOR = 1e-10

_CHUNK = 8 * 2**20
_ENTITY = re.compile(rb"#\d+\s*=")
_EXTERNAL = re.compile(rb"\b(DOCUMENT_FILE|EXTERNAL_SOURCE|EXTERNALLY_DEFINED_\w+)\s*\(")
_NAUO = re.compile(rb"NEXT_ASSEMBLY_USAGE_OCCURRENCE\s*\(\s*'[^']*'\s*,\s*'[^']*'\s*,\s*"
                   rb"(?:'[^']*'|\$)\s*,\s*#(\d+)\s*,\s*#(\d+)")
_LENGTH_UNIT = re.compile(rb"#(\d+)\s*=\s*\(([^;]*?LENGTH_UNIT\s*\(\s*\)[^;]*?)\)\s*;")
#: the units a representation context declares for its coordinates (other length units
#: may stand in the file only as the base of a conversion: SolidWorks' inch is 0.0254 of
#: a metre unit of its own)
_GLOBAL_UNITS = re.compile(rb"GLOBAL_UNIT_ASSIGNED_CONTEXT\s*\(\s*\(([^)]*)\)")
_REFERENCE = re.compile(rb"#(\d+)")
_SI = re.compile(rb"SI_UNIT\s*\(\s*(\$|\.\w+\.)\s*,\s*\.METRE\.\s*\)")
_CONVERSION = re.compile(rb"CONVERSION_BASED_UNIT\s*\(\s*'([^']*)'")
_SI_PREFIX = {b"$": "m", b".MILLI.": "mm", b".CENTI.": "cm", b".KILO.": "km",
              b".DECI.": "dm", b".MICRO.": "um"}
_CONVERTED = {"INCH": "in", "FOOT": "ft", "MILLIMETRE": "mm", "MILLIMETER": "mm",
              "METRE": "m", "METER": "m", "CENTIMETRE": "cm", "CENTIMETER": "cm"}
_METRES = {"m": 1.0, "dm": 0.1, "cm": 0.01, "mm": 1e-3, "um": 1e-6, "km": 1e3, "in": 0.0254,
           "ft": 0.3048}
#: seconds the child may take (``PLUMBOB_STEP_SECONDS``), bytes of memory it may map
STEP_SECONDS = float(os.environ.get("PLUMBOB_STEP_SECONDS", "600"))
STEP_MEMORY = 8 * 2**30
#: how the child is started (it then serves reads: :mod:`.cad_child`)
_WORKER = ["-m", "plumbob.formats.step_worker"]


def require_ocp() -> None:
    """An :class:`InputFileError` in one line when OpenCASCADE (``plumbob[cad]``) is missing."""
    import importlib.util

    if importlib.util.find_spec("OCP") is None:
        raise InputFileError("reading STEP, IGES or BREP files needs OpenCASCADE: "
                             "install plumbob[cad] (pip install 'plumbob[cad]')")


def _scan(path: str) -> dict:
    """What the text of a STEP file says before OpenCASCADE reads it, in bounded memory:
    its header and trailer, the entity count, external references, length units and
    the assembly's parent → child links."""
    size = require_regular_file(path)
    if size > limits.MAX_STEP_BYTES:
        raise LimitError(f"is {size} bytes, over plumbob's limit of {limits.MAX_STEP_BYTES} for "
                         "a STEP file (plumbob.limits.MAX_STEP_BYTES)", path=path)
    found: dict = {"entities": 0, "external": None, "units": {}, "global": set(), "links": []}
    tail = b""
    with open(path, "rb") as f:
        head = f.read(4096)
        if not head.lstrip(b"\xef\xbb\xbf \t\r\n").startswith(b"ISO-10303-21;"):
            raise FormatError("is not a STEP file: it does not begin with ISO-10303-21;", path=path)
        f.seek(0)
        carry = b""
        while chunk := f.read(_CHUNK):
            text = carry + chunk
            # entities whole within this block: up to its last ';' (the rest carries over)
            end = text.rfind(b";") + 1
            block, carry = text[:end], text[end:]
            if len(carry) > _CHUNK:  # one entity longer than a block: not a CAD file
                raise FormatError("holds a single record over 8 MiB long", path=path)
            _scan_block(block, found, path)
            tail = (tail + chunk)[-4096:]
    if b"END-ISO-10303-21;" not in tail:
        raise FormatError("is truncated: it does not end with END-ISO-10303-21;", path=path)
    return found


def _scan_block(block: bytes, found: dict, path: str) -> None:
    found["entities"] += len(_ENTITY.findall(block))
    if found["entities"] > limits.MAX_STEP_ENTITIES:
        raise LimitError(f"holds over {limits.MAX_STEP_ENTITIES} entities, plumbob's limit for a "
                         "STEP file (plumbob.limits.MAX_STEP_ENTITIES)", path=path)
    external = _EXTERNAL.search(block)
    if external and found["external"] is None:
        found["external"] = external.group(1).decode()
    for match in _LENGTH_UNIT.finditer(block):
        found["units"][int(match.group(1))] = _unit_of(match.group(2))
    for match in _GLOBAL_UNITS.finditer(block):
        found["global"].update(int(n) for n in _REFERENCE.findall(match.group(1)))
    links = _NAUO.findall(block)
    found["links"] += links
    if len(found["links"]) > limits.MAX_PARTS:
        raise LimitError(f"places over {limits.MAX_PARTS} part instances, plumbob's limit "
                         "(plumbob.limits.MAX_PARTS)", path=path)


def _unit_of(entity: bytes) -> str:
    """The unit a length-unit entity names (``"mm"``, ``"in"``, …), or a sentence saying
    what is odd about it (refused if the file's coordinates are in it)."""
    si = _SI.search(entity)
    if si is not None:
        if si.group(1) not in _SI_PREFIX:
            return f"an odd length unit ({si.group(1).decode().strip('.')}METRE)"
        return _SI_PREFIX[si.group(1)]
    conversion = _CONVERSION.search(entity)
    name = conversion.group(1).decode("latin-1").strip().upper() if conversion else "?"
    return _CONVERTED.get(name, f"an odd length unit ({name!r})")


def _nesting(links: list[tuple[bytes, bytes]], path: str) -> int:
    """How deep the assembly nests (a cycle is refused), by an iterative walk."""
    children: dict[bytes, list[bytes]] = {}
    for parent, child in links:
        children.setdefault(parent, []).append(child)
    depth: dict[bytes, int] = {}
    for root in children:
        stack, on_path = [(root, iter(children.get(root, ())))], {root}
        while stack:
            node, kids = stack[-1]
            kid = next(kids, None)
            if kid is None:
                stack.pop()
                on_path.discard(node)
                depth[node] = 1 + max((depth[k] for k in children.get(node, ())), default=0)
                continue
            if kid in on_path:
                raise FormatError("has an assembly that contains itself", path=path)
            if kid not in depth:
                if len(stack) > limits.MAX_NESTING:
                    raise LimitError(f"nests its assembly over {limits.MAX_NESTING} deep, plumbob's "
                                     "limit (plumbob.limits.MAX_NESTING)", path=path)
                stack.append((kid, iter(children.get(kid, ()))))
                on_path.add(kid)
    return max(depth.values(), default=0)


def step_unit(path: str) -> str:
    """The length unit the STEP file ``path`` declares (``"mm"``, ``"in"``, …), after the
    checks :func:`read_step` makes before OpenCASCADE reads it."""
    found = _scan(path)
    if found["external"] is not None:
        raise FormatError(f"refers to an external file ({found['external']}): plumbob reads one "
                          "self-contained STEP file; export the assembly with its parts in it",
                          path=path)
    _nesting(found["links"], path)
    # the units the coordinates are in: those of the representation contexts (else every
    # length unit the file names)
    units = {found["units"][n] for n in found["global"] if n in found["units"]} or \
        set(found["units"].values())
    if not units:
        raise FormatError("declares no length unit: save it again from the CAD program "
                          "(every STEP export states one)", path=path)
    odd = sorted(u for u in units if u not in _METRES)
    if odd:
        raise FormatError(f"declares {odd[0]}: save it in mm, m or inches", path=path)
    if len(units) > 1:
        raise FormatError(f"mixes length units ({', '.join(sorted(units))}): save it "
                          "in one unit", path=path)
    return next(iter(units))


def _run_worker(path: str) -> dict:
    """The child process's result for ``path`` (see :mod:`.step_worker`)."""
    # the folder holding the plumbob package, so the child imports this very copy
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [root] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])}

    def bounded() -> None:  # in the child, before it runs: its memory
        import resource

        resource.setrlimit(resource.RLIMIT_AS, (STEP_MEMORY, STEP_MEMORY))

    with tempfile.TemporaryDirectory(prefix="plumbob-step-") as folder:
        out = os.path.join(folder, "parts.pickle")
        try:
            read_in_child([sys.executable, *_WORKER], env,
                          [os.path.abspath(path), out, repr(DEVIATION)], timeout=STEP_SECONDS,
                          limit=bounded if os.name == "posix" else None)
        except ChildTimedOut:
            raise LimitError(f"took OpenCASCADE over {STEP_SECONDS:g} s to read: refused "
                             "(PLUMBOB_STEP_SECONDS sets the limit)", path=path) from None
        except ChildFailed as failed:
            if "MemoryError" in failed.last_line or "bad_alloc" in failed.last_line:
                raise LimitError(f"needed over {STEP_MEMORY // 2**30} GiB for OpenCASCADE to read",
                                 path=path) from None
            last = f": {failed.last_line}" if failed.last_line else ""
            raise FormatError(f"made OpenCASCADE fail ({failed.how}) while reading it: the file is "
                              f"malformed or beyond what it reads{last}", path=path) from None
        if not os.path.exists(out):
            raise FormatError("gave no answer from OpenCASCADE while reading it", path=path)
        with open(out, "rb") as f:
            return pickle.load(f)  # noqa: S301 - our own child's output, in our own folder


def read_step(path: str, *, units: str | None = None, units_override: bool = False) -> Reading:
    """Read the parts of a STEP, IGES or BREP file as exact B-rep solids, in metres.

    ``units``: the unit the file's coordinates are in; one that contradicts the unit
    the file declares is refused unless ``units_override`` (then used, with a notice).
    Every defect is one :class:`PlumbobError` naming the file."""
    require_ocp()
    suffix = os.path.splitext(path)[1].lower()
    if suffix in (".step", ".stp"):
        declared = step_unit(path)
    else:  # IGES and BREP: OpenCASCADE's own unit, millimetres
        require_regular_file(path)
        declared = "mm"
    scale, notices = units_scale(units, declared, _METRES[declared], override=units_override,
                                 path=path)
    if suffix == ".brep" and units is None:
        notices = ("units: mm (a BREP file states none; OpenCASCADE's convention)",)
    result = _run_worker(path)
    if "defect" in result:
        raise FormatError(str(result["defect"]), path=path)
    # OpenCASCADE gives millimetres (it converts the declared unit): back to file units,
    # then to metres by the unit in force
    mm = 1e-3 / _METRES[declared] * scale
    return _reading(path, result["parts"], mm, notices, units or declared)


def _stl_triangles(data: bytes, path: str) -> np.ndarray:
    """The triangles (n, 3, 3), float64, of the binary STL the child wrote."""
    count = int.from_bytes(data[80:84], "little") if len(data) >= 84 else -1
    if count <= 0 or len(data) != 84 + 50 * count:
        raise FormatError("gave OpenCASCADE no tessellation of a part", path=path)
    record = np.frombuffer(data, dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")],
                           count=count, offset=84)
    return record["v"].astype(np.float64)


def _reading(path: str, parts: list[dict], mm: float, notices: tuple[str, ...],
             unit: str) -> Reading:
    from ..bodies.brep import BRepSolid
    from .parts import assemble, stem, unique_names

    names = unique_names([p["name"] or f"part {i + 1}" for i, p in enumerate(parts)])
    bodies = []
    for name, part in zip(names, parts):
        local = _stl_triangles(part["stl"], path)
        # float32 STL coordinates about the part's middle: rounded by up to 2⁻²⁴ of them
        rounding = float(np.abs(local).max()) * 2.0**-24 * np.sqrt(3)
        triangles = (local + np.asarray(part["offset"])) * mm
        bodies.append(BRepSolid.from_gprops(
            name=name, volume=part["volume"] * mm**3, centre=np.asarray(part["centre"]) * mm,
            inertia=np.asarray(part["inertia"]) * mm**5, triangles=triangles,
            deviation=(part["deviation"] + rounding) * mm, planar=part["planar"],
            relative_error=max(part["error"], GPROP_ERROR_FLOOR)))
    worst = max(b.deviation / max(b.size, 1e-300) for b in bodies)
    notices += (f"mass properties from the B-rep (relative error ≤ {GPROP_ERROR_FLOOR:g}); "
                f"hulls, contact and pictures from a tessellation within {worst:.1g} of each "
                f"part's size (tilts to about {np.degrees(worst):.1g}°)",)
    unchecked = [n for n, p in zip(names, parts) if not p.get("self_checked", True)]
    if unchecked:
        from .step_worker import SELF_CHECK_FACES

        notices += (f"{', '.join(repr(n) for n in unchecked[:5])}"
                    f"{f' and {len(unchecked) - 5} more' if len(unchecked) > 5 else ''}: over "
                    f"{SELF_CHECK_FACES} faces, not checked for faces crossing each other "
                    "(OpenCASCADE's check would take minutes); a self-intersecting solid would "
                    "give a wrong volume",)
    try:
        body = assemble(bodies, stem(path))
    except PlumbobError as error:
        raise error.within(path=path) from None
    from ..units import unit_symbol

    return Reading(body, notices, path, unit_symbol(unit) if unit in ("m", "cm", "mm", "km", "in",
                                                                      "ft") else None)
