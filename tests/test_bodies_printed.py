"""Inward offsets and as-printed bodies (``--shell``/``--infill``) against closed forms.

Exact offsets (boxes, convex meshes, balls, cylinders, cones, tori, convex prisms)
must give the closed forms to 1e-9; level-set offsets must agree within the error
they state.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from plumbob.bodies.csg import union
from plumbob.bodies.offset import inward_offset
from plumbob.bodies.primitives import box, cone, cylinder, disc, polygon, prism, sphere, torus
from plumbob.bodies.printed import Printed, parse_fraction, parse_length, printed
from plumbob.errors import GeometryError
from plumbob.massprops import rotation_matrix
from plumbob.stability import check, resting_poses

RHO = 1240.0  # PLA, kg/m³


def _box_inertia(mass, a, b, c):
    return mass / 12 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])


# ---------------------------------------------------------------- inward offsets
@pytest.mark.parametrize("body, t, volume", [
    (box(4, 3, 2), 0.25, 3.5 * 2.5 * 1.5),
    (sphere(1.5), 0.5, 4 / 3 * np.pi),
    (cylinder(1, 3), 0.25, np.pi * 0.75**2 * 2.5),
    (torus(3, 1), 0.5, 2 * np.pi**2 * 3 * 0.25),
    (prism(disc(2), 1), 0.25, np.pi * 1.75**2 * 0.5),
    (prism(polygon([[0, 0], [4, 0], [0, 3]]), 2), 0.5, None),  # a right triangle: inradius 1
])
def test_exact_offsets_match_closed_forms(body, t, volume):
    offset = inward_offset(body, t)
    assert offset.exact and offset.surface_error == 0.0
    got = offset.body.mass_properties().measure
    if volume is None:  # the 3-4-5 triangle's offset is similar to it, scaled by (r − t)/r
        volume = 6 * ((1 - t) / 1) ** 2 * (2 - 2 * t)
    assert got == pytest.approx(volume, rel=1e-12)


def test_cone_offset_is_the_similar_cone():
    """A cone's inner offset: base raised by t, slant moved in by t — a similar cone whose
    apex drops by t / sin α (α the half angle at the apex)."""
    r, h, t = 1.0, 2.0, 0.1
    sin_a = r / np.hypot(r, h)
    inner_h = h - t / sin_a - t
    expected = cone(r * inner_h / h, inner_h).translated([0, 0, t]).mass_properties()
    got = inward_offset(cone(r, h), t).body.mass_properties()
    assert got.measure == pytest.approx(expected.measure, rel=1e-12)
    assert np.allclose(got.center_of_mass, expected.center_of_mass, rtol=0, atol=1e-12)
    assert np.allclose(got.inertia, expected.inertia, rtol=1e-10, atol=0)


def test_convex_mesh_offset_placed_and_turned():
    turn = rotation_matrix([1, 1, 0], 0.7)
    moved = box(2, 2, 2).transformed(turn, [5.0, -1.0, 2.0])
    offset = inward_offset(moved, 0.5)
    expected = box(1, 1, 1).transformed(turn, turn @ [0.5, 0.5, 0.5] + [5.0, -1.0, 2.0])
    got, want = offset.body.mass_properties(), expected.mass_properties()
    assert offset.exact
    assert got.measure == pytest.approx(1.0, rel=1e-12)
    assert np.allclose(got.center_of_mass, want.center_of_mass, atol=1e-12)
    assert np.allclose(got.inertia, want.inertia, atol=1e-12)


def test_offset_deeper_than_the_body_is_empty():
    assert inward_offset(box(1, 1, 1), 0.5).empty
    assert inward_offset(sphere(1), 1.0).empty
    assert inward_offset(cylinder(1, 5), 1.0).empty


@pytest.mark.parametrize("distance", [0.0, -1.0, float("nan")])
def test_offset_needs_a_positive_distance(distance):
    with pytest.raises(GeometryError, match="positive distance"):
        inward_offset(box(1, 1, 1), distance)


def test_level_set_offset_of_an_l_prism_within_its_stated_error():
    """A non-convex L prism has no closed-form path in plumbob, so it goes through the
    level set. Its true offset: every edge moved in by t, plus the (1 − π/4) t² the
    quarter circle about the reflex corner keeps, times the height less 2t."""
    ell = prism(polygon([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]), 1.0)
    t = 0.1
    offset = inward_offset(ell, t, step=0.025)
    assert not offset.exact and offset.method.startswith("level set")
    sharp = 1.8 * 0.8 + 0.8 * 1.0
    volume = (sharp + (1 - np.pi / 4) * t * t) * (1 - 2 * t)
    got = offset.body.mass_properties().measure
    assert 0 < offset.relative_error < 0.02
    assert abs(got - volume) / volume <= offset.relative_error


# ---------------------------------------------------------------- printed parts
def test_printed_cube_closed_form():
    a, t, f = 0.02, 0.0012, 0.2
    props = printed(box(a, a, a, density=RHO), t, f).mass_properties()
    inner = a - 2 * t
    mass = RHO * (a**3 - (1 - f) * inner**3)
    inertia = RHO * (a**5 - (1 - f) * inner**5) / 6 * np.eye(3)  # a cube: m a² / 6 each
    assert props.exact
    assert props.mass == pytest.approx(mass, rel=1e-12)
    assert props.measure == pytest.approx(a**3, rel=1e-12)
    assert np.allclose(props.center_of_mass, [a / 2] * 3, rtol=0, atol=1e-15)
    assert np.allclose(props.inertia, inertia, rtol=1e-9, atol=1e-20)


def test_printed_sphere_closed_form():
    r, t, f = 0.03, 0.002, 0.15
    props = printed(sphere(r, density=RHO), t, f).mass_properties()
    mass = RHO * 4 / 3 * np.pi * (r**3 - (1 - f) * (r - t) ** 3)
    inertia = RHO * 8 / 15 * np.pi * (r**5 - (1 - f) * (r - t) ** 5)  # 2/5 m r² = 8π/15 ρ r⁵
    assert props.exact
    assert props.mass == pytest.approx(mass, rel=1e-12)
    assert np.allclose(np.diag(props.inertia), inertia, rtol=1e-9)


def test_hollow_walled_box_closed_form():
    """Infill 0: only the walls — a closed box of 2 mm walls, its centre and inertia
    those of the solid box less the cavity."""
    a, b, c, t = 0.1, 0.06, 0.04, 0.002
    props = printed(box(a, b, c, density=RHO).translated([0.3, 0, 0]), t, 0.0).mass_properties()
    outer, cavity = RHO * a * b * c, RHO * (a - 2 * t) * (b - 2 * t) * (c - 2 * t)
    inertia = _box_inertia(outer, a, b, c) - _box_inertia(cavity, a - 2 * t, b - 2 * t, c - 2 * t)
    assert props.mass == pytest.approx(outer - cavity, rel=1e-12)
    assert np.allclose(props.center_of_mass, [0.35, 0.03, 0.02], atol=1e-15)
    assert np.allclose(props.inertia, inertia, rtol=1e-9, atol=1e-18)


def test_printed_cone_centre_moves():
    """A cone's walls are thicker at the base, relative to its section: the printed cone's
    centre lies below the solid's — as the inner cone placed by hand says."""
    r, h, t, f = 0.03, 0.06, 0.003, 0.1
    sin_a = r / np.hypot(r, h)
    inner_h = h - t / sin_a - t
    inner = cone(r * inner_h / h, inner_h, density=RHO).translated([0, 0, t]).mass_properties()
    solid = cone(r, h, density=RHO).mass_properties()
    expected = solid.mass - (1 - f) * inner.mass
    centre = (solid.mass * solid.center_of_mass - (1 - f) * inner.mass * inner.center_of_mass) / expected
    props = printed(cone(r, h, density=RHO), t, f).mass_properties()
    assert props.mass == pytest.approx(expected, rel=1e-12)
    assert np.allclose(props.center_of_mass, centre, atol=1e-14)
    assert props.center_of_mass[2] < solid.center_of_mass[2]


def test_printed_level_set_part_states_its_error():
    ell = prism(polygon([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]), 1.0, density=1000.0)
    t, f = 0.1, 0.25
    part = printed(ell, t, f)
    props = part.mass_properties()
    inner = (1.8 * 0.8 + 0.8 * 1.0 + (1 - np.pi / 4) * t * t) * (1 - 2 * t)
    mass = 1000.0 * (3.0 - (1 - f) * inner)
    assert not props.exact
    assert 0 < props.relative_error < 0.05
    assert abs(props.mass - mass) / mass <= props.relative_error
    assert any("level set" in n for n in props.notes)


@settings(max_examples=25, deadline=None)
@given(st.floats(0.01, 0.2), st.floats(0.01, 0.2), st.floats(0.01, 0.2),
       st.floats(0.0005, 0.004), st.floats(0.0, 1.0))
def test_printed_box_property(a, b, c, t, f):
    """Any box: mass ρ(abc − (1 − f)·Π(side − 2t)), a part that is all wall when a side is
    at most 2t, and never more than the solid."""
    solid = RHO * a * b * c
    inner = np.prod([max(s - 2 * t, 0.0) for s in (a, b, c)])
    props = printed(box(a, b, c, density=RHO), t, f).mass_properties()
    assert props.mass == pytest.approx(solid - (1 - f) * RHO * inner, rel=1e-9)
    assert props.mass <= solid * (1 + 1e-12)


def test_printed_body_answers_as_a_body():
    """Stability and poses see the printed part's centre with the solid's outside."""
    part = printed(cone(0.03, 0.06, density=RHO), 0.003, 0.1)
    assert isinstance(part, Printed)
    verdict = check(part)
    assert verdict.stands
    assert np.allclose(verdict.center_of_mass, part.mass_properties().center_of_mass)
    assert part.contains([[0, 0, 0.01], [0, 0, 0.07]]).tolist() == [True, False]
    poses = resting_poses(part)
    assert len(poses.poses) >= 1


def test_printed_needs_one_solid_and_a_fraction():
    with pytest.raises(GeometryError, match="between 0 and 1"):
        printed(box(1, 1, 1), 0.1, 1.2)
    with pytest.raises(GeometryError, match="only a solid"):
        printed(disc(1), 0.1, 0.2)
    with pytest.raises(GeometryError, match="one density"):
        printed(union(box(1, 1, 1, density=1.0), box(1, 1, 1, density=2.0).translated([3, 0, 0])),
                0.1, 0.2)


def test_parse_length_and_fraction():
    assert parse_length("1.2mm") == pytest.approx(0.0012)
    assert parse_length("2", scale=1e-3) == pytest.approx(0.002)
    assert parse_fraction("20%") == pytest.approx(0.2) and parse_fraction("0.35") == 0.35
    with pytest.raises(GeometryError):
        parse_length("1.2 parsecs")
    with pytest.raises(GeometryError):
        parse_fraction("lots")


# ---------------------------------------------------------------- command line and spec
def _write_cube_stl(path, side_mm):
    from plumbob.formats.writers import stl_bytes

    path.write_bytes(stl_bytes(box(side_mm, side_mm, side_mm).triangles, "cube"))


def _json(capsys, *argv):
    from plumbob.cli import main

    assert main(list(argv)) in (0, None)
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("command", ["mass", "check", "poses"])
def test_cli_shell_and_infill(tmp_path, capsys, command):
    stl = tmp_path / "cube.stl"
    _write_cube_stl(stl, 20)
    out = _json(capsys, command, str(stl), "--units", "mm", "--density", str(RHO),
                "--shell", "1.2mm", "--infill", "20%", "--json")
    mass = RHO * (0.02**3 - 0.8 * 0.0176**3)
    assert out["mass"] == pytest.approx(mass, rel=1e-6)  # float32 STL corners


def test_cli_bare_shell_is_in_the_file_units(tmp_path, capsys):
    stl = tmp_path / "cube.stl"
    _write_cube_stl(stl, 20)
    out = _json(capsys, "mass", str(stl), "--units", "mm", "--density", "1000",
                "--shell", "2", "--infill", "0", "--json")
    assert out["mass"] == pytest.approx(1000 * (0.02**3 - 0.016**3), rel=1e-6)


def test_spec_part_shell_and_infill(tmp_path, capsys):
    spec = tmp_path / "cube.toml"
    spec.write_text('[shape]\nunits = "mm"\ndensity = 1240\n\n[[part]]\ntype = "cube"\nside = 20\n'
                    'shell = 1.2\ninfill = "20%"\n')
    out = _json(capsys, "mass", str(spec), "--json")
    assert out["mass"] == pytest.approx(RHO * (0.02**3 - 0.8 * 0.0176**3), rel=1e-12)


@pytest.mark.parametrize("args, phrase", [
    (["--shell", "1.2mm"], "give both"),
    (["--infill", "20%"], "give both"),
    (["--shell", "1.2mm", "--infill", "150%"], "between 0 and 1"),
    (["--shell", "-1mm", "--infill", "20%"], "positive"),
    (["--shell", "thick", "--infill", "20%"], "a shell thickness"),
])
def test_cli_bad_print_options_are_one_line(tmp_path, args, phrase):
    from hostile import assert_bad_input, run_limited

    stl = tmp_path / "cube.stl"
    _write_cube_stl(stl, 20)
    outcome = run_limited("mass", str(stl), "--units", "mm", *args, cwd=tmp_path)
    assert_bad_input(outcome, phrase)


def test_spec_part_needs_both_keys(tmp_path):
    from plumbob import read
    from plumbob.errors import SpecError

    spec = tmp_path / "cube.toml"
    spec.write_text('[[part]]\ntype = "cube"\nside = 1\nshell = 0.1\n')
    with pytest.raises(SpecError, match="give both shell"):
        read(str(spec))
