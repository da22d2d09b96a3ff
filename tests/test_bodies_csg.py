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
