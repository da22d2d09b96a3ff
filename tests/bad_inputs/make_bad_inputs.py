"""Generate plumbob's corpus of broken input files (small, deterministic).

    python tests/bad_inputs/make_bad_inputs.py [DIRECTORY]

writes every case of :data:`CASES` into DIRECTORY (default: this folder).
Each case says what reading it must give: an error of a given class whose
message contains a given fragment, or a body with a given volume/area and a
notice containing a fragment. ``tests/test_io_bad_inputs.py`` checks them all.
"""

from __future__ import annotations

import gzip
import io
import os
import struct
import sys
import zipfile
from dataclasses import dataclass, field

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))


@dataclass(frozen=True)
class Case:
    """One broken file and what plumbob must say about it.

    error: the PlumbobError subclass name expected, or None when the file reads
        (then ``measure`` is the volume/area expected and ``message`` a notice fragment).
    read: keyword arguments for ``plumbob.formats.read``.
    """

    name: str
    error: str | None
    message: str
    read: dict = field(default_factory=dict)
    measure: float | None = None
    why: str = ""


CASES: tuple[Case, ...] = (
    Case("missing.stl", "InputFileError", "no such file", why="the file does not exist"),
    Case("folder.stl", "InputFileError", "is a folder", why="a directory, not a file"),
    Case("unknown.xyz", "InputFileError", "unknown file type", why="no reader for .xyz"),
    Case("empty.stl", "InputFileError", "is empty (0 bytes)", why="zero bytes"),
    Case("garbage.stl", "InputFileError", "too short for a binary STL", why="11 bytes of text"),
    Case("truncated.stl", "InputFileError", "header says 12 triangles",
         why="binary STL cut short: fewer bytes than its triangle count needs"),
    Case("overlong.stl", "FormatError", "17 more",
         why="binary STL with bytes beyond its triangle count"),
    Case("truncated_ascii.stl", "InputFileError", "ends in the middle of a facet",
         why="ASCII STL cut off inside a facet"),
    Case("bad_number.stl", "FormatError", "line 4",
         why="ASCII STL with a vertex that is not three numbers"),
    Case("no_facets.stl", "FormatError", "has no facets", why="'solid' … 'endsolid' only"),
    Case("nan.stl", "GeometryError",
         "triangle 5 has a coordinate that is not a finite number (NaN)",
         why="binary cube with a NaN coordinate"),
    Case("infinite.stl", "GeometryError", "not a finite number (infinity)",
         why="ASCII cube with an 'inf' coordinate"),
    Case("absurd.stl", "GeometryError", "far beyond any real object",
         why="a cube 1e12 m across"),
    Case("open.stl", "GeometryError", "the mesh is open: 3 boundary edges (1 hole), e.g. near",
         why="a cube (192 triangles) missing one triangle"),
    Case("open.stl", None, "repair: closed 1 hole (3 boundary edges)", read={"repair": True},
         measure=1.0, why="--repair closes the small hole exactly"),
    Case("open_big.stl", "GeometryError", "hole too large to close safely",
         read={"repair": True}, why="a cube missing a whole face: too big to patch"),
    Case("winding.stl", None, "winding: 1 of 12 triangles", measure=1.0,
         why="a cube with one triangle wound backwards: turned, with a notice"),
    Case("inside_out.stl", None, "inside out", measure=1.0,
         why="a cube with every triangle wound backwards: turned, with a notice"),
    Case("overlap.stl", None, "2 shells overlap; united with manifold3d", measure=1.5,
         why="two unit cubes overlapping by half: united, with a notice"),
    Case("flat.stl", "GeometryError", "encloses no volume",
         why="a closed but flat (two-sided square) surface"),
    Case("degenerate.stl", "GeometryError", "triangles have zero area",
         why="every triangle has collinear corners"),
    Case("pen_2000m.stl", None, "is 2000 × 0.007812 × 0.007812 m, implausible for metres",
         measure=2000 / 128**2,
         why="a 2000 m pen: plausible only in mm; read, with a warning"),
    Case("corrupt.3mf", "FormatError", "is not a readable 3MF (zip) archive",
         why="not a zip archive"),
    Case("zip_bomb.3mf", "LimitError", "(plumbob.limits.MAX_ARCHIVE_BYTES): refused unread",
         why="a 3MF whose archive declares 2 GiB of contents"),
    Case("entities.3mf", "FormatError", "declares a DTD or XML entities",
         why="a 3MF model with an entity-expansion DTD"),
    Case("nonsense.obj", "FormatError", "contains no triangle mesh", why="text that is not OBJ"),
    Case("entities.svg", "FormatError", "declares XML entities",
         why="an SVG with a billion-laughs entity expansion"),
    Case("open_path.svg", "GeometryError", "path 'cut' (subpath 1) never closes",
         why="an SVG path that never closes"),
    Case("crossing.svg", "GeometryError", "cross each other at",
         why="two outlines that cross"),
    Case("not_xml.svg", "FormatError", "is not well-formed XML", why="broken XML"),
    Case("no_closed.dxf", "FormatError", "has no closed outline (2 LINE)",
         why="a DXF whose entities never close"),
    Case("bowtie.geojson", "GeometryError", "crosses itself at (1, 1)",
         why="a self-intersecting (bow-tie) polygon"),
    Case("bowtie.csv", "GeometryError", "crosses itself at (1, 1)",
         why="a bow-tie vertex list"),
    Case("zero_area.wkt", "GeometryError", "has zero area", why="a polygon with collinear corners"),
    Case("not_json.geojson", "FormatError", "is not valid JSON", why="truncated JSON"),
    Case("nan.csv", "GeometryError", "line 3: a coordinate is not a finite number",
         why="a vertex list with 'nan'"),
    Case("bad_row.csv", "FormatError", "line 3", why="a vertex list row with three numbers"),
    Case("bad.wkb", "FormatError", "is not valid WKB", why="truncated WKB"),
    Case("unsupported.dae", "InputFileError", "unsupported file type '.dae' (COLLADA)",
         why="a 3D format plumbob knows of but does not read"),
    Case("cube.stl.gz", None, "gzip: read cube.stl from the archive", measure=1.0,
         why="a gzipped binary STL reads as the STL it holds"),
    Case("slip.zip", "FormatError", "points outside the archive",
         why="a zip member named ../evil.stl (zip slip)"),
    Case("two.zip", "FormatError", "holds 2 files plumbob reads (a.stl, b.stl)",
         why="a zip of two meshes: which one is meant?"),
)


# ------------------------------------------------------------------ meshes
def cube(n: int = 1, size: float = 1.0, offset=(0.0, 0.0, 0.0)) -> np.ndarray:
    """Triangles (12 n², 3, 3) of a cube [0, size]³ + offset, each face an n × n grid,
    wound outward."""
    g = np.linspace(0.0, size, n + 1)
    u, v = np.meshgrid(g[:-1], g[:-1], indexing="ij")
    u, v = u.ravel(), v.ravel()
    d = size / n
    quads = np.stack([np.stack((u, v), -1), np.stack((u + d, v), -1),
                      np.stack((u + d, v + d), -1), np.stack((u, v + d), -1)], axis=1)  # (m, 4, 2)
    tris2 = np.concatenate((quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]))  # CCW in (u, v)
    faces = []
    for axis in range(3):  # per face of the cube
        for level in (0.0, size):
            t = np.zeros(tris2.shape[:2] + (3,))
            others = [a for a in range(3) if a != axis]
            t[..., others[0]], t[..., others[1]] = tris2[..., 0], tris2[..., 1]
            t[..., axis] = level
            normal = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])[:, axis]
            outward = 1.0 if level > 0 else -1.0
            faces.append(np.where((normal * outward < 0)[:, None, None], t[:, ::-1], t))
    return np.concatenate(faces) + np.asarray(offset)


def binary_stl(triangles: np.ndarray, count: int | None = None, extra: bytes = b"") -> bytes:
    tri = np.asarray(triangles, dtype="<f4").reshape(-1, 9)
    records = np.zeros(len(tri), dtype=[("normal", "<f4", (3,)), ("tri", "<f4", (9,)),
                                        ("attr", "<u2")])
    records["tri"] = tri
    header = b"plumbob bad-input corpus".ljust(80, b" ")
    return header + struct.pack("<I", len(tri) if count is None else count) + \
        records.tobytes() + extra


def ascii_stl(triangles: np.ndarray, name: str = "part", end: bool = True) -> bytes:
    lines = [f"solid {name}"]
    for t in np.asarray(triangles):
        lines += ["  facet normal 0 0 0", "    outer loop"]
        lines += [f"      vertex {x!r} {y!r} {z!r}" for x, y, z in t.tolist()]
        lines += ["    endloop", "  endfacet"]
    if end:
        lines.append(f"endsolid {name}")
    return ("\n".join(lines) + "\n").encode()


def zip_bytes(members: dict[str, bytes]) -> bytes:
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, data in members.items():
            info = zipfile.ZipInfo(name, date_time=(2020, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            archive.writestr(info, data)
    return buffer.getvalue()


_CONTENT_TYPES = (b'<?xml version="1.0" encoding="UTF-8"?>\n<Types xmlns="http://schemas.'
                  b'openxmlformats.org/package/2006/content-types"><Default Extension="model" '
                  b'ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>'
                  b"</Types>")
_RELS = (b'<?xml version="1.0" encoding="UTF-8"?>\n<Relationships xmlns="http://schemas.'
         b'openxmlformats.org/package/2006/relationships"><Relationship Target="/3D/3dmodel.model"'
         b' Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>'
         b"</Relationships>")


def model_xml(triangles: np.ndarray, unit: str = "millimeter", prolog: str = "") -> bytes:
    """A 3MF model part for one mesh (vertices written per corner, full precision)."""
    v = np.asarray(triangles, dtype=float).reshape(-1, 3)
    verts = "".join(f'<vertex x="{x!r}" y="{y!r}" z="{z!r}"/>' for x, y, z in v.tolist())
    tris = "".join(f'<triangle v1="{3 * i}" v2="{3 * i + 1}" v3="{3 * i + 2}"/>'
                   for i in range(len(v) // 3))
    return (f'<?xml version="1.0" encoding="UTF-8"?>\n{prolog}<model unit="{unit}" '
            'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">'
            f'<resources><object id="1" type="model"><mesh><vertices>{verts}</vertices>'
            f'<triangles>{tris}</triangles></mesh></object></resources>'
            '<build><item objectid="1"/></build></model>').encode()


def three_mf(model: bytes) -> bytes:
    return zip_bytes({"[Content_Types].xml": _CONTENT_TYPES, "_rels/.rels": _RELS,
                      "3D/3dmodel.model": model})


def _zip_bomb() -> bytes:
    """A small 3MF whose central directory declares its model as 2 GiB (a forged bomb:
    a real one would be megabytes of compressed zeros)."""
    data = bytearray(three_mf(model_xml(cube())))
    at = data.rfind(b"PK\x01\x02")  # the model's central directory entry is the last
    struct.pack_into("<I", data, at + 24, 0x7FFFFFFF)
    return bytes(data)


_LAUGHS = ('<!DOCTYPE lolz [<!ENTITY lol "lol">'
           + "".join(f'<!ENTITY lol{i} "{("&lol" + (str(i - 1) if i > 1 else "") + ";") * 10}">'
                     for i in range(1, 10))
           + "]>\n")


def _minimal_dxf(entities: list[tuple[str, dict[int, float | str]]]) -> bytes:
    """A hand-written DXF (no timestamps, so the bytes never change)."""
    out = ["0", "SECTION", "2", "ENTITIES"]
    for kind, tags in entities:
        out += ["0", kind, "8", "0"]
        for code, value in tags.items():
            out += [str(code), str(value)]
    out += ["0", "ENDSEC", "0", "EOF"]
    return ("\n".join(out) + "\n").encode()


# ------------------------------------------------------------------ the corpus
def contents() -> dict[str, bytes | None]:
    """File name → bytes (None: a folder; names absent here are not created)."""
    box = cube()
    fine = cube(4)
    flipped = box.copy()
    flipped[3] = flipped[3, ::-1]
    nan = box.copy()
    nan[4, 1, 2] = np.nan
    infinite = ascii_stl(box).replace(b"vertex 1.0 1.0 1.0", b"vertex 1.0 inf 1.0", 1)
    pen = cube() * np.array([2000.0, 1 / 128, 1 / 128])
    square = np.array([[[0, 0, 0], [1, 0, 0], [1, 1, 0]], [[0, 0, 0], [1, 1, 0], [0, 1, 0]]], float)
    flat = np.concatenate((square, square[:, ::-1]))
    degenerate = np.array([[[0, 0, 0], [1, 0, 0], [2, 0, 0]]] * 4, float)
    top = np.isclose(box[:, :, 2], 1.0).all(axis=1)
    ascii_lines = ascii_stl(box).split(b"\n")
    bad_number = b"\n".join(ascii_lines[:3] + [b"      vertex 0.0 0.0 zero"] + ascii_lines[4:])
    svg = '<svg xmlns="http://www.w3.org/2000/svg">{}</svg>'
    return {
        "folder.stl": None,
        "unknown.xyz": b"1 2 3\n",
        "empty.stl": b"",
        "garbage.stl": b"hello world",
        "truncated.stl": binary_stl(box)[: 84 + 50 * 7 + 20],
        "overlong.stl": binary_stl(box, extra=b"x" * 17),
        "truncated_ascii.stl": b"\n".join(ascii_stl(box).split(b"\n")[:40]),
        "bad_number.stl": bad_number,
        "no_facets.stl": b"solid nothing\nendsolid nothing\n",
        "nan.stl": binary_stl(nan),
        "infinite.stl": infinite,
        "absurd.stl": binary_stl(box * 1e12),
        "open.stl": binary_stl(fine[1:]),
        "open_big.stl": binary_stl(box[~top]),
        "winding.stl": binary_stl(flipped),
        "inside_out.stl": binary_stl(box[:, ::-1]),
        "overlap.stl": binary_stl(np.concatenate((box, cube(offset=(0.5, 0, 0))))),
        "flat.stl": binary_stl(flat),
        "degenerate.stl": binary_stl(degenerate),
        "pen_2000m.stl": binary_stl(pen),
        "corrupt.3mf": b"PK\x03\x04 this is not a zip archive",
        "zip_bomb.3mf": _zip_bomb(),
        "entities.3mf": three_mf(model_xml(box, prolog=_LAUGHS)),
        "nonsense.obj": b"this is not an OBJ file\n",
        "entities.svg": (_LAUGHS.replace("lolz", "svg")
                         + svg.format("<text>&lol9;</text>")).encode(),
        "open_path.svg": svg.format('<path id="cut" d="M 0 0 L 10 0 L 10 10"/>').encode(),
        "crossing.svg": svg.format('<rect x="0" y="0" width="10" height="10"/>'
                                   '<rect x="5" y="5" width="10" height="10"/>').encode(),
        "not_xml.svg": b'<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0 L1 0 L1 1 Z">',
        "no_closed.dxf": _minimal_dxf([("LINE", {10: 0.0, 20: 0.0, 30: 0.0, 11: 1.0, 21: 0.0,
                                                  31: 0.0}),
                                        ("LINE", {10: 1.0, 20: 0.0, 30: 0.0, 11: 1.0, 21: 1.0,
                                                  31: 0.0})]),
        "bowtie.geojson": b'{"type": "Polygon", "coordinates": [[[0, 0], [2, 2], [2, 0], [0, 2], '
                          b'[0, 0]]]}\n',
        "bowtie.csv": b"x,y\n0,0\n2,2\n2,0\n0,2\n",
        "zero_area.wkt": b"POLYGON ((0 0, 1 1, 2 2, 0 0))\n",
        "not_json.geojson": b'{"type": "Polygon", "coordinates": [[[0, 0], [1, 0]',
        "nan.csv": b"x,y\n0,0\n1,nan\n1,1\n",
        "bad_row.csv": b"x,y\n0,0\n1,0,5\n1,1\n",
        "bad.wkb": bytes.fromhex("0103000000010000000500000000"),
        "unsupported.dae": b'<?xml version="1.0"?><COLLADA/>',
        "cube.stl.gz": gzip.compress(binary_stl(box), mtime=0),
        "slip.zip": zip_bytes({"../evil.stl": binary_stl(box)}),
        "two.zip": zip_bytes({"a.stl": binary_stl(box), "b.stl": binary_stl(box)}),
    }


def generate(directory: str = HERE) -> list[str]:
    """Write the corpus into ``directory``; return the paths written."""
    os.makedirs(directory, exist_ok=True)
    written = []
    for name, data in contents().items():
        target = os.path.join(directory, name)
        if data is None:
            os.makedirs(target, exist_ok=True)
            keep = os.path.join(target, ".gitkeep")
            if not os.path.exists(keep):
                open(keep, "wb").close()
        else:
            with open(target, "wb") as f:
                f.write(data)
        written.append(target)
    return written


if __name__ == "__main__":
    for path in generate(sys.argv[1] if len(sys.argv) > 1 else HERE):
        print(path)
