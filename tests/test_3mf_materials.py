"""3MF assemblies: several objects, each with its own base material (a slicer's
multi-material output), read as named parts with their materials
(plumbob.formats.threemf). The files are written here; the answers are by hand."""

from __future__ import annotations

import json
import os
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "bad_inputs"))
from make_bad_inputs import cube, three_mf, zip_bytes  # noqa: E402

from plumbob import read  # noqa: E402
from plumbob.cli import main  # noqa: E402
from plumbob.errors import DensityError, FormatError, LimitError  # noqa: E402
from plumbob.formats.threemf import match_material  # noqa: E402

MM = 1e-3
PLA, PETG = 1240.0, 1270.0
CORE = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
PRODUCTION = "http://schemas.microsoft.com/3dmanufacturing/production/2015/06"


def mesh_xml(triangles: np.ndarray) -> str:
    v = np.asarray(triangles, dtype=float).reshape(-1, 3)
    verts = "".join(f'<vertex x="{x!r}" y="{y!r}" z="{z!r}"/>' for x, y, z in v.tolist())
    tris = "".join(f'<triangle v1="{3 * i}" v2="{3 * i + 1}" v3="{3 * i + 2}"/>'
                   for i in range(len(v) // 3))
    return f"<mesh><vertices>{verts}</vertices><triangles>{tris}</triangles></mesh>"


def box(a: float, b: float, c: float) -> np.ndarray:
    return cube() * np.array([a, b, c])


def model(objects: str, items: str, materials=("PLA", "PETG")) -> bytes:
    bases = "".join(f'<base name="{m}" displaycolor="#FF0000"/>' for m in materials)
    return (f'<?xml version="1.0" encoding="UTF-8"?>\n<model unit="millimeter" xmlns="{CORE}" '
            f'xmlns:p="{PRODUCTION}"><resources><basematerials id="1">{bases}</basematerials>'
            f"{objects}</resources><build>{items}</build></model>").encode()


# a 20 × 10 × 10 mm block at the origin, and a 10 × 10 × 30 mm post placed on it by
# the build item at (5, 0, 10)
BLOCK, POST = box(20, 10, 10), box(10, 10, 30)


def two_objects(materials=("PLA", "PETG"), names=("block", "post")) -> bytes:
    objects = (f'<object id="2" type="model" name="{names[0]}" pid="1" pindex="0">'
               f"{mesh_xml(BLOCK)}</object>"
               f'<object id="3" type="model" name="{names[1]}" pid="1" pindex="1">'
               f"{mesh_xml(POST)}</object>")
    items = '<item objectid="2"/><item objectid="3" transform="1 0 0 0 1 0 0 0 1 5 0 10"/>'
    return three_mf(model(objects, items, materials))


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("3mf")
    out = {}
    for name, data in {"print": two_objects(),
                       "colours": two_objects(("Red", "Blue"))}.items():
        out[name] = str(folder / f"{name}.3mf")
        with open(out[name], "wb") as f:
            f.write(data)
    return out


def hand():
    """Mass (kg) and centre (m) of the block in PLA and the post in PETG."""
    m1, m2 = PLA * 2000 * MM**3, PETG * 3000 * MM**3
    c1, c2 = np.array([10.0, 5.0, 5.0]) * MM, np.array([10.0, 5.0, 25.0]) * MM
    return m1 + m2, (m1 * c1 + m2 * c2) / (m1 + m2), (m1, m2)


def test_each_object_takes_its_base_material(files):
    reading = read(files["print"])
    props = reading.body.mass_properties()
    mass, centre, (m1, m2) = hand()
    assert abs(props.mass / mass - 1) <= 1e-9
    assert np.abs(props.center_of_mass - centre).max() <= 1e-9 * 30 * MM
    parts = reading.body.assembly_parts()
    assert [p.name for p in parts] == ["block", "post"]
    assert [p.mass_properties().mass for p in parts] == pytest.approx([m1, m2], rel=1e-12)
    assert reading.materials == (("block", "pla"), ("post", "petg"))
    # what was matched is said, never guessed silently
    said = [n for n in reading.notices if n.startswith("3mf:")]
    assert "'PLA' is pla (1240 kg/m³, by the name): 'block'" in said[0]
    assert "'PETG' is petg (1270 kg/m³, by the name): 'post'" in said[1]


def test_the_part_table_lists_both_parts_with_their_materials(files, capsys):
    assert main(["mass", files["print"]]) == 0
    out, err = capsys.readouterr()
    table = out[out.index("part "):].splitlines()
    assert table[1].split()[:2] == ["block", "pla"] and table[2].split()[:2] == ["post", "petg"]
    assert "base material 'PLA' is pla" in err and "no density given" not in err
    assert main(["mass", files["print"], "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert abs(data["mass"] / hand()[0] - 1) <= 1e-9


def test_unmatched_materials_are_refused_naming_both_parts(files, capsys):
    with pytest.raises(DensityError, match=r"2 parts with no density: 'block', 'post'"):
        read(files["colours"])
    assert main(["mass", files["colours"]]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and files["colours"] in err
    assert "'block', 'post'" in err and "--part-material" in err


def test_part_material_gives_the_unmatched_parts_theirs(files, capsys):
    assert main(["mass", files["colours"], "--json", "--part-material", "block=pla",
                 "--part-material", "p*=1270"]) == 0
    out, err = capsys.readouterr()
    data = json.loads(out)
    mass, centre, _ = hand()
    assert abs(data["mass"] / mass - 1) <= 1e-9
    assert np.abs(np.array(data["center_of_mass"]) - centre).max() <= 1e-9 * 30 * MM
    assert "'Red' ('block') names no plumbob material" in err


def test_one_material_for_every_part_is_not_a_multi_material_print(tmp_path):
    path = tmp_path / "one.3mf"
    path.write_bytes(two_objects(("Green", "Green")))
    reading = read(str(path))  # the usual assumed density, said; no refusal
    assert None in reading.body.densities()
    assert any("'Green' ('block', 'post') names no plumbob material" in n
               for n in reading.notices)
    assert read(str(path), density=1000.0).body.mass_properties().mass == \
        pytest.approx(1000.0 * 5000 * MM**3, rel=1e-12)


def test_components_from_another_model_part_keep_names_and_materials(tmp_path):
    # the production extension, as Bambu Studio writes: the build places an object of
    # components, each a mesh object in 3D/Objects/parts.model; the placement composes
    parts = (f'<?xml version="1.0" encoding="UTF-8"?>\n<model unit="millimeter" xmlns="{CORE}">'
             f'<resources><basematerials id="1"><base name="PLA"/><base name="PETG"/>'
             f'</basematerials><object id="7" name="block" pid="1" pindex="0">'
             f'{mesh_xml(BLOCK)}</object><object id="8" name="post" pid="1" pindex="1">'
             f'{mesh_xml(POST)}</object></resources><build/></model>').encode()
    objects = ('<object id="9" name="print"><components>'
               '<component p:path="/3D/Objects/parts.model" objectid="7"/>'
               '<component p:path="/3D/Objects/parts.model" objectid="8" '
               'transform="1 0 0 0 1 0 0 0 1 5 0 10"/></components></object>')
    main_part = model(objects, '<item objectid="9" transform="1 0 0 0 1 0 0 0 1 0 0 10"/>')
    data = three_mf(main_part)
    import io
    import zipfile

    with zipfile.ZipFile(io.BytesIO(data)) as z:
        members = {n: z.read(n) for n in z.namelist()}
    members["3D/Objects/parts.model"] = parts
    path = tmp_path / "bambu.3mf"
    path.write_bytes(zip_bytes(members))
    reading = read(str(path))
    mass, centre, _ = hand()
    props = reading.body.mass_properties()
    assert [p.name for p in reading.body.assembly_parts()] == ["block", "post"]
    assert abs(props.mass / mass - 1) <= 1e-9
    # the whole print is 10 mm higher than in the other file
    assert np.abs(props.center_of_mass - centre - [0, 0, 10 * MM]).max() <= 1e-9 * 40 * MM


def test_painted_triangles_are_said_and_do_not_change_the_volume(tmp_path):
    painted = mesh_xml(BLOCK).replace('<triangle v1="0"', '<triangle pid="1" p1="1" v1="0"', 1)
    objects = (f'<object id="2" name="block" pid="1" pindex="0">{painted}</object>'
               f'<object id="3" name="post" pid="1" pindex="1">{mesh_xml(POST)}</object>')
    path = tmp_path / "painted.3mf"
    path.write_bytes(three_mf(model(
        objects, '<item objectid="2"/><item objectid="3" transform="1 0 0 0 1 0 0 0 1 5 0 10"/>')))
    reading = read(str(path))
    assert abs(reading.body.mass_properties().mass / hand()[0] - 1) <= 1e-9
    assert any("triangles of 'block' name other materials" in n for n in reading.notices)


@pytest.mark.parametrize("objects, items, match, error", [
    ('<object id="2"><components><component objectid="2"/></components></object>',
     '<item objectid="2"/>', "contains itself", FormatError),
    ("", '<item objectid="5"/>', "does not define", FormatError),
    ('<object id="2"><components><component objectid="2" transform="1 0 0"/></components>'
     "</object>", '<item objectid="2"/>', "not 12 finite numbers", FormatError),
    ('<object id="2"><components><component p:path="/3D/nowhere.model" objectid="1"/>'
     "</components></object>", '<item objectid="2"/>', "does not hold", FormatError),
    ('<object id="2"><components><component p:path="/_rels/.rels" objectid="1"/>'
     "</components></object>", '<item objectid="2"/>', "ends in .model", FormatError),
], ids=["cycle", "undefined", "transform", "missing part", "not a model part"])
def test_broken_structures_are_refused_in_one_line(objects, items, match, error, tmp_path):
    path = tmp_path / "bad.3mf"
    path.write_bytes(three_mf(model(objects, items)))
    with pytest.raises(error, match=match) as caught:
        read(str(path))
    assert str(path) in str(caught.value)


def test_deep_nesting_is_refused(tmp_path):
    chain = "".join(f'<object id="{i}"><components><component objectid="{i + 1}"/>'
                    "</components></object>" for i in range(2, 200))
    chain += f'<object id="200">{mesh_xml(BLOCK)}</object>'
    path = tmp_path / "deep.3mf"
    path.write_bytes(three_mf(model(chain, '<item objectid="2"/>')))
    with pytest.raises(LimitError, match="nests its components over 64 deep"):
        read(str(path))


@pytest.mark.parametrize("name, expected", [
    ("PLA", "pla"), ("petg", "petg"), ("Generic PETG", "petg"), ("Bambu PLA Basic", "pla"),
    ("Stainless steel", "stainless_steel"), ("Green", None), ("PLA PETG blend", None),
])
def test_base_material_names_match_only_plainly(name, expected):
    found, how = match_material(name)
    assert (found.name if found else None) == expected
    assert (how is None) == (expected is None)


def test_the_docs_worked_example_is_this_file():
    from conftest import ROOT

    with open(os.path.join(ROOT, "docs", "models", "print.3mf"), "rb") as f:
        assert f.read() == two_objects(("Red", "Blue"))


# --------------------------------------------------------------- slicers' projects
PLACED_POST = POST + np.array([5.0, 0.0, 10.0])
TWEAK = box(2, 2, 2) + np.array([1.0, 1.0, 1.0])  # a settings modifier inside the block


def _with(data: bytes, extra: dict[str, bytes]) -> bytes:
    import io
    import zipfile

    with zipfile.ZipFile(io.BytesIO(data)) as z:
        members = {n: z.read(n) for n in z.namelist()}
    return zip_bytes({**members, **extra})


def prusa_project(post_type: str = "ModelPart") -> bytes:
    """As PrusaSlicer saves a project: one object whose mesh holds every volume, the
    volumes as triangle ranges in Metadata/Slic3r_PE_model.config."""
    mesh = np.concatenate([BLOCK, PLACED_POST, TWEAK])
    objects = f'<object id="1" type="model">{mesh_xml(mesh)}</object>'
    core = three_mf(model(objects, '<item objectid="1"/>', materials=("Unused",)))
    n = len(BLOCK)

    def volume(first, last, name, extruder, kind):
        return (f'<volume firstid="{first}" lastid="{last}">'
                f'<metadata type="volume" key="name" value="{name}"/>'
                f'<metadata type="volume" key="volume_type" value="{kind}"/>'
                f'<metadata type="volume" key="extruder" value="{extruder}"/></volume>')

    config = ('<?xml version="1.0" encoding="UTF-8"?>\n<config><object id="1" instances_count="1">'
              '<metadata type="object" key="name" value="print"/>'
              '<metadata type="object" key="extruder" value="1"/>'
              + volume(0, n - 1, "block", 0, "ModelPart")
              + volume(n, 2 * n - 1, "post", 2, post_type)
              + volume(2 * n, 3 * n - 1, "infill tweak", 0, "ParameterModifier")
              + "</object></config>")
    settings = "; generated by PrusaSlicer\n; filament_type = PLA;PETG\n; layer_height = 0.2\n"
    return _with(core, {"Metadata/Slic3r_PE_model.config": config.encode(),
                        "Metadata/Slic3r_PE.config": settings.encode()})


def bambu_project() -> bytes:
    """As Bambu Studio saves a project: an object of components in the main model, its
    parts in 3D/Objects/object_1.model, their extruders in Metadata/model_settings.config."""
    parts = (f'<?xml version="1.0" encoding="UTF-8"?>\n<model unit="millimeter" xmlns="{CORE}">'
             f'<resources><object id="1" type="model">{mesh_xml(BLOCK)}</object>'
             f'<object id="2" type="model">{mesh_xml(POST)}</object>'
             f'<object id="3" type="model">{mesh_xml(TWEAK)}</object></resources>'
             "<build/></model>").encode()
    components = "".join(
        f'<component p:path="/3D/Objects/object_1.model" objectid="{i}" transform="{t}"/>'
        for i, t in ((1, "1 0 0 0 1 0 0 0 1 0 0 0"), (2, "1 0 0 0 1 0 0 0 1 5 0 10"),
                     (3, "1 0 0 0 1 0 0 0 1 0 0 0")))
    core = three_mf(model(f'<object id="4" type="model"><components>{components}'
                          "</components></object>", '<item objectid="4"/>', materials=("X",)))

    def part(i, name, extruder, subtype="normal_part"):
        return (f'<part id="{i}" subtype="{subtype}"><metadata key="name" value="{name}"/>'
                f'<metadata key="extruder" value="{extruder}"/></part>')

    config = ('<?xml version="1.0" encoding="UTF-8"?>\n<config><object id="4">'
              '<metadata key="name" value="print"/><metadata key="extruder" value="1"/>'
              + part(1, "block", 0) + part(2, "post", 2)
              + part(3, "infill tweak", 0, "modifier_part") + "</object></config>")
    project = json.dumps({"filament_type": ["PLA", "PETG"], "layer_height": "0.2"})
    return _with(core, {"3D/Objects/object_1.model": parts,
                        "Metadata/model_settings.config": config.encode(),
                        "Metadata/project_settings.config": project.encode()})


@pytest.mark.parametrize("make", [prusa_project, bambu_project], ids=["prusaslicer", "bambu"])
def test_a_slicer_project_gives_parts_names_and_extruder_filaments(make, tmp_path):
    path = tmp_path / "project.3mf"
    path.write_bytes(make())
    reading = read(str(path))
    parts = reading.body.assembly_parts()
    assert [p.name for p in parts] == ["block", "post"]  # the modifier is no material
    mass, centre, (m1, m2) = hand()
    props = reading.body.mass_properties()
    assert abs(props.mass / mass - 1) <= 1e-9
    assert np.abs(props.center_of_mass - centre).max() <= 1e-9 * 30 * MM
    assert reading.materials == (("block", "pla"), ("post", "petg"))
    said = "\n".join(reading.notices)
    assert "extruder 1 (PLA) is pla (1240 kg/m³, by the name): 'block'" in said
    assert "extruder 2 (PETG) is petg" in said
    assert "'infill tweak' is not printed material: left out" in said


def test_a_negative_volume_is_refused_not_ignored(tmp_path):
    path = tmp_path / "cut.3mf"
    path.write_bytes(prusa_project(post_type="NegativeVolume"))
    with pytest.raises(FormatError, match="negative volume 'post' cuts object 'print'"):
        read(str(path))


@settings(max_examples=15, deadline=None)
@given(shift=st.tuples(*[st.integers(-10**6, 10**6).map(lambda k: k / 64)] * 3),
       turns=st.integers(0, 3))
def test_a_build_placement_moves_the_centre_and_keeps_the_mass(shift, turns, tmp_path_factory):
    # the post turned by quarter turns about its own vertical axis and the whole print
    # moved by `shift` (mm, exact binary fractions): mass unchanged, centre moved by it
    c, s = [(1, 0), (0, 1), (-1, 0), (0, -1)][turns]
    x, y, z = shift
    # the turn about the post's axis (x, y) = (10, 5): the post's own placement
    px, py = 10 - (c * 5 - s * 5), 5 - (s * 5 + c * 5)
    objects = (f'<object id="2" name="block" pid="1" pindex="0">{mesh_xml(BLOCK)}</object>'
               f'<object id="3" name="post" pid="1" pindex="1">{mesh_xml(POST)}</object>'
               '<object id="4" name="print"><components><component objectid="2"/>'
               f'<component objectid="3" transform="{c} {s} 0 {-s} {c} 0 0 0 1 {px} {py} 10"/>'
               "</components></object>")
    path = tmp_path_factory.mktemp("placed") / "placed.3mf"
    path.write_bytes(three_mf(model(objects, f'<item objectid="4" transform="1 0 0 0 1 0 0 0 1 '
                                             f'{x!r} {y!r} {z!r}"/>')))
    props = read(str(path)).body.mass_properties()
    mass, centre, _ = hand()
    assert abs(props.mass / mass - 1) <= 1e-12
    reach = 30 * MM + np.abs(shift).max() * MM
    assert np.abs(props.center_of_mass - centre - np.array(shift) * MM).max() <= 1e-12 * reach


def test_part_material_overrides_what_the_file_names(files, capsys):
    reading = read(files["print"], part_materials={"post": "abs"})  # ABS: 1040 kg/m³
    m1, m2 = PLA * 2000 * MM**3, 1040.0 * 3000 * MM**3
    assert abs(reading.body.mass_properties().mass / (m1 + m2) - 1) <= 1e-9
    assert dict(reading.materials) == {"block": "pla", "post": "abs"}
    assert main(["mass", files["print"], "--part-material", "post=abs"]) == 0
    table = capsys.readouterr().out.split("part ")[-1].splitlines()
    assert table[1].split()[:2] == ["block", "pla"] and table[2].split()[:2] == ["post", "abs"]


def test_components_that_multiply_are_refused_before_the_walk_explodes(tmp_path, monkeypatch):
    # six levels of ten components each: a million placements from a few hundred bytes
    from plumbob import limits

    monkeypatch.setattr(limits, "MAX_PARTS", 500)  # the same refusal, sooner
    levels = "".join(f'<object id="{i}"><components>'
                     + f'<component objectid="{i + 1}"/>' * 10 + "</components></object>"
                     for i in range(2, 8))
    levels += f'<object id="8">{mesh_xml(BLOCK)}</object>'
    path = tmp_path / "fan.3mf"
    path.write_bytes(three_mf(model(levels, '<item objectid="2"/>')))
    with pytest.raises(LimitError, match="placed objects"):
        read(str(path))
