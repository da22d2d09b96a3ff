"""Fuzzing: generated and mutated bytes through every reader.

Whatever the bytes, ``read`` either returns a body or raises a PlumbobError —
never another exception — and it answers promptly (hypothesis' deadline).
"""

import os
import sys
import tempfile

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "bad_inputs"))
from make_bad_inputs import ascii_stl, binary_stl, cube, model_xml, three_mf  # noqa: E402

from plumbob.errors import PlumbobError  # noqa: E402
from plumbob.formats import SUFFIXES, read  # noqa: E402

# PLUMBOB_FUZZ_EXAMPLES=2000 runs a deeper, randomised search (default: 15, repeatable).
_DEEP = int(os.environ.get("PLUMBOB_FUZZ_EXAMPLES", "0"))
FUZZ = settings(max_examples=_DEEP or 15, deadline=5000, derandomize=not _DEEP,
                suppress_health_check=list(HealthCheck))


def _seeds() -> dict[str, bytes]:
    """A small valid file per suffix, to mutate."""
    import io

    import ezdxf
    import shapely
    import trimesh

    box = trimesh.creation.box([1.0, 2.0, 3.0])
    glb = box.export(file_type="glb")
    doc = ezdxf.new()
    doc.modelspace().add_lwpolyline([(0, 0, 0.5), (2, 0, 0), (2, 1, 0)], format="xyb", close=True)
    doc.modelspace().add_circle((5, 5), 1)
    stream = io.StringIO()
    doc.write(stream)
    stl = binary_stl(cube())
    return {
        **_archive_seeds(stl),
        ".stl": binary_stl(cube()),
        ".stl ascii": ascii_stl(cube()),
        ".obj": box.export(file_type="obj").encode(),
        ".ply": box.export(file_type="ply"),
        ".off": box.export(file_type="off").encode(),
        ".3mf": three_mf(model_xml(cube())),
        ".glb": glb,
        ".gltf": b'{"asset": {"version": "2.0"}, "meshes": []}',
        ".geojson": b'{"type": "Polygon", "coordinates": [[[0, 0], [2, 0], [2, 1], [0, 0]]]}',
        ".json": b'{"type": "Feature", "properties": {}, "geometry": {"type": "MultiPolygon", '
                 b'"coordinates": [[[[0, 0], [2, 0], [2, 1], [0, 0]]]]}}',
        ".wkt": b"POLYGON ((0 0, 4 0, 4 3, 0 0), (1 0.5, 2 0.5, 2 1, 1 0.5))",
        ".wkb": shapely.from_wkt("POLYGON ((0 0, 4 0, 4 3, 0 0))").wkb,
        ".csv": b"x,y\n0,0\n2,0\n2,1\n\n0.5,0.2\n1.5,0.2\n1.5,0.6\n",
        ".svg": b'<svg xmlns="http://www.w3.org/2000/svg" width="10mm" viewBox="0 0 10 10">'
                b'<path d="M 1 1 L 9 1 A 4 4 0 0 1 1 1 Z"/><ellipse cx="5" cy="3" rx="1" ry="1.5"/>'
                b'<path d="M 12 2 Q 13 4 14 2 C 14 1 12 1 12 2 Z"/></svg>',
        ".dxf": stream.getvalue().encode(),
    }


def _archive_seeds(stl: bytes) -> dict[str, bytes]:
    """A cube STL compressed, zipped and tarred (the member is named ``cube.stl``)."""
    import bz2
    import gzip
    import io
    import lzma
    import tarfile
    import zipfile

    packed = io.BytesIO()
    with zipfile.ZipFile(packed, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("cube.stl", stl)
    tarred = io.BytesIO()
    with tarfile.open(fileobj=tarred, mode="w") as archive:
        member = tarfile.TarInfo("cube.stl")
        member.size = len(stl)
        archive.addfile(member, io.BytesIO(stl))
    return {".zip": packed.getvalue(), ".gz": gzip.compress(stl), ".bz2": bz2.compress(stl),
            ".xz": lzma.compress(stl), ".tar": tarred.getvalue(),
            ".tgz": gzip.compress(tarred.getvalue())}


def _name(suffix: str) -> str:
    """A file name for ``suffix``: a compressed file is named for what it holds."""
    return ("fuzz.stl" if suffix in (".gz", ".bz2", ".xz") else "fuzz") + suffix


SEEDS = _seeds()
#: CAD formats: each read starts OpenCASCADE in a child process (about a second), so they
#: are fuzzed with fewer examples below; their hostile files are in test_formats_step.py
CAD = (".brep", ".iges", ".igs", ".step", ".stp")
READERS = sorted(s for s in SUFFIXES if s != ".toml" and s not in CAD)
CAD_FUZZ = settings(max_examples=_DEEP or 3, deadline=None, derandomize=not _DEEP,
                    suppress_health_check=list(HealthCheck))
STAND = os.path.join(os.path.dirname(os.path.dirname(__file__)), "docs", "models", "stand.step")


def _outcome(suffix: str, data: bytes) -> None:
    """Read ``data`` as a ``suffix`` file; only a PlumbobError may escape."""
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, _name(suffix))
        with open(path, "wb") as f:
            f.write(data)
        try:
            reading = read(path)
            reading.body.mass_properties()
        except PlumbobError as error:
            assert str(error).startswith(path)


def test_every_reader_has_a_seed():
    assert {s.split()[0] for s in SEEDS} == set(READERS)
    assert set(SUFFIXES) - {".toml"} == set(READERS) | set(CAD)  # every reader fuzzed
    for suffix in READERS:  # and every seed reads
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, _name(suffix))
            with open(path, "wb") as f:
                f.write(SEEDS[suffix])
            if suffix == ".gltf":
                with pytest.raises(PlumbobError, match="no triangle mesh"):
                    read(path)
            else:
                assert read(path).body.mass_properties().measure > 0


@pytest.mark.parametrize("suffix", READERS)
@FUZZ
@given(data=st.binary(max_size=600))
def test_random_bytes(suffix, data):
    _outcome(suffix, data)


@st.composite
def mutations(draw, seed: bytes) -> bytes:
    data = bytearray(seed)
    for _ in range(draw(st.integers(1, 6))):
        kind = draw(st.sampled_from(["flip", "insert", "delete", "truncate", "digit"]))
        at = draw(st.integers(0, max(len(data) - 1, 0)))
        if kind == "flip" and data:
            data[at] ^= 1 << draw(st.integers(0, 7))
        elif kind == "insert":
            data[at:at] = draw(st.binary(min_size=1, max_size=8))
        elif kind == "delete" and data:
            del data[at:at + draw(st.integers(1, 16))]
        elif kind == "truncate":
            del data[at:]
        elif kind == "digit" and data:  # numbers made huge, tiny, NaN or negative
            data[at:at] = draw(st.sampled_from([b"e300", b"9999999999", b"nan", b"-", b"inf"]))
    return bytes(data)


@pytest.mark.parametrize("seed", sorted(SEEDS))
@FUZZ
@given(data=st.data())
def test_mutated_files(seed, data):
    _outcome(seed.split()[0], data.draw(mutations(SEEDS[seed])))


@FUZZ
@given(st.lists(st.floats(allow_nan=True, allow_infinity=True, width=32), min_size=9,
                max_size=9 * 40).map(lambda v: np.array(v[: len(v) // 9 * 9], dtype="<f4")))
def test_binary_stl_with_any_coordinates(coordinates):
    _outcome(".stl", binary_stl(coordinates.reshape(-1, 3, 3)))


@pytest.mark.parametrize("suffix", CAD)
@CAD_FUZZ
@given(data=st.binary(max_size=600))
def test_random_bytes_as_cad(suffix, data):
    _outcome(suffix, data)


@CAD_FUZZ
@given(data=st.data())
def test_mutated_step_files(data):
    """The worked example's STEP assembly, mutated (its parts give no density, so an
    intact read is refused too: only a PlumbobError may come out)."""
    with open(STAND, "rb") as handle:
        seed = handle.read()
    _outcome(".step", data.draw(mutations(seed)))
