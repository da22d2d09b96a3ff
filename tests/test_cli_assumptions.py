"""No silent defaults where they change an answer, and each format's own conventions.

* every output says on stderr what it assumed (density, units, up axis), one line each;
* ``mass --format urdf|sdf|mjcf`` refuses a body without a density (exit 2, one line);
* a ``--units`` that contradicts the unit a file declares (3MF, glTF, DXF, a spec's
  ``units``) is refused unless ``--units-override``;
* glTF/GLB are +y up by their specification and rest on −y; STL, OBJ, PLY and 3MF +z.
"""

from __future__ import annotations

import json
import zipfile

import numpy as np
import pytest
from hostile import assert_bad_input, run_in_process

DENSITY_LINE = "no density given: 1 kg/m³"
UP_Z_LINE = "up: +z assumed"


def _tee_mesh() -> tuple[np.ndarray, np.ndarray]:
    """An upright "T" in glTF's frame: a 1 × 0.1 × 1 m plate in the xz-plane at y = 0..0.1
    and a 0.2 × 2 × 0.2 m post up +y. It stands on its plate (−y down); on −z it lies on
    the plate's edge, 0.1 m deep, under a centre 0.5 m up the post: it topples."""
    import manifold3d

    plate = manifold3d.Manifold.cube([1.0, 0.1, 1.0]).translate([-0.5, 0.0, -0.5])
    post = manifold3d.Manifold.cube([0.2, 2.0, 0.2]).translate([-0.1, 0.05, -0.1])
    mesh = (plate + post).to_mesh64()
    return np.asarray(mesh.vert_properties)[:, :3], np.asarray(mesh.tri_verts)


@pytest.fixture(scope="module")
def tee(tmp_path_factory):
    """The T as GLB, STL, OBJ, PLY and 3MF (metres) in one folder."""
    import trimesh

    folder = tmp_path_factory.mktemp("tee")
    vertices, faces = _tee_mesh()
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    for suffix in ("glb", "stl", "obj", "ply"):
        mesh.export(folder / f"tee.{suffix}")
    (folder / "tee.3mf").write_bytes(_threemf(vertices, faces, "meter"))
    return folder


def _threemf(vertices: np.ndarray, faces: np.ndarray, unit: str) -> bytes:
    """A minimal 3MF archive of one mesh in ``unit``."""
    import io

    verts = "".join(f'<vertex x="{x!r}" y="{y!r}" z="{z!r}"/>' for x, y, z in vertices.tolist())
    tris = "".join(f'<triangle v1="{a}" v2="{b}" v3="{c}"/>' for a, b, c in faces.tolist())
    model = (f'<?xml version="1.0" encoding="UTF-8"?>\n<model unit="{unit}" xml:lang="en-US" '
             'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources>'
             f'<object id="1" type="model"><mesh><vertices>{verts}</vertices><triangles>{tris}'
             '</triangles></mesh></object></resources><build><item objectid="1"/></build></model>')
    types = ('<?xml version="1.0" encoding="UTF-8"?>\n<Types xmlns="http://schemas.openxmlformats'
             '.org/package/2006/content-types"><Default Extension="rels" ContentType="application/'
             'vnd.openxmlformats-package.relationships+xml"/><Default Extension="model" '
             'ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>')
    rels = ('<?xml version="1.0" encoding="UTF-8"?>\n<Relationships xmlns="http://schemas.'
            'openxmlformats.org/package/2006/relationships"><Relationship Target="/3D/3dmodel.'
            'model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/'
            '3dmodel"/></Relationships>')
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as archive:
        archive.writestr("[Content_Types].xml", types)
        archive.writestr("_rels/.rels", rels)
        archive.writestr("3D/3dmodel.model", model)
    return buffer.getvalue()


def _notes(outcome) -> list[str]:
    return [line for line in outcome.lines if line.startswith("plumbob: note: ")]


# ------------------------------------------------------------------ up axis
def test_a_glb_rests_on_minus_y(capsys, tee):
    """glTF is +y up: `check` rests the T on its plate (it stands), says so on stderr and
    puts the chosen direction in the JSON; told −z it topples, as the STL does."""
    out = run_in_process(capsys, "check", tee / "tee.glb", "--json")
    assert out.status == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["down"] == [0.0, -1.0, 0.0] and data["verdict"] == "stands"
    # plate 0.1 m³ at y 0.05, post above it 0.078 m³ at y 1.075; GLB stores float32
    assert data["com_height"] == pytest.approx((0.1 * 0.05 + 0.078 * 1.075) / 0.178, rel=1e-6)
    assert any("+y, as glTF specifies" in n for n in data["notices"])
    assert any("up: +y" in line for line in _notes(out))
    sideways = run_in_process(capsys, "check", tee / "tee.glb", "--json", "--down", "0,0,-1")
    assert json.loads(sideways.stdout)["down"] == [0.0, 0.0, -1.0]
    assert json.loads(sideways.stdout)["verdict"] != "stands"
    assert not any(UP_Z_LINE in line for line in _notes(sideways))


@pytest.mark.parametrize("suffix", ["stl", "obj", "ply", "3mf"])
def test_other_meshes_keep_plus_z_up_and_say_so(capsys, tee, suffix):
    out = run_in_process(capsys, "check", tee / f"tee.{suffix}", "--json")
    assert out.status == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["down"] == [0.0, 0.0, -1.0] and data["verdict"] != "stands"
    assert sum(UP_Z_LINE in line for line in _notes(out)) == 1


# -------------------------------------------------------- assumptions on stderr
@pytest.mark.parametrize("output", [[], ["--json"]])
def test_mass_says_what_it_assumed_once_each(capsys, tee, output):
    out = run_in_process(capsys, "mass", tee / "tee.stl", *output)
    assert out.status == 0
    notes = _notes(out)
    assert sum("metres assumed" in n for n in notes) == 1
    assert sum(DENSITY_LINE in n for n in notes) == 1
    assert not any("up:" in n for n in notes)  # a mass has no up
    given = run_in_process(capsys, "mass", tee / "tee.stl", "--units", "m", "--density", "7850",
                           *output)
    assert _notes(given) == []


@pytest.mark.parametrize("fmt", ["urdf", "mjcf", "sdf"])
def test_simulator_inertials_refuse_without_a_density(capsys, tee, fmt):
    line = assert_bad_input(run_in_process(capsys, "mass", tee / "tee.stl", "--units", "in",
                                           "--format", fmt), "--density", "--material")
    assert fmt in line
    ok = run_in_process(capsys, "mass", tee / "tee.stl", "--units", "m", "--format", fmt,
                        "--material", "steel")
    assert ok.status == 0 and "7850" not in ok.stderr and DENSITY_LINE not in ok.stderr
    assert "mass" in ok.stdout


def test_a_spec_with_every_density_gives_inertials(capsys, shapes_dir):
    out = run_in_process(capsys, "mass", f"{shapes_dir}/cabinet.toml", "--format", "urdf")
    assert out.status == 0 and "<inertial>" in out.stdout


# ------------------------------------------------------------- declared units
def test_units_that_contradict_a_3mf_are_refused(capsys, tmp_path):
    vertices, faces = _tee_mesh()
    path = tmp_path / "tee_mm.3mf"
    path.write_bytes(_threemf(vertices * 1000, faces, "millimeter"))
    assert_bad_input(run_in_process(capsys, "mass", path, "--units", "in", "--density", "1"),
                     "millimeter", "--units-override")
    same = run_in_process(capsys, "mass", path, "--units", "mm", "--density", "1", "--json")
    assert same.status == 0
    forced = run_in_process(capsys, "mass", path, "--units", "in", "--units-override",
                            "--density", "1", "--json")
    assert forced.status == 0 and any("--units-override" in n for n in _notes(forced))
    volume = json.loads(same.stdout)["volume"]
    assert json.loads(forced.stdout)["volume"] == pytest.approx(volume * 25.4**3, rel=1e-12)


def test_units_that_contradict_a_glb_are_refused(capsys, tee):
    assert_bad_input(run_in_process(capsys, "mass", tee / "tee.glb", "--units", "mm"),
                     "meter", "--units-override")
    ok = run_in_process(capsys, "mass", tee / "tee.glb", "--units", "mm", "--units-override",
                        "--json", "--density", "1")
    assert ok.status == 0
    assert json.loads(ok.stdout)["volume"] == pytest.approx(0.178e-9, rel=1e-6)  # float32


def test_units_that_contradict_a_dxf_are_refused(capsys, tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    doc = ezdxf.new()
    doc.header["$INSUNITS"] = 4  # millimetres
    doc.modelspace().add_lwpolyline([(0, 0), (10, 0), (10, 5), (0, 5)], close=True)
    path = tmp_path / "plate.dxf"
    doc.saveas(path)
    assert_bad_input(run_in_process(capsys, "mass", path, "--units", "in"), "--units-override")
    ok = run_in_process(capsys, "mass", path, "--units", "in", "--units-override", "--json")
    assert ok.status == 0
    assert json.loads(ok.stdout)["area"] == pytest.approx(50 * 0.0254**2, rel=1e-12)


def test_units_that_contradict_a_spec_are_refused(capsys, shapes_dir):
    spec = f"{shapes_dir}/cabinet.toml"  # units = "m"
    assert_bad_input(run_in_process(capsys, "mass", spec, "--units", "mm"), "--units-override")
    ok = run_in_process(capsys, "mass", spec, "--units", "mm", "--units-override", "--json")
    assert ok.status == 0 and any("--units-override" in n for n in _notes(ok))


def test_units_override_needs_units(capsys, tee):
    assert_bad_input(run_in_process(capsys, "mass", tee / "tee.stl", "--units-override"),
                     "--units")
