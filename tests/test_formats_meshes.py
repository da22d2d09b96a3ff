"""The same solid in every mesh format gives the same mass properties; scenes, units, limits."""

import os
import sys

import numpy as np
import pytest
import trimesh
from conftest import rel

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "bad_inputs"))
from make_bad_inputs import ascii_stl, binary_stl, cube, model_xml, three_mf  # noqa: E402

from plumbob import limits  # noqa: E402
from plumbob.bodies.csg import Assembly  # noqa: E402
from plumbob.bodies.solid import MeshSolid  # noqa: E402
from plumbob.errors import ArgumentError, FormatError, GeometryError, LimitError  # noqa: E402
from plumbob.formats import read  # noqa: E402
from plumbob.formats.meshes import read_mesh  # noqa: E402


def irregular() -> trimesh.Trimesh:
    """A closed, non-convex, non-symmetric mesh: a box united with a tilted cylinder."""
    box = trimesh.creation.box([1.0, 2.0, 0.7])
    cyl = trimesh.creation.cylinder(0.3, 2.0, sections=24)
    cyl.apply_transform(trimesh.transformations.rotation_matrix(0.6, [1, 0.3, 0]))
    cyl.apply_translation([0.4, 0.2, 0.1])
    mesh = trimesh.boolean.union([box, cyl], engine="manifold")
    mesh.apply_translation([0.3, -0.2, 0.5])
    assert mesh.is_watertight
    return mesh


def obj_text(v, f) -> bytes:
    return ("".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in v.tolist())
            + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in f.tolist())).encode()


def off_text(v, f) -> bytes:
    return (f"OFF\n{len(v)} {len(f)} 0\n"
            + "".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in v.tolist())
            + "".join(f"3 {a} {b} {c}\n" for a, b, c in f.tolist())).encode()


def ply_text(v, f) -> bytes:
    head = (f"ply\nformat ascii 1.0\nelement vertex {len(v)}\n"
            "property double x\nproperty double y\nproperty double z"
            f"\nelement face {len(f)}\nproperty list uchar int vertex_indices\n"
            "end_header\n")
    return (head + "".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in v.tolist())
            + "".join(f"3 {a} {b} {c}\n" for a, b, c in f.tolist())).encode()


def write(path, data: bytes) -> str:
    with open(path, "wb") as f:
        f.write(data)
    return str(path)


def test_same_solid_in_every_format(tmp_path):
    mesh = irregular()
    v, f = np.asarray(mesh.vertices), np.asarray(mesh.faces)
    reference = MeshSolid(mesh.triangles).mass_properties()
    assert reference.volume == pytest.approx(mesh.volume, rel=1e-12)  # a second method
    exact = {  # formats that store float64 (written with full precision)
        "a.stl": ascii_stl(mesh.triangles),
        "m.obj": obj_text(v, f),
        "m.ply": ply_text(v, f),
        "m.off": off_text(v, f),
        "m.3mf": three_mf(model_xml(mesh.triangles, unit="meter")),
    }
    for name, data in exact.items():
        props = read(write(tmp_path / name, data)).body.mass_properties()
        assert props.volume == pytest.approx(reference.volume, rel=1e-12), name
        assert rel(props.center_of_mass, reference.center_of_mass, scale=mesh.scale) < 1e-12, name
        assert rel(props.inertia, reference.inertia) < 1e-12, name
    mesh.export(tmp_path / "m.glb")
    float32 = {"b.stl": write(tmp_path / "b.stl", binary_stl(mesh.triangles)),
               "m.glb": str(tmp_path / "m.glb")}
    for name, path in float32.items():
        props = read(path).body.mass_properties()
        assert props.volume == pytest.approx(reference.volume, rel=1e-6), name
        assert rel(props.center_of_mass, reference.center_of_mass, scale=mesh.scale) < 1e-6, name
        assert rel(props.inertia, reference.inertia) < 1e-6, name


def test_3mf_units_come_from_the_file(tmp_path):
    path = write(tmp_path / "mm.3mf", three_mf(model_xml(cube(size=10.0))))
    reading = read(path)
    assert reading.body.mass_properties().volume == pytest.approx(1e-6, rel=1e-15)
    assert "units: millimeter (from the file)" in reading.notices
    with pytest.raises(ArgumentError, match="--units-override"):
        read(path, units="cm")  # contradicts the file's unit
    override = read(path, units="cm", units_override=True)
    assert override.body.mass_properties().volume == pytest.approx(1e-3, rel=1e-15)
    assert any("file says millimeter" in n for n in override.notices)


def test_obj_without_units_says_metres_assumed(tmp_path):
    mesh = trimesh.creation.box([1.0, 2.0, 3.0])
    reading = read(write(tmp_path / "b.obj", obj_text(mesh.vertices, mesh.faces)))
    assert reading.body.mass_properties().volume == pytest.approx(6.0, rel=1e-15)
    assert any("metres assumed" in n for n in reading.notices)


def test_scene_with_several_meshes_is_an_assembly(tmp_path):
    small = trimesh.creation.box([1.0, 1.0, 1.0])
    big = trimesh.creation.box([2.0, 2.0, 2.0])
    scene = trimesh.Scene()
    scene.add_geometry(small, node_name="small")
    scene.add_geometry(big, node_name="big", transform=trimesh.transformations.translation_matrix(
        [5.0, 0.0, 0.0]))
    path = tmp_path / "two.glb"
    scene.export(path)
    reading = read(str(path))
    body = reading.body
    assert isinstance(body, Assembly)
    parts = {p.name: p.mass_properties() for p in body.parts}
    assert parts["small"].volume == pytest.approx(1.0, rel=1e-6)
    assert parts["big"].volume == pytest.approx(8.0, rel=1e-6)
    assert parts["big"].center_of_mass == pytest.approx([5.0, 0.0, 0.0], abs=1e-6)
    total = body.mass_properties()
    assert total.center_of_mass[0] == pytest.approx(40.0 / 9.0, rel=1e-6)
    assert "units: meter (from the file)" in reading.notices


def test_mirrored_instance_keeps_outward_winding(tmp_path):
    mesh = trimesh.creation.box([1.0, 2.0, 3.0])
    scene = trimesh.Scene()
    mirror = np.diag([-1.0, 1.0, 1.0, 1.0])
    mirror[0, 3] = 4.0
    scene.add_geometry(mesh, node_name="mirrored", transform=mirror)
    path = tmp_path / "mirror.glb"
    scene.export(path)
    reading = read(str(path))
    props = reading.body.mass_properties()
    assert props.volume == pytest.approx(6.0, rel=1e-6)
    assert props.center_of_mass == pytest.approx([4.0, 0.0, 0.0], abs=1e-6)
    assert not any("inside out" in n for n in reading.notices)


def test_3mf_expansion_limit_is_checked_before_reading(tmp_path, monkeypatch):
    path = write(tmp_path / "cube.3mf", three_mf(model_xml(cube())))
    assert read_mesh(path).body.mass_properties().volume == pytest.approx(1e-9)
    monkeypatch.setattr(limits, "MAX_ARCHIVE_BYTES", 1000)
    with pytest.raises(LimitError, match="MAX_ARCHIVE_BYTES"):
        read_mesh(path)


def test_3mf_without_a_model_is_refused(tmp_path):
    import zipfile

    path = tmp_path / "empty.3mf"
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("readme.txt", "no model here")
    with pytest.raises(FormatError, match="no 3D model part"):
        read(str(path))


def test_open_obj_is_reported_like_an_stl(tmp_path):
    soup = cube(4)[1:]  # 191 of a cube's 192 triangles, corners unshared in the file
    path = write(tmp_path / "open.obj", obj_text(soup.reshape(-1, 3),
                                                 np.arange(3 * len(soup)).reshape(-1, 3)))
    with pytest.raises(GeometryError, match="3 boundary edges"):
        read(path)
    repaired = read(path, repair=True)
    assert repaired.body.mass_properties().volume == pytest.approx(1.0, rel=1e-12)


def test_gltf_with_an_external_buffer(tmp_path):
    mesh = trimesh.creation.box([1.0, 2.0, 3.0])
    files = trimesh.Scene([mesh]).export(file_type="gltf")  # {name: bytes}
    for name, data in files.items():
        (tmp_path / name).write_bytes(data)
    gltf = next(n for n in files if n.endswith(".gltf"))
    assert any(not n.endswith(".gltf") for n in files)  # the buffer is a file of its own
    props = read(str(tmp_path / gltf)).body.mass_properties()
    assert props.volume == pytest.approx(6.0, rel=1e-6)
