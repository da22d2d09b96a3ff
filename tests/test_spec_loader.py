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
    from plumbob.io import read as read_file

    with pytest.raises(InputFileError, match="plumbob.read"):
        read_file(write(tmp_path, '[[part]]\ntype = "disc"\nradius = 1\n'))
