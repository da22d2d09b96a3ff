"""Hostile mesh files: each is generated into ``tmp_path`` and read by the command line
inside the hostile-input limits (10 s, 1 GiB); each ends in one line and exit status 2
naming what is wrong, or in the right answer."""

from __future__ import annotations

import json
import struct
import zipfile

import numpy as np
import pytest
from hostile import assert_bad_input, run_limited

from plumbob import limits
from plumbob.errors import LimitError
from plumbob.formats import read

# A unit cube: 8 vertices, 12 outward triangles (1-based OBJ faces below).
CUBE_V = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
QUADS = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
CUBE_F = np.array([f for a, b, c, d in QUADS for f in ((a, b, c), (a, c, d))])


def binary_stl(triangles: np.ndarray, count: int | None = None) -> bytes:
    """A binary STL of ``triangles`` whose header announces ``count`` of them."""
    records = np.zeros(len(triangles), dtype=[("n", "<f4", 3), ("t", "<f4", (3, 3)),
                                              ("a", "<u2")])
    records["t"] = triangles
    count = len(triangles) if count is None else count
    return b"hostile".ljust(80, b" ") + struct.pack("<I", count) + records.tobytes()


def obj_text(faces: np.ndarray, vertices: np.ndarray = CUBE_V) -> str:
    lines = [f"v {float(x)!r} {float(y)!r} {float(z)!r}" for x, y, z in vertices]
    lines += ["f " + " ".join(str(i) for i in f) for f in faces]
    return "\n".join(lines) + "\n"


def model_xml(unit: str = "millimeter") -> str:
    vertices = "".join(f'<vertex x="{x}" y="{y}" z="{z}"/>' for x, y, z in CUBE_V)
    triangles = "".join(f'<triangle v1="{a}" v2="{b}" v3="{c}"/>' for a, b, c in CUBE_F)
    return (f'<?xml version="1.0" encoding="UTF-8"?><model unit="{unit}" '
            'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources>'
            f'<object id="1" type="model"><mesh><vertices>{vertices}</vertices><triangles>'
            f'{triangles}</triangles></mesh></object></resources><build><item objectid="1"/>'
            '</build></model>')


CONTENT_TYPES = ('<?xml version="1.0" encoding="UTF-8"?><Types xmlns="http://schemas.openxml'
                 'formats.org/package/2006/content-types"><Default Extension="model" '
                 'ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>'
                 '</Types>')


def write_3mf(path, model: str | bytes) -> None:
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("[Content_Types].xml", CONTENT_TYPES)
        archive.writestr("3D/3dmodel.model", model)


def cli_json(outcome) -> dict:
    assert outcome.status == 0, outcome.stderr[-2000:]
    return json.loads(outcome.stdout)


# ------------------------------------------------------------------ STL
def test_binary_stl_with_no_triangles(tmp_path):
    path = tmp_path / "none.stl"
    path.write_bytes(binary_stl(np.zeros((0, 3, 3))))
    assert_bad_input(run_limited("mass", path), "0 triangles")


@pytest.mark.parametrize("count, phrase", [(13, "truncated"), (11, "corrupt"),
                                           (2**32 - 1, "truncated")])
def test_binary_stl_whose_header_count_disagrees_with_its_size(tmp_path, count, phrase):
    path = tmp_path / "count.stl"
    path.write_bytes(binary_stl(CUBE_V[CUBE_F], count))
    assert_bad_input(run_limited("mass", path), f"header says {count} triangles", phrase)


@pytest.mark.parametrize("value", ["nan", "inf", "-inf"])
def test_stl_with_a_coordinate_that_is_not_finite(tmp_path, value):
    tri = CUBE_V[CUBE_F].copy()
    tri[5, 1, 2] = float(value)
    path = tmp_path / "nonfinite.stl"
    path.write_bytes(binary_stl(tri))
    assert_bad_input(run_limited("mass", path), "triangle 6", "not a finite number")


def test_ascii_stl_with_nan(tmp_path):
    facets = "".join("facet normal 0 0 0\nouter loop\n" + "".join(
        f"vertex {x} {y} {z}\n" for x, y, z in t) + "endloop\nendfacet\n" for t in CUBE_V[CUBE_F])
    path = tmp_path / "nan_ascii.stl"
    path.write_text("solid c\n" + facets.replace("vertex 1.0 1.0 1.0", "vertex nan 1 1", 1)
                    + "endsolid c\n")
    assert_bad_input(run_limited("mass", path), "not a finite number")


def test_triangle_limit_is_checked_from_the_header_before_allocating(tmp_path, monkeypatch):
    path = tmp_path / "many.stl"
    path.write_bytes(binary_stl(CUBE_V[CUBE_F]))
    monkeypatch.setattr(limits, "MAX_TRIANGLES", 10)
    with pytest.raises(LimitError, match="triangles 12 is over plumbob.s limit of 10"):
        read(str(path))


def test_ascii_stl_triangle_limit(tmp_path, monkeypatch):
    facets = "".join("facet normal 0 0 0\nouter loop\n" + "".join(
        f"vertex {x} {y} {z}\n" for x, y, z in t) + "endloop\nendfacet\n" for t in CUBE_V[CUBE_F])
    path = tmp_path / "many_ascii.stl"
    path.write_text("solid c\n" + facets + "endsolid c\n")
    monkeypatch.setattr(limits, "MAX_TRIANGLES", 10)
    with pytest.raises(LimitError, match="over plumbob's limit of 10"):
        read(str(path))


def test_ply_header_face_count_is_checked_before_trimesh(tmp_path):
    path = tmp_path / "many.ply"
    path.write_bytes(b"ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
                     b"property float x\nproperty float y\nproperty float z\n"
                     b"element face 4000000000\nproperty list uchar int vertex_indices\n"
                     b"end_header\n" + bytes(36))
    assert_bad_input(run_limited("mass", path), "faces 4000000000", "limit")


# ------------------------------------------------------------------ open meshes
def test_cube_without_top_and_bottom_is_open(tmp_path):
    tri = CUBE_V[CUBE_F]
    sides = tri[~(np.ptp(tri[:, :, 2], axis=1) == 0)]
    assert len(sides) == 8
    path = tmp_path / "sleeve.stl"
    path.write_bytes(binary_stl(sides))
    assert_bad_input(run_limited("mass", path), "is open", "8 boundary edges", "2 holes",
                     "near")


def test_open_tube_is_open(tmp_path):
    k = 32
    a = 2 * np.pi * np.arange(k) / k
    ring = np.stack((np.cos(a), np.sin(a)), axis=1)
    lo = np.pad(ring, ((0, 0), (0, 1)))
    hi = np.pad(ring, ((0, 0), (0, 1)), constant_values=3.0)
    nxt = np.roll(np.arange(k), -1)
    tri = np.concatenate((np.stack((lo, lo[nxt], hi[nxt]), 1), np.stack((lo, hi[nxt], hi), 1)))
    path = tmp_path / "tube.stl"
    path.write_bytes(binary_stl(tri))
    line = assert_bad_input(run_limited("mass", path), "is open", "64 boundary edges",
                            "2 holes")
    assert "overlapping" not in line


# ------------------------------------------------------------------ OBJ
@pytest.mark.parametrize("shift, phrase, where", [(-1, "index 0", "line 9"),
                                                  (+1, "index 9", "line 11")])
def test_obj_face_index_out_of_range(tmp_path, shift, phrase, where):
    path = tmp_path / "indices.obj"
    path.write_text(obj_text(CUBE_F + 1 + shift))  # 0-based, or one past the end
    line = assert_bad_input(run_limited("mass", path), phrase, where)
    assert "8 vertices" in line


def test_obj_negative_index_beyond_the_vertices(tmp_path):
    path = tmp_path / "negative.obj"
    path.write_text(obj_text(CUBE_F + 1) + "f -1 -2 -9\n")
    assert_bad_input(run_limited("mass", path), "index -9", "line 21")


def test_obj_continued_lines_are_joined_and_errors_name_the_physical_line(tmp_path):
    faces = ["f " + " ".join(str(i) for i in f) for f in CUBE_F + 1]
    faces[0] = faces[0].replace(" ", " \\\n", 1)  # 'f \' then the indices on the next line
    good = obj_text(np.zeros((0, 3), dtype=int)) + "\n".join(faces) + "\n"
    path = tmp_path / "continued.obj"
    path.write_text(good)
    assert cli_json(run_limited("mass", path, "--json"))["volume"] == pytest.approx(1.0)
    path.write_text(good + "f 1 2 \\\n 99\n")
    assert_bad_input(run_limited("mass", path), "line 22", "index 99")


def test_obj_materials_are_one_body(tmp_path):
    half = len(CUBE_F) // 2
    text = obj_text(np.zeros((0, 3), dtype=int)) + "usemtl a\n" + "".join(
        "f " + " ".join(map(str, f)) + "\n" for f in CUBE_F[:half] + 1) + "usemtl b\n" + "".join(
        "f " + " ".join(map(str, f)) + "\n" for f in CUBE_F[half:] + 1)
    path = tmp_path / "materials.obj"
    path.write_text(text)
    assert cli_json(run_limited("mass", path, "--json"))["volume"] == pytest.approx(1.0)


def test_obj_relative_indices_read_right(tmp_path):
    path = tmp_path / "relative.obj"
    path.write_text(obj_text(CUBE_F - 8))  # -8..-1: the eight vertices above
    data = cli_json(run_limited("mass", path, "--json"))
    assert data["volume"] == pytest.approx(1.0, rel=1e-15)


def test_obj_with_nan(tmp_path):
    vertices = CUBE_V.copy()
    vertices[3, 0] = np.nan
    path = tmp_path / "nan.obj"
    path.write_text(obj_text(CUBE_F + 1, vertices))
    assert_bad_input(run_limited("mass", path), "not a finite number")


# ------------------------------------------------------------------ 3MF
def test_3mf_reads_in_its_declared_unit(tmp_path):
    path = tmp_path / "cube.3mf"
    write_3mf(path, model_xml("centimeter"))
    data = cli_json(run_limited("mass", path, "--json"))
    assert data["volume"] == pytest.approx(1e-6, rel=1e-12)


def test_3mf_whose_zip_claims_a_later_version(tmp_path):
    path = tmp_path / "version.3mf"
    write_3mf(path, model_xml())
    data = bytearray(path.read_bytes())
    for signature in (b"PK\x03\x04", b"PK\x01\x02"):  # local and central headers
        start = 0
        while (at := data.find(signature, start)) >= 0:
            field = at + (4 if signature == b"PK\x03\x04" else 6)  # version needed
            data[field:field + 2] = struct.pack("<H", 84)  # "8.4"
            start = at + 4
    path.write_bytes(bytes(data))
    assert_bad_input(run_limited("mass", path), "zip")


def test_3mf_zip_bomb_is_refused_before_it_expands(tmp_path):
    path = tmp_path / "bomb.3mf"
    filler = b"<!-- " + b"A" * (64 * 2**20) + b" -->"  # 64 MiB of comment, ~64 KB packed
    write_3mf(path, model_xml().encode().replace(b"<resources>", b"<resources>" + filler))
    assert path.stat().st_size < 2**20
    assert_bad_input(run_limited("mass", path), "expand", "zip bomb")


def test_3mf_whose_declared_sizes_exceed_the_archive_limit(tmp_path, monkeypatch):
    path = tmp_path / "big.3mf"
    write_3mf(path, model_xml())
    monkeypatch.setattr(limits, "MAX_ARCHIVE_BYTES", 1000)
    with pytest.raises(LimitError, match="MAX_ARCHIVE_BYTES"):
        read(str(path))


def test_3mf_with_an_entity_declaration(tmp_path):
    path = tmp_path / "entities.3mf"
    xml = model_xml().replace('<?xml version="1.0" encoding="UTF-8"?>',
                              '<?xml version="1.0"?><!DOCTYPE model [<!ENTITY a "aaaa">]>')
    write_3mf(path, xml)
    assert_bad_input(run_limited("mass", path), "entities")


def test_3mf_with_a_face_index_past_its_vertices(tmp_path):
    path = tmp_path / "index.3mf"
    write_3mf(path, model_xml().replace('v3="2"', 'v3="99"', 1))
    assert_bad_input(run_limited("mass", path))


# ------------------------------------------------------------------ units
def test_a_figurine_in_millimetres_gets_a_loud_notice(tmp_path):
    tri = CUBE_V[CUBE_F] * np.array([40.0, 30.0, 119.0])  # 119 "m" tall: millimetres
    path = tmp_path / "figurine.stl"
    path.write_bytes(binary_stl(tri))
    outcome = run_limited("mass", path)
    assert outcome.status == 0
    assert "119 m" in outcome.stderr and "--units mm" in outcome.stderr
    assert "implausible" in outcome.stderr.lower()
