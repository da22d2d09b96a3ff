import os

import numpy as np
import pytest

from plumbob.bodies.csg import Assembly, Composite
from plumbob.errors import ExpressionError, InputFileError, SpecError
from plumbob.loading import read
from plumbob.spec.loader import build_spec, load_spec, parse_simulation


def write(tmp_path, text, name="shape.toml"):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def test_parameters_build_on_each_other(tmp_path):
    path = write(
        tmp_path,
        """
[parameters]
a = 2
b = "a^2 + 1"
[[part]]
type = "rectangle"
width = "b"
height = "a"
""",
    )
    props = load_spec(path).body.mass_properties()
    assert props.area == pytest.approx(10.0)


def test_units_scale_lengths_not_angles(tmp_path):
    path = write(
        tmp_path,
        """
[shape]
units = "mm"
[[part]]
type = "sector"
radius = 1000
angle = 90
""",
    )
    props = load_spec(path).body.mass_properties()
    assert props.area == pytest.approx(np.pi / 4, rel=1e-14)


def test_material_and_thickness_make_a_heavy_lamina(tmp_path):
    path = write(
        tmp_path,
        """
[shape]
material = "steel"
thickness = 0.01
[[part]]
type = "square"
side = 1
""",
    )
    assert load_spec(path).body.mass_properties().mass == pytest.approx(78.5)


def test_lamina_of_a_material_needs_a_thickness(tmp_path):
    path = write(tmp_path, '[shape]\nmaterial = "steel"\n[[part]]\ntype = "disc"\nradius = 1\n')
    with pytest.raises(SpecError, match="needs a thickness"):
        load_spec(path)


def test_subtract_and_placement(tmp_path):
    path = write(
        tmp_path,
        """
[shape]
density = 2
[[part]]
type = "rectangle"
width = 4
height = 2
[[part]]
op = "subtract"
type = "disc"
radius = 0.5
at = [3, 1]
""",
    )
    body = load_spec(path).body
    assert isinstance(body, Composite)
    assert body.mass_properties().mass == pytest.approx(2 * (8 - np.pi / 4), rel=1e-15)


def test_parts_of_different_materials_make_an_assembly(tmp_path):
    path = write(
        tmp_path,
        """
[[part]]
name = "foot"
type = "box"
length = 1
width = 1
height = 0.2
material = "concrete"
[[part]]
name = "post"
type = "cylinder"
radius = 0.05
height = 2
at = [0.5, 0.5, 0.2]
material = "steel"
""",
    )
    body = load_spec(path).body
    assert isinstance(body, Assembly) and body.kind == "assembly"
    assert [p.name for p in body.parts] == ["foot", "post"]


def test_rotation_in_3d_and_2d(tmp_path):
    path = write(
        tmp_path,
        """
[[part]]
type = "cylinder"
radius = 1
height = 2
rotate = { axis = [0, 1, 0], angle = 90 }
""",
    )
    assert load_spec(path).body.mass_properties().center_of_mass == pytest.approx(
        [1, 0, 0], abs=1e-15
    )
    path = write(
        tmp_path, '[[part]]\ntype = "rectangle"\nwidth = 2\nheight = 1\nrotate = 90\n', "b.toml"
    )
    assert load_spec(path).body.mass_properties().center_of_mass == pytest.approx(
        [-0.5, 1], abs=1e-15
    )


def test_particles(tmp_path):
    path = write(
        tmp_path,
        """
[[particle]]
mass = 1
position = [0, 0, 0]
[[particle]]
mass = 3
position = [4, 0, 0]
""",
    )
    props = load_spec(path).body.mass_properties()
    assert props.center_of_mass == pytest.approx([3, 0, 0])


@pytest.mark.parametrize(
    "text, error, message",
    [
        (
            '[[part]]\ntype = "rectangle"\nwidht = 1\nheight = 1\n',
            SpecError,
            "did you mean 'width'",
        ),
        (
            '[[part]]\ntype = "rectangel"\nwidth = 1\nheight = 1\n',
            SpecError,
            "did you mean 'rectangle'",
        ),
        ('[[part]]\ntype = "rectangle"\nwidth = 1\n', SpecError, "needs height"),
        (
            '[[part]]\ntype = "disc"\nradius = "__import__(\'os\')"\n',
            SpecError,
            "unexpected character",
        ),
        ('[[part]]\ntype = "disc"\nradius = "2 +"\n', SpecError, "ends too soon"),
        ('[shape]\ndensity = -5\n[[part]]\ntype = "disc"\nradius = 1\n', SpecError, "positive"),
        ('[[part]]\ntype = "disc"\nradius = 0\n', SpecError, "radius must be a positive"),
        ('[[part]]\ntype = "box"\nlength = 1\nwidth = 1\nheight = 0\n', SpecError, "height"),
        (
            '[shape]\nmaterial = "unobtainium"\nthickness = 1\n'
            '[[part]]\ntype = "disc"\nradius = 1\n',
            SpecError,
            "unknown material",
        ),
        ("[shapes]\n", SpecError, "unknown top-level key 'shapes'"),
        ('[shape]\nname = "x"\n', SpecError, "needs \\[\\[part\\]\\]"),
        (
            '[[part]]\ntype = "disc"\nradius = 1\n[[part]]\ntype = "box"\nlength = 1\nwidth = 1\n'
            "height = 1\n",
            SpecError,
            "all parts must be 2D",
        ),
        ("not toml at all = = =", SpecError, "not valid TOML"),
        ("[[particle]]\nmass = -1\nposition = [0, 0]\n", SpecError, "must be positive"),
        ('[parameters]\nx = 1\n[[part]]\ntype = "disc"\nradius = 1\n', SpecError, "reserved"),
    ],
)
def test_bad_specs_name_the_problem(tmp_path, text, error, message):
    path = write(tmp_path, text)
    with pytest.raises(error, match=message) as info:
        load_spec(path)
    assert str(path) in str(info.value)


def test_empty_and_missing_files(tmp_path):
    with pytest.raises(InputFileError, match="empty"):
        load_spec(write(tmp_path, "  \n"))
    with pytest.raises(InputFileError, match="no such file"):
        read(str(tmp_path / "missing.toml"))
    with pytest.raises(InputFileError, match="unknown file type"):
        read(write(tmp_path, "x", "shape.xyz"))


def test_expression_errors_are_spec_errors():
    assert issubclass(ExpressionError, SpecError)
    with pytest.raises(SpecError):
        build_spec({"part": [{"type": "disc", "radius": "sqrt(-1)"}]})


def test_density_field_is_in_the_spec_frame_and_sees_parameters(tmp_path):
    path = write(tmp_path, """
[parameters]
k = 0.5
[shape]
density = "1 + k*x"
[[part]]
type = "rectangle"
width = 1
height = 1
at = [1, 0]
[[part]]
op = "subtract"
type = "rectangle"
width = 0.5
height = 0.5
at = [1.5, 0.25]
""")
    props = load_spec(path).body.mass_properties()
    # ∫ over [1,2]×[0,1] minus [1.5,2]×[0.25,0.75] of 1 + x/2
    mass = (1 + 0.5 * 1.5) - 0.5 * (0.5 + 0.5 * (2**2 - 1.5**2) / 2)
    first = (1.5 + 0.5 * 7 / 3) - 0.5 * ((2**2 - 1.5**2) / 2 + 0.5 * (2**3 - 1.5**3) / 3)
    assert props.mass == pytest.approx(mass, rel=1e-12)
    assert props.center_of_mass[0] == pytest.approx(first / mass, rel=1e-12)


def test_nested_group_is_placed_as_one(tmp_path):
    path = write(tmp_path, """
[[part]]
at = [10, 0]
[[part.part]]
type = "square"
side = 1
[[part.part]]
type = "square"
side = 1
at = [1, 0]
""")
    assert load_spec(path).body.mass_properties().center_of_mass == pytest.approx([11, 0.5])


def test_kind_chooses_the_reader_or_the_content_does(tmp_path):
    particles = '[[particle]]\nname = "A"\nmass = 1\nposition = [0, 0]\n'
    spring = particles + '[[particle]]\nname = "B"\nmass = 3\nposition = [4, 0]\n' \
        '[[spring]]\nbetween = ["A", "B"]\nstiffness = 1\n'
    # a simulation read for its mass properties: its particles at t = 0, kind given or not
    for text in (spring, 'kind = "simulation"\n' + spring):
        props = load_spec(write(tmp_path, text)).body.mass_properties()
        assert props.center_of_mass == pytest.approx([3, 0])
    assert load_spec(write(tmp_path, 'kind = "shape"\n' + particles)).body.kind == "particles"
    data = {"particle": [{"name": "A", "mass": 1, "position": [0, 0]}]}
    assert parse_simulation(data).model.names == ("A",)
    with pytest.raises(SpecError, match="not a simulation"):
        parse_simulation({"kind": "shape", **data})
    with pytest.raises(SpecError, match='"shape" or a "simulation"'):
        load_spec(write(tmp_path, 'kind = "lamina"\n' + particles))


def test_one_particle_schema_force_acts_only_in_a_simulation(tmp_path):
    forced = '[[particle]]\nmass = 2\nposition = [1, 0]\nforce = [1, 0]\n'
    assert load_spec(write(tmp_path, forced)).body.mass_properties().mass == 2  # a simulation
    with pytest.raises(SpecError, match="only in a simulation"):
        load_spec(write(tmp_path, '[shape]\nunits = "mm"\n' + forced))
    with pytest.raises(SpecError, match="names must be unique"):
        load_spec(write(tmp_path, '[[particle]]\nname = "A"\nmass = 1\nposition = [0, 0]\n' * 2))


def test_io_reads_files_and_leaves_specs_to_loading(tmp_path):
    from plumbob.formats import read as read_file

    with pytest.raises(InputFileError, match="plumbob.read"):
        read_file(write(tmp_path, '[[part]]\ntype = "disc"\nradius = 1\n'))


# ------------------------------------------------ issue 10: units, types, limits
def _write_3mf(path, side, unit):
    """A closed cube of ``side`` in a 3MF that declares ``unit``."""
    import zipfile

    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1],
                  [0, 1, 1]], float) * side
    f = [[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5],
         [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]]
    verts = "".join(f'<vertex x="{x}" y="{y}" z="{z}"/>' for x, y, z in v)
    tris = "".join(f'<triangle v1="{a}" v2="{b}" v3="{c}"/>' for a, b, c in f)
    model = (f'<?xml version="1.0" encoding="UTF-8"?><model unit="{unit}" '
             'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources>'
             f'<object id="1" type="model"><mesh><vertices>{verts}</vertices><triangles>{tris}'
             '</triangles></mesh></object></resources><build><item objectid="1"/></build></model>')
    rels = ('<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.'
            'openxmlformats.org/package/2006/relationships"><Relationship Target="/3D/'
            '3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/'
            '01/3dmodel"/></Relationships>')
    types = ('<?xml version="1.0" encoding="UTF-8"?><Types xmlns="http://schemas.openxmlformats'
             '.org/package/2006/content-types"><Default Extension="rels" ContentType="application'
             '/vnd.openxmlformats-package.relationships+xml"/><Default Extension="model" '
             'ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>')
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("[Content_Types].xml", types)
        z.writestr("_rels/.rels", rels)
        z.writestr("3D/3dmodel.model", model)


def test_a_mesh_file_that_declares_its_unit_keeps_it(tmp_path):
    """3MF in cm inside a spec in mm: the file's own unit wins (and is said)."""
    _write_3mf(tmp_path / "cube.3mf", 10, "centimeter")
    path = write(tmp_path, '[shape]\nunits = "mm"\n[[part]]\ntype = "mesh"\nfile = "cube.3mf"\n')
    reading = load_spec(path)
    assert reading.body.mass_properties().measure == pytest.approx(1e-3, rel=1e-14)
    assert reading.notices == ("mesh cube.3mf: units: centimeter (from the file)",)


def test_units_option_on_particles_scales_positions(tmp_path):
    path = write(tmp_path, "[[particle]]\nmass = 1\nposition = [0, 0]\n"
                           "[[particle]]\nmass = 1\nposition = [1000, 0]\n")
    props = read(path, units="mm").body.mass_properties()
    assert props.center_of_mass.tolist() == pytest.approx([0.5, 0.0], rel=1e-15)


@pytest.mark.parametrize("text, phrases", [
    ('[shape]\nunits = ["m"]\n[[part]]\ntype = "disc"\nradius = 1\n',
     ["shape.units", "['m'] (an array)"]),
    ('[[part]]\ntype = "box"\nlength = 1\nwidth = 1\nheight = 1\ncentered = "no"\n',
     ["part 1.centered", "'no' (text)", "true or false"]),
    ('[[part]]\ntype = "box"\nlength = 1\nwidth = 1\nheight = 1\ncentered = 0\n',
     ["part 1.centered", "0 (an integer)"]),
    ('[[part]]\ntype = "disc"\nradius = [1]\n', ["part 1.radius", "[1] (an array)"]),
    ('[[part]]\ntype = "mesh"\nfile = 5\n', ["part 1.file", "5 (an integer)", "a file name"]),
    ('[[part]]\ntype = "disc"\nradius = 1\n[[part]]\ntype = "disc"\nradius = 0.5\nop = 1\n',
     ["part 2.op", "1 (an integer)"]),
    ('title = 5\n[[particle]]\nmass = 1\nposition = [0, 0]\n', ["title", "5 (an integer)"]),
    ('[shape]\nfigure = 3\n[[part]]\ntype = "disc"\nradius = 1\n', ["shape.figure", "3"]),
])
def test_wrong_typed_values_name_key_value_and_type(tmp_path, text, phrases):
    with pytest.raises(SpecError) as error:
        load_spec(write(tmp_path, text))
    message = str(error.value)
    assert "\n" not in message
    for phrase in phrases:
        assert phrase in message


def test_centered_true_and_false_both_mean_what_they_say(tmp_path):
    def centre(flag):
        return load_spec(write(tmp_path, '[[part]]\ntype = "box"\nlength = 2\nwidth = 2\n'
                               f'height = 2\ncentered = {flag}\n')).body.mass_properties()
    assert centre("true").center_of_mass.tolist() == [0, 0, 0]
    assert centre("false").center_of_mass.tolist() == [1, 1, 1]


def test_a_caller_built_table_is_held_to_the_nesting_limit():
    from plumbob.errors import LimitError

    data: dict = {"type": "disc", "radius": 1}
    for _ in range(600):
        data = {"part": [data]}
    with pytest.raises(LimitError, match="MAX_SPEC_NESTING"):
        build_spec(data)


def test_a_fifo_is_refused_as_a_spec(tmp_path):
    fifo = tmp_path / "pipe.toml"
    os.mkfifo(fifo)
    with pytest.raises(InputFileError, match="FIFO"):
        load_spec(str(fifo))


def test_a_run_of_holes_is_cut_in_one_pass(tmp_path):
    holes = "".join(f'[[part]]\ntype = "disc"\nradius = 0.1\nat = [{0.5 + i}, 0.5]\n'
                    'op = "subtract"\n' for i in range(20))
    path = write(tmp_path, '[[part]]\ntype = "rectangle"\nwidth = 20\nheight = 1\n' + holes)
    props = load_spec(path).body.mass_properties()
    assert props.exact and props.area == pytest.approx(20 - 20 * np.pi * 0.01, rel=1e-14)


def test_shape_segments_sets_the_faceting_of_booleans(tmp_path):
    def lens(extra):
        return load_spec(write(tmp_path, f"[shape]\n{extra}\n[[part]]\ntype = \"disc\"\n"
                               "radius = 1\n[[part]]\ntype = \"disc\"\nradius = 1\n"
                               "at = [1, 0]\n")).body.mass_properties()
    exact = 2 * np.pi - (2 * np.pi / 3 - np.sqrt(3) / 2)
    coarse, fine = lens("segments = 32"), lens("")
    assert "32 and 16 segments" in " ".join(coarse.notes)
    assert "256 and 128 segments" in " ".join(fine.notes)
    assert abs(coarse.area - exact) <= coarse.relative_error * exact
    with pytest.raises(SpecError, match="shape.segments"):
        lens('segments = "many"')
    with pytest.raises(SpecError, match="at least 8"):
        lens("segments = 4")
