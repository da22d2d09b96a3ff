"""STEP files read exactly from their B-rep (plumbob.formats.step, the plumbob[cad] extra):
closed-form solids, a named two-part assembly with a material per part, and hostile files.

The files are made here with OpenCASCADE itself (tests/step_models.py). Reading one
through the child process costs a few seconds (OpenCASCADE's import), so the accuracy
tests call the child's reader in this process and share one read per model."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import step_models as M

pytest.importorskip("OCP", reason="the plumbob[cad] extra (cadquery-ocp-novtk)")

from plumbob import read  # noqa: E402
from plumbob.cli import main  # noqa: E402
from plumbob.errors import DensityError, FormatError, LimitError, PlumbobError  # noqa: E402
from plumbob.formats import step as S  # noqa: E402
from plumbob.formats import step_worker  # noqa: E402
from plumbob.stability import check, resting_poses  # noqa: E402

MM = 1e-3
STEEL, ALUMINIUM = 7850.0, 2700.0


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("step")
    out = {
        "cylinder": M.write_shape(M.cylinder(10.0, 30.0), folder / "cylinder.step"),
        "assembly": M.write_assembly(folder / "stand.step", [
            ("base", _box(100.0, 60.0, 10.0), (0, 0, 0)),
            ("post", M.cylinder(5.0, 80.0), (50.0, 30.0, 10.0))]),
    }
    return out


def _box(a, b, c):
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox

    return BRepPrimAPI_MakeBox(a, b, c).Shape()


def _read_here(path: str):
    """The file's body read by the child's reader in this process (no child: faster)."""
    result = step_worker.read(str(path), S.DEVIATION)
    assert "parts" in result, result
    return S._reading(str(path), result["parts"], MM, (), "mm").body


# --------------------------------------------------------------- closed forms, 1e-9
def _cylinder_props(r, h):
    v = math.pi * r * r * h
    return v, np.array([0, 0, h / 2]), np.diag([v * (3 * r * r + h * h) / 12] * 2 + [v * r * r / 2])


def _sphere_props(r):
    v = 4 / 3 * math.pi * r**3
    return v, np.zeros(3), np.eye(3) * 0.4 * v * r * r


def _cone_props(r, h):
    v = math.pi * r * r * h / 3
    side = 3 / 20 * v * r * r + 3 / 80 * v * h * h
    return v, np.array([0, 0, h / 4]), np.diag([side, side, 0.3 * v * r * r])


def _torus_props(big, a):
    v = 2 * math.pi**2 * big * a * a
    side = v * (big * big / 2 + 5 / 8 * a * a)
    return v, np.zeros(3), np.diag([side, side, v * (big * big + 0.75 * a * a)])


def _box_with_holes_props(a, b, c, r, centres):
    """Volume, centre and inertia (unit density) of the box less its holes, by parallel axes."""
    pieces = [(a * b * c, np.array([a / 2, b / 2, c / 2]),
               np.diag([a * b * c * (b * b + c * c) / 12, a * b * c * (a * a + c * c) / 12,
                        a * b * c * (a * a + b * b) / 12]))]
    for x, y in centres:
        v = math.pi * r * r * c
        side = v * (3 * r * r + c * c) / 12
        pieces.append((-v, np.array([x, y, c / 2]), -np.diag([side, side, v * r * r / 2])))
    volume = sum(p[0] for p in pieces)
    centre = sum(p[0] * p[1] for p in pieces) / volume
    inertia = sum(p[2] + p[0] * (np.dot(p[1] - centre, p[1] - centre) * np.eye(3)
                                  - np.outer(p[1] - centre, p[1] - centre)) for p in pieces)
    return volume, centre, inertia


HOLES = [(20.0, 15.0), (60.0, 40.0), (75.0, 10.0)]
SOLIDS = {
    "cylinder": (lambda: M.cylinder(10.0, 30.0), _cylinder_props(10.0, 30.0)),
    "sphere": (lambda: M.sphere(12.5), _sphere_props(12.5)),
    "cone": (lambda: M.cone(8.0, 21.0), _cone_props(8.0, 21.0)),
    "torus": (lambda: M.torus(40.0, 7.5), _torus_props(40.0, 7.5)),
    "box with holes": (lambda: M.box_with_holes(90.0, 50.0, 12.0, 4.0, HOLES),
                       _box_with_holes_props(90.0, 50.0, 12.0, 4.0, HOLES)),
}


@pytest.mark.parametrize("name", list(SOLIDS))
def test_mass_properties_come_from_the_brep_within_the_stated_bound(name, tmp_path):
    make, (volume, centre, inertia) = SOLIDS[name]
    body = _read_here(M.write_shape(make(), tmp_path / "solid.step"))
    props = body.mass_properties()
    stated = props.relative_error
    assert not props.exact and stated <= 1e-9
    size = body.size
    # the stated bound covers the true error of every quantity (mm → m: volume mm³, inertia mm⁵)
    assert abs(props.measure / (volume * MM**3) - 1) <= stated
    assert np.max(np.abs(props.center_of_mass - centre * MM)) <= stated * size
    expected = inertia * MM**5
    assert np.max(np.abs(props.inertia - expected)) <= stated * np.max(np.abs(expected))


def test_a_step_cylinder_in_mm_reads_to_its_closed_forms(files):
    """Through the child process, as the command line reads it."""
    reading = read(files["cylinder"])
    volume, centre, inertia = _cylinder_props(10.0, 30.0)
    props = reading.body.mass_properties()
    assert reading.length_unit == "mm" and any("mm (from the file)" in n for n in reading.notices)
    assert props.measure == pytest.approx(volume * MM**3, rel=1e-9)
    assert np.allclose(props.center_of_mass, centre * MM, rtol=0, atol=1e-9 * 0.03)
    assert props.inertia[2, 2] == pytest.approx(inertia[2, 2] * MM**5, rel=1e-9)
    assert any("tessellation" in n for n in reading.notices)


def test_an_stl_export_of_the_cylinder_agrees_to_its_faceting(files, tmp_path):
    import trimesh

    n, r, h = 64, 10.0, 30.0
    mesh = trimesh.creation.cylinder(radius=r, height=h, sections=n)
    mesh.apply_translation([0, 0, h / 2])
    path = tmp_path / "cylinder.stl"
    mesh.export(path)
    stl = read(str(path), units="mm").body.mass_properties()
    step = _read_here(files["cylinder"]).mass_properties()
    alpha = 2 * math.pi / n
    # the inscribed n-gon: area n r² sin α / 2 and polar moment n r⁴ sin α (2 + cos α) / 12
    area = n * r * r * math.sin(alpha) / 2
    assert stl.measure / step.measure == pytest.approx(area / (math.pi * r * r), rel=1e-6)
    polar = n * r**4 * math.sin(alpha) * (2 + math.cos(alpha)) / 12
    assert stl.inertia[2, 2] / step.inertia[2, 2] == pytest.approx(polar / (math.pi * r**4 / 2), rel=1e-6)
    assert np.allclose(stl.center_of_mass, step.center_of_mass, atol=1e-6 * h * MM)


def test_the_tessellation_is_closed_and_within_its_deviation(files):
    from plumbob.integrals.mesh import triangle_soup_moments

    body = _read_here(files["cylinder"])
    tri = body.surface().triangles
    radius = np.hypot(tri[..., 0], tri[..., 1])
    # vertices on the surface (to float32 rounding, which the deviation includes), chords inside
    assert radius.max() <= 10 * MM + body.deviation
    assert body.deviation <= 1.1e-4 * body.size
    volume = triangle_soup_moments(tri).m0
    assert 0 < 1 - volume / body.mass_properties().measure <= 2 * body.deviation / (10 * MM)


# --------------------------------------------------------------- assemblies
def _stand_expected():
    m_base = STEEL * 100 * 60 * 10 * MM**3
    m_post = ALUMINIUM * math.pi * 25 * 80 * MM**3
    mass = m_base + m_post
    centre = np.array([50, 30, (m_base * 5 + m_post * 50) / mass]) * MM
    return mass, centre


def test_an_assembly_with_part_materials_gives_the_hand_computed_mass_and_centre(files, capsys):
    from plumbob.materials import material

    assert material("steel").density == STEEL and material("aluminium").density == ALUMINIUM
    assert main(["mass", files["assembly"], "--part-material", "base=steel",
                 "--part-material", "p*=aluminium", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    mass, centre = _stand_expected()
    assert data["mass"] == pytest.approx(mass, rel=1e-9)
    assert np.allclose(data["center_of_mass"], centre, rtol=0, atol=1e-9 * 0.1)
    parts = {p["name"]: p for p in data["part_properties"]}
    assert set(parts) == {"base", "post"}
    assert parts["base"]["material"] == "steel" and parts["post"]["material"] == "aluminium"
    assert parts["post"]["center_of_mass"] == pytest.approx([0.05, 0.03, 0.05], abs=1e-12)


def test_the_part_table_lists_name_material_mass_and_centre(files, capsys):
    assert main(["mass", files["assembly"], "--part-material", "base=steel",
                 "--part-material", "post=aluminium"]) == 0
    out = capsys.readouterr().out
    header = next(line for line in out.splitlines() if line.startswith("part "))
    assert "material" in header and "mass" in header and "centre of mass" in header
    assert any(line.split()[:2] == ["base", "steel"] for line in out.splitlines())


def test_check_stands_the_assembly_with_the_right_margin(files):
    mass, centre = _stand_expected()
    body = read(files["assembly"], part_materials={"base": "steel", "post": "aluminium"}).body
    verdict = check(body)
    assert verdict.verdict == "stands"
    # the base's 100 × 60 mm footprint, centre above its middle: 30 mm to the long edges
    assert verdict.margin == pytest.approx(0.030, rel=1e-9)
    assert verdict.critical_tilt_deg == pytest.approx(math.degrees(math.atan2(0.030, centre[2])),
                                                      rel=1e-9)


def test_without_materials_the_assembly_is_refused_naming_both_parts(files, capsys):
    assert main(["mass", files["assembly"]]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert "'base'" in err and "'post'" in err and "--part-material" in err


def test_a_glob_that_matches_no_part_is_refused(files):
    from plumbob.formats.parts import require_part_densities, with_part_materials
    from plumbob.reading import Reading

    reading = Reading(_read_here(files["assembly"]), (), files["assembly"])
    with pytest.raises(DensityError, match="'base', 'post'"):
        require_part_densities(reading, "--part-material")
    with pytest.raises(DensityError, match="'bolt\\*' matches no part; the parts are 'base', 'post'"):
        with_part_materials(reading, {"bolt*": "steel", "*": "pla"}, "--part-material")
    half = with_part_materials(reading, {"b*": "steel"}, "--part-material")
    with pytest.raises(DensityError, match="1 part with no density: 'post'"):
        require_part_densities(half, "--part-material")


def test_instances_of_one_part_count_once_each(tmp_path):
    path = M.write_assembly(tmp_path / "two_posts.step", [
        ("post", M.cylinder(5.0, 80.0), (0.0, 0.0, 0.0)),
        ("post", M.cylinder(5.0, 80.0), (40.0, 0.0, 0.0))])
    body = _read_here(path)
    names = [p.name for p in body.assembly_parts()]
    assert names == ["post", "post (2)"]
    props = body.mass_properties()
    assert props.measure == pytest.approx(2 * math.pi * 25 * 80 * MM**3, rel=1e-9)
    assert props.center_of_mass[0] == pytest.approx(0.020, rel=1e-9)


def test_a_spec_reads_a_step_part_with_materials(files, tmp_path):
    import shutil

    shutil.copy(files["assembly"], tmp_path / "stand.step")
    spec = tmp_path / "stand.toml"
    spec.write_text('[[part]]\ntype = "step"\nfile = "stand.step"\n'
                    'materials = { "base" = "steel", "post*" = "aluminium" }\n')
    reading = read(str(spec))
    mass, centre = _stand_expected()
    assert reading.body.mass_properties().mass == pytest.approx(mass, rel=1e-9)
    assert any("base = steel" in n for n in reading.notices)
    spec.write_text('[[part]]\ntype = "step"\nfile = "stand.step"\nmaterials = { "base" = "steel" }\n')
    with pytest.raises(PlumbobError, match="'post'"):
        read(str(spec))


# --------------------------------------------------------------- everything else on it
def test_poses_on_a_step_cylinder_give_its_two_ends_and_one_rolling_pose(files):
    body = _read_here(files["cylinder"])
    poses = resting_poses(body)
    kinds = sorted(p.kind for p in poses)
    assert len(poses) == 3 and kinds.count("rolling") == 1
    ends = [p for p in poses if p.kind != "rolling"]
    assert sorted(round(abs(p.down[2])) for p in ends) == [1, 1]
    assert sum(p.down[2] for p in ends) == pytest.approx(0, abs=1e-9)
    (side,) = [p for p in poses if p.kind == "rolling"]
    assert abs(side.axis[2]) == pytest.approx(1, abs=1e-9)


def test_exports_and_pictures_take_the_tessellation(files, tmp_path):
    from plumbob.export.inertial import inertial_xml

    body = _read_here(files["cylinder"]).with_default_density(STEEL)
    text = inertial_xml(body.mass_properties(), "urdf")
    assert "ixx" in text
    fig = body.plot()
    assert fig is not None


def test_brep_and_iges_files_go_the_same_way(tmp_path):
    from OCP.BRepTools import BRepTools
    from OCP.IGESControl import IGESControl_Writer

    assert BRepTools.Write_s(M.cylinder(10.0, 30.0), str(tmp_path / "cylinder.brep"))
    reading = read(str(tmp_path / "cylinder.brep"))
    volume, _, _ = _cylinder_props(10.0, 30.0)
    assert reading.body.mass_properties().measure == pytest.approx(volume * MM**3, rel=1e-9)
    assert reading.body.name == "cylinder" and "BREP file states none" in reading.notices[0]
    writer = IGESControl_Writer("MM", 0)  # faces only: an IGES surface model, not a solid
    writer.AddShape(M.cylinder(10.0, 30.0))
    writer.ComputeModel()
    assert writer.Write(str(tmp_path / "cylinder.igs"))
    _refused(tmp_path / "cylinder.igs", "faces only, not a closed solid")


# --------------------------------------------------------------- hostile files
def _refused(path, match, error=FormatError):
    with pytest.raises(error, match=match) as caught:
        read(str(path))
    assert str(path) in str(caught.value)


def test_a_truncated_file_is_refused(files, tmp_path):
    data = open(files["cylinder"], "rb").read()
    (tmp_path / "cut.step").write_bytes(data[: len(data) // 2])
    _refused(tmp_path / "cut.step", "truncated")


def test_a_file_that_is_not_step_is_refused(tmp_path):
    (tmp_path / "fake.step").write_text("solid nothing\nendsolid\n")
    _refused(tmp_path / "fake.step", "not a STEP file")


def _edited(files, tmp_path, old: bytes, new: bytes, name="edited.step"):
    data = open(files["cylinder"], "rb").read()
    assert old in data
    (tmp_path / name).write_bytes(data.replace(old, new))
    return tmp_path / name


def test_missing_and_odd_units_are_refused(files, tmp_path):
    _refused(_edited(files, tmp_path, b"LENGTH_UNIT()", b"MASS_UNIT()"), "declares no length unit")
    _refused(_edited(files, tmp_path, b"SI_UNIT(.MILLI.,.METRE.)", b"SI_UNIT(.EXA.,.METRE.)"),
             "odd length unit")


def test_an_external_reference_is_refused(files, tmp_path):
    path = _edited(files, tmp_path, b"ENDSEC;\nEND-ISO",
                   b"#99999 = DOCUMENT_FILE('part.stp','',$,#1,'',$);\nENDSEC;\nEND-ISO")
    _refused(path, "external file")


def test_too_many_entities_are_refused_before_opencascade(files, monkeypatch):
    monkeypatch.setattr(S.limits, "MAX_STEP_ENTITIES", 50)
    _refused(files["cylinder"], "entities", LimitError)


def test_an_assembly_nested_thousands_deep_is_refused_unread(tmp_path):
    # a chain: each occurrence's child is the next one's parent
    text = "".join(f"#{i} = NEXT_ASSEMBLY_USAGE_OCCURRENCE('{i}','n','',#{10**6 + i},"
                   f"#{10**6 + i + 1},$);\n" for i in range(1, 5000))
    (tmp_path / "deep.step").write_text(
        "ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#0 = ( LENGTH_UNIT() NAMED_UNIT(*) "
        "SI_UNIT(.MILLI.,.METRE.) );\n" + text + "ENDSEC;\nEND-ISO-10303-21;\n")
    _refused(tmp_path / "deep.step", "nests its assembly over 64 deep", LimitError)


@pytest.mark.parametrize("make, match", [
    (M.face_only, "not a closed solid"), (M.open_box, "open shell"),
    (M.bow_tie_prism, "self-intersecting"),
], ids=["faces", "open shell", "self-intersecting"])
def test_a_shape_that_is_not_a_closed_solid_is_refused(make, match, tmp_path):
    path = M.write_shape(make(), tmp_path / "bad.step")
    result = step_worker.read(path, S.DEVIATION)  # the child's verdict, here
    assert match in result.get("defect", ""), result


def test_a_defect_found_by_the_child_is_one_line_naming_the_file(tmp_path, capsys):
    path = M.write_shape(M.face_only(), tmp_path / "face.step")
    assert main(["mass", path]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and path in err and "not a closed solid" in err


def test_a_crash_of_the_reader_costs_one_line_not_the_process(files, monkeypatch):
    monkeypatch.setattr(S, "_WORKER", ["-c", "import os, signal; os.kill(os.getpid(), signal.SIGSEGV)"])
    _refused(files["cylinder"], "signal 11")


def test_a_reader_that_runs_too_long_is_stopped(files, monkeypatch):
    monkeypatch.setattr(S, "_WORKER", ["-c", "import time; time.sleep(30)"])
    monkeypatch.setattr(S, "STEP_SECONDS", 0.5)
    _refused(files["cylinder"], "over 0.5 s", LimitError)


def test_without_the_cad_extra_the_error_names_it(files, monkeypatch):
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name == "OCP" else real(name, *a))
    with pytest.raises(PlumbobError, match=r"install plumbob\[cad\]"):
        read(files["cylinder"])


def test_one_child_serves_every_read_and_a_crash_costs_only_its_own(files, monkeypatch):
    """OpenCASCADE's child is started once (about a second) and serves the reads that
    follow; a child that crashes takes only the read it was on with it."""
    from plumbob.formats import cad_child

    first = read(files["cylinder"]).body.mass_properties().measure
    pid = cad_child._child.process.pid
    assert read(files["cylinder"]).body.mass_properties().measure == first
    assert cad_child._child.process.pid == pid  # the same child answered
    with monkeypatch.context() as patched:
        patched.setattr(S, "_WORKER", ["-c", "import os, signal; os.kill(os.getpid(), signal.SIGSEGV)"])
        _refused(files["cylinder"], "signal 11")
    assert read(files["cylinder"]).body.mass_properties().measure == first  # a fresh child
    assert cad_child._child.process.pid != pid
