import numpy as np
import pytest

from plumbob.bodies import primitives as P
from plumbob.bodies.csg import Assembly, Composite, Faceted, difference, intersection, union
from plumbob.bodies.lamina import Lamina
from plumbob.bodies.solid import MeshSolid
from plumbob.errors import GeometryError
from plumbob.massprops import rotation_matrix


def test_touching_parts_compose_exactly():
    l_shape = union(P.rectangle(2, 1), P.rectangle(1, 1).translated([0, 1]))
    assert isinstance(l_shape, Composite)
    props = l_shape.mass_properties()
    assert props.exact and props.parts == 2
    assert props.center_of_mass == pytest.approx([5 / 6, 5 / 6], rel=1e-15)


def test_hole_inside_is_exact_negative_mass():
    plate = difference(P.rectangle(4, 4), P.disc(1).translated([2, 2]))
    assert isinstance(plate, Composite)
    assert plate.mass_properties().area == pytest.approx(16 - np.pi, rel=1e-15)


def test_hole_outside_is_ignored_and_partial_hole_goes_faceted():
    plate = P.rectangle(4, 4)
    assert difference(plate, P.disc(1).translated([10, 10])) is plate
    bitten = difference(plate, P.disc(1).translated([4, 2]))
    props = bitten.mass_properties()
    assert not props.exact
    assert props.area == pytest.approx(16 - np.pi / 2, rel=10 * props.relative_error + 1e-12)


def test_overlapping_solids_faceted_with_honest_error_estimate():
    a = P.sphere(1.0, density=5.0)
    b = P.sphere(1.0, density=5.0).translated([1.0, 0, 0])
    both = union(a, b)
    assert isinstance(both, Faceted) and isinstance(both.shape, MeshSolid)
    props = both.mass_properties()
    lens = np.pi * (4 + 1) * (2 - 1) ** 2 / 12
    exact = 2 * 4 / 3 * np.pi - lens
    true_error = abs(props.volume - exact) / exact
    assert not props.exact
    assert 0 < true_error <= props.relative_error  # the estimate bounds the error
    assert true_error < 1e-7  # extrapolated over two facetings: far below either's 2e-4
    assert props.mass == pytest.approx(5 * props.volume, rel=1e-14)
    assert props.center_of_mass == pytest.approx([0.5, 0, 0], abs=1e-7)
    assert any("facets" in n for n in props.notes)


def test_faceted_laminas_keep_thickness_and_placed_solids_keep_density():
    discs = union(
        P.disc(1, density=2.0, thickness=0.5), P.disc(1, density=2.0, thickness=0.5).translated([1, 0])
    )
    area = 2 * np.pi - (2 * np.pi / 3 - np.sqrt(3) / 2)
    assert discs.mass_properties().mass == pytest.approx(area, rel=1e-5)  # 2 kg/m³ × 0.5 m
    turned = P.cylinder(0.5, 2, density=3.0).transformed(rotation_matrix([0, 1, 0], np.pi / 2))
    cross = union(P.cylinder(0.5, 2, density=3.0).translated([1, 0, -1]), turned)
    props = cross.mass_properties()
    assert props.mass == pytest.approx(3.0 * props.volume, rel=1e-14)


def test_intersection_picks_contained_part_exactly():
    inner = P.disc(1)
    assert intersection(inner, P.rectangle(5, 5).translated([-2, -2])) is inner
    lens = intersection(P.disc(1), P.disc(1).translated([1, 0]))
    exact = 2 * np.pi / 3 - np.sqrt(3) / 2
    props = lens.mass_properties()
    true_error = abs(props.area - exact) / exact
    assert true_error < 1e-5
    assert true_error <= props.relative_error


def test_disjoint_intersection_is_an_error():
    with pytest.raises(GeometryError, match="empty"):
        intersection(P.disc(1), P.disc(1).translated([5, 0]))


def test_overlap_of_different_densities_is_an_error():
    with pytest.raises(GeometryError, match="different densities"):
        union(P.disc(1, density=2), P.disc(1, density=3).translated([1, 0]))


def test_stepped_cylinder_from_two_placed_cylinders():
    turn = rotation_matrix([0, 1, 0], np.pi / 2)
    body = union(P.cylinder(1, 2).transformed(turn), P.cylinder(3, 2).transformed(turn, [2, 0, 0]))
    assert isinstance(body, Composite)
    assert body.mass_properties().center_of_mass == pytest.approx([14 / 5, 0, 0], abs=1e-14)


def test_hole_takes_the_parents_density():
    cup = difference(P.cylinder(1, 2, density=500), P.cylinder(0.5, 1.5).translated([0, 0, 0.5]))
    assert cup.mass_properties().mass == pytest.approx(500 * np.pi * (2 - 0.25 * 1.5), rel=1e-14)


def test_assembly_combines_parts_by_equation_15():
    head = P.sphere(0.05, density=7850).translated([0, 0, 1.05])
    shaft = P.cylinder(0.01, 1.0, density=600)
    assembly = Assembly((head, shaft))
    parts = assembly.part_properties()
    total = assembly.mass_properties()
    expected = sum(p.mass * p.center_of_mass for p in parts) / sum(p.mass for p in parts)
    assert total.center_of_mass == pytest.approx(expected, rel=1e-14)
    assert assembly.kind == "assembly"


def test_mirrored_lamina_keeps_positive_area():
    tri = P.triangle([0, 0], [2, 0], [0, 1])
    mirrored = tri.transformed(np.diag([-1.0, 1.0]))
    assert isinstance(mirrored, Lamina)
    assert mirrored.mass_properties().area == pytest.approx(1.0)


# --------------------------------------------------- far from the origin (issue 10)
def _lens_union_volume(r: float, d: float) -> float:
    """Two spheres of radius r, centres d apart: 2 × (4/3)πr³ less their lens,
    π (4r + d)(2r − d)² / 12."""
    return 2 * 4 / 3 * np.pi * r**3 - np.pi * (4 * r + d) * (2 * r - d) ** 2 / 12


@pytest.mark.parametrize("far", [1e6, 1e8])
def test_a_boolean_far_away_is_as_good_as_at_the_origin(far):
    """Shifted to a local origin for the boolean: the error and its stated bound are
    those at the origin, and the true error stays within the bound."""
    at_origin = union(P.sphere(1), P.sphere(1).translated([1, 0, 0])).mass_properties()
    offset = np.array([far, -far / 3, far / 7])
    moved = union(P.sphere(1).translated(offset),
                  P.sphere(1).translated(offset + [1, 0, 0])).mass_properties()
    exact = _lens_union_volume(1.0, 1.0)
    assert not moved.exact
    assert abs(moved.measure - exact) / exact <= moved.relative_error
    assert moved.relative_error == pytest.approx(at_origin.relative_error, rel=1e-3)
    assert moved.measure == pytest.approx(at_origin.measure, rel=1e-9)
    assert moved.center_of_mass - offset == pytest.approx([0.5, 0, 0], abs=1e-7)
    assert moved.inertia == pytest.approx(at_origin.inertia, rel=1e-8)


def test_a_difference_far_away_keeps_its_accuracy():
    offset = np.array([3e7, 0, 0])
    near = difference(P.box(2, 2, 2), P.sphere(1).translated([2, 1, 1])).mass_properties()
    far = difference(P.box(2, 2, 2).translated(offset),
                     P.sphere(1).translated(offset + [2, 1, 1])).mass_properties()
    assert far.measure == pytest.approx(8 - 2 / 3 * np.pi, rel=far.relative_error)
    assert far.measure == pytest.approx(near.measure, rel=1e-6)
    assert far.relative_error == pytest.approx(near.relative_error, rel=1e-2)


# ------------------------------------------------------------ many parts
def test_only_the_overlapping_parts_go_faceted():
    """Three spheres, two of which overlap: the lone one stays an exact part."""
    body = union(P.sphere(1), P.sphere(1).translated([1, 0, 0]), P.sphere(1).translated([9, 0, 0]))
    assert isinstance(body, Composite) and len(body.parts) == 2
    assert isinstance(body.parts[0], Faceted) and not isinstance(body.parts[1], Faceted)
    props = body.mass_properties()
    exact = _lens_union_volume(1.0, 1.0) + 4 / 3 * np.pi
    assert abs(props.measure - exact) / exact <= props.relative_error
    assert not props.exact


def test_many_disjoint_parts_need_no_facets(monkeypatch):
    """A grid of 400 spheres touches no boolean: to_geometry is never called."""
    def refuse(*args, **kwargs):
        raise AssertionError("a disjoint part was faceted")

    spheres = [P.sphere(0.4).translated([i % 20, i // 20, 0]) for i in range(400)]
    monkeypatch.setattr(type(spheres[0]), "to_geometry", refuse)
    body = union(*spheres)
    assert isinstance(body, Composite) and len(body.parts) == 400
    assert body.mass_properties().measure == pytest.approx(400 * 4 / 3 * np.pi * 0.064,
                                                          rel=1e-14)


def test_holes_whose_boxes_miss_the_body_are_skipped():
    plate = P.rectangle(1, 1)
    assert difference(plate, *[P.disc(0.1).translated([5 + i, 5]) for i in range(50)]) is plate


@pytest.mark.parametrize("far", [1e6, 1e8])
def test_a_lamina_boolean_far_away_is_as_good_as_at_the_origin(far):
    """Two unit discs 1 apart: area 2π less the lens 2π/3 − √3/2."""
    offset = np.array([far, far / 3])
    props = union(P.disc(1).translated(offset),
                  P.disc(1).translated(offset + [1, 0])).mass_properties()
    exact = 2 * np.pi - (2 * np.pi / 3 - np.sqrt(3) / 2)
    assert abs(props.area - exact) / exact <= props.relative_error
    assert props.center_of_mass - offset == pytest.approx([0.5, 0], abs=1e-7)


def test_a_boolean_near_the_largest_float_keeps_its_volume():
    """At 1e308 a plain norm of the coordinates overflows: the boxes and the local
    origin must not, so the lens is still found and measured."""
    a = P.sphere(1).translated([1e308, 0, 0])
    b = P.sphere(1).translated([1e308, 0.5, 0])
    props = union(a, b).mass_properties()
    exact = _lens_union_volume(1.0, 0.5)
    assert abs(props.measure - exact) / exact <= props.relative_error

