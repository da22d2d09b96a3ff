"""plumbob's own STL reader: binary and ASCII, chunked, several solids, units."""

import os
import sys

import numpy as np
import pytest
import trimesh
from conftest import rel

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "bad_inputs"))
from make_bad_inputs import ascii_stl, binary_stl, cube  # noqa: E402

from plumbob.bodies.csg import Assembly  # noqa: E402
from plumbob.bodies.solid import MeshSolid  # noqa: E402
from plumbob.errors import InputFileError  # noqa: E402
from plumbob.formats import read  # noqa: E402
from plumbob.formats import stl as stl_module  # noqa: E402
from plumbob.formats.stl import load_stl, read_stl  # noqa: E402
from plumbob.units import UNITS_ASSUMED  # noqa: E402


def box(a: float, b: float, c: float, offset=(0.0, 0.0, 0.0)) -> np.ndarray:
    """Triangles of the box [0, a]×[0, b]×[0, c] + offset, wound outward."""
    return cube() * np.array([a, b, c]) + np.asarray(offset)


def box_inertia(mass, a, b, c):
    return mass / 12 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])


def write(path, data: bytes) -> str:
    with open(path, "wb") as f:
        f.write(data)
    return str(path)


def test_binary_and_ascii_give_the_closed_form_box(tmp_path):
    tri = box(0.5, 2.0, 4.0, offset=(1.0, -3.0, 0.25))  # dyadic: exact in float32 too
    for data in (binary_stl(tri), ascii_stl(tri)):
        reading = read(write(tmp_path / "box.stl", data))
        props = reading.body.mass_properties()
        assert props.volume == 4.0
        assert rel(props.center_of_mass, [1.25, -2.0, 2.25]) < 1e-15
        assert rel(props.inertia, box_inertia(4.0, 0.5, 2.0, 4.0)) < 1e-12
        assert reading.notices == (UNITS_ASSUMED,)


def test_float32_binary_agrees_with_float64_ascii_and_trimesh(tmp_path):
    sphere = trimesh.creation.icosphere(subdivisions=3, radius=0.7)
    tri = sphere.triangles
    binary = read(write(tmp_path / "b.stl", binary_stl(tri))).body
    text = read(write(tmp_path / "a.stl", ascii_stl(tri))).body
    assert binary.triangles.dtype == np.float32  # kept, not upcast
    assert text.triangles.dtype == np.float64
    pb, pa = binary.mass_properties(), text.mass_properties()
    assert pa.volume == pytest.approx(sphere.volume, rel=1e-12)
    assert rel(pa.inertia, sphere.moment_inertia) < 1e-12
    assert pb.volume == pytest.approx(pa.volume, rel=1e-6)
    assert rel(pb.inertia, pa.inertia) < 1e-6
    assert rel(pb.center_of_mass, pa.center_of_mass, scale=1.4) < 1e-7


@pytest.mark.parametrize("chunk", [1, 5, 7, 1000])
def test_binary_chunks_do_not_matter(tmp_path, monkeypatch, chunk):
    tri = box(1.0, 2.0, 3.0)
    path = write(tmp_path / "b.stl", binary_stl(tri))
    monkeypatch.setattr(stl_module, "CHUNK", chunk)
    loaded = load_stl(path)
    assert np.array_equal(loaded.solids[0].triangles, tri.astype(np.float32))
    assert loaded.reach == 3.0 and loaded.binary


@pytest.mark.parametrize("block", [64, 300, 4096])
def test_ascii_blocks_do_not_matter(tmp_path, monkeypatch, block):
    a, b = box(1.0, 1.0, 1.0), box(2.0, 1.0, 1.0, offset=(5, 0, 0))
    data = ascii_stl(a, "first") + ascii_stl(b, "second")
    path = write(tmp_path / "two.stl", data)
    monkeypatch.setattr(stl_module, "ASCII_BLOCK", block)
    loaded = load_stl(path)
    assert [s.name for s in loaded.solids] == ["first", "second"]
    assert np.array_equal(loaded.solids[0].triangles, a)
    assert np.array_equal(loaded.solids[1].triangles, b)


def test_several_ascii_solids_are_an_assembly(tmp_path):
    data = ascii_stl(box(1, 1, 1), "lid") + ascii_stl(box(2, 1, 1, (5, 0, 0)), "base")
    reading = read(write(tmp_path / "parts.stl", data))
    body = reading.body
    assert isinstance(body, Assembly) and body.name == "parts"
    assert [p.name for p in body.parts] == ["lid", "base"]
    assert [p.mass_properties().volume for p in body.parts] == [1.0, 2.0]
    total = body.mass_properties()
    assert total.volume == 3.0
    assert total.center_of_mass == pytest.approx([(0.5 + 2 * 6.0) / 3, 0.5, 0.5])


def test_ascii_variants_read_the_same(tmp_path):
    tri = box(1.0, 2.0, 3.0)
    plain = ascii_stl(tri)
    variants = [
        plain.replace(b"\n", b"\r\n"),
        plain.upper(),
        plain.replace(b"      vertex ", b"\tvertex\t  "),
        plain.replace(b"vertex 0.0", b"vertex 0.0e+00").replace(b" 1.0", b" 1e0"),
    ]
    expected = read(write(tmp_path / "p.stl", plain)).body.mass_properties()
    for i, data in enumerate(variants):
        got = read(write(tmp_path / f"v{i}.stl", data)).body.mass_properties()
        assert got.volume == expected.volume
        assert rel(got.inertia, expected.inertia) == 0


def test_units_scale_lengths_and_say_so(tmp_path):
    path = write(tmp_path / "mm.stl", binary_stl(box(10.0, 20.0, 40.0)))
    reading = read(path, units="mm")
    props = reading.body.mass_properties()
    assert props.volume == pytest.approx(8000e-9, rel=1e-15)
    assert rel(props.center_of_mass, [0.005, 0.01, 0.02]) < 1e-15
    assert UNITS_ASSUMED not in reading.notices
    assert read(path).body.mass_properties().volume == 8000.0


def test_names_from_binary_header_and_file(tmp_path):
    data = bytearray(binary_stl(box(1, 1, 1)))
    data[:80] = b"solid widget".ljust(80, b"\0")  # a binary file whose header starts 'solid'
    body = read(write(tmp_path / "w.stl", bytes(data))).body
    assert isinstance(body, MeshSolid) and body.name == "widget"
    data[:80] = b"COLOR=\xff\x00\x00\x00".ljust(80, b"\0")
    assert read(write(tmp_path / "colour.stl", bytes(data))).body.name == "colour"
    data[:80] = b"Exported by SomeCAD 2024".ljust(80, b" ")
    assert read(write(tmp_path / "banner.stl", bytes(data))).body.name == "banner"


def test_missing_endsolid_is_a_notice(tmp_path):
    path = write(tmp_path / "cut.stl", ascii_stl(box(1, 1, 1), end=False))
    reading = read(path)
    assert reading.body.mass_properties().volume == 1.0
    assert any("no 'endsolid'" in n for n in reading.notices)


def test_read_stl_direct_and_empty_file(tmp_path):
    path = write(tmp_path / "b.stl", binary_stl(box(1, 1, 1)))
    assert read_stl(path).body.mass_properties().volume == 1.0
    with pytest.raises(InputFileError, match="is empty"):
        load_stl(write(tmp_path / "e.stl", b""))


def test_binary_memory_is_the_triangles_only(tmp_path):
    import tracemalloc

    sphere = trimesh.creation.icosphere(subdivisions=5)
    path = write(tmp_path / "s.stl", binary_stl(sphere.triangles))
    size = os.path.getsize(path)
    tracemalloc.start()
    loaded = load_stl(path)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert loaded.solids[0].triangles.nbytes == 36 * len(sphere.faces)
    assert peak < 0.72 * size + 4_000_000  # the float32 array plus one chunk of records
