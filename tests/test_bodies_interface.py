"""The questions every body answers (plumbob.bodies.base.Body): contains, is_polytope,
density_cells, densities, graded — and a clear error from a body kind that does not."""

import numpy as np
import pytest

from plumbob.bodies import primitives as P
from plumbob.bodies.base import Body, DensityCells
from plumbob.bodies.containment import mesh_contains, triangle_distances
from plumbob.bodies.csg import Assembly, Composite, Faceted, difference, union
from plumbob.bodies.density_field import DensityField
from plumbob.bodies.graded import GradedSolid, with_density_field
from plumbob.bodies.particles import ParticleSystem
from plumbob.bodies.solid import MeshSolid
from plumbob.errors import BodyQueryError, DensityError, GeometryError, PlumbobError
from plumbob.massprops import MassProperties, rotation_matrix
from plumbob.mesh import solid_angle, winding_numbers

RNG = np.random.default_rng(9)


class Blob(Body):
    """A body kind that implements only the abstract methods."""

    kind = "solid"
    dim = 3

    def mass_properties(self) -> MassProperties:
        return P.box(1, 1, 1).mass_properties()

    def hull_points(self, tolerance=None) -> np.ndarray:
        return P.box(1, 1, 1).hull_points()

    def contains(self, points, tolerance=None) -> np.ndarray:
        return P.box(1, 1, 1).contains(points, tolerance)

    @property
    def is_polytope(self) -> bool:
        return True

    def densities(self) -> set:
        return {None}


class Shy(Blob):
    """A body kind that cannot answer two questions, and says so."""

    def contains(self, points, tolerance=None) -> np.ndarray:
        raise BodyQueryError("a Shy cannot tell which points it contains")

    @property
    def is_polytope(self) -> bool:
        raise BodyQueryError("a Shy cannot tell whether its hull points are exact")


# ------------------------------------------------------------------ contains, kind by kind
def test_lamina_contains_with_its_boundary():
    square = P.rectangle(2, 1)
    pts = np.array([[1, 0.5], [0, 0], [2, 0.5], [2.001, 0.5], [-1, 0]])
    assert square.contains(pts).tolist() == [True, True, True, False, False]
    assert square.contains(pts, tolerance=0.01).tolist() == [True, True, True, True, False]
    assert square.contains(pts, tolerance=-0.1).tolist() == [True, False, False, False, False]


def test_curved_lamina_contains_points_on_its_arc():
    disc = P.disc(1)
    t = RNG.uniform(0, 2 * np.pi, 50)
    rim = np.stack((np.cos(t), np.sin(t)), axis=1)
    assert disc.contains(rim).all()
    assert not disc.contains(rim * (1 + 1e-4)).any()
    assert disc.contains(rim * (1 - 1e-4)).all()
    annulus = P.annulus(1, 2)
    assert annulus.contains([[0, 0], [1.5, 0], [0, -1], [2.5, 0]]).tolist() == [False, True, True, False]


def test_a_single_point_is_one_row():
    assert P.disc(1).contains([0.5, 0]).tolist() == [True]


def test_points_of_the_wrong_dimension_are_refused():
    with pytest.raises(GeometryError, match="3 coordinates"):
        P.box(1, 1, 1).contains([[0, 0]])


def test_mesh_contains_matches_the_box_and_its_surface():
    box = P.box(1, 2, 3)
    pts = RNG.uniform(-0.5, 3.5, (400, 3))
    want = np.all((pts >= 0) & (pts <= [1, 2, 3]), axis=1)
    np.testing.assert_array_equal(box.contains(pts), want)
    corners_edges_faces = np.array([[0, 0, 0], [1, 2, 3], [0.5, 0, 0], [0.5, 1, 3], [1, 1, 1.5]])
    assert box.contains(corners_edges_faces).all()  # on the body
    assert not box.contains(corners_edges_faces, tolerance=-1e-3).any()  # not inside it


def test_mesh_contains_a_non_convex_pyramid():
    base = np.array([[0, 0], [3, 0], [3, 1], [1, 1], [1, 3], [0, 3]], dtype=float)
    body = P.pyramid(base, 1.0, apex=[0.5, 0.5])
    assert body.contains([[0.5, 0.5, 0.5], [2, 2, 0.01], [2.5, 0.5, 0.01]]).tolist() == [True, False, True]


def test_prism_and_revolution_contain():
    prism = P.prism(P.disc(1), 2.0)
    assert prism.contains([[0, 0, 1], [1, 0, 2], [0, 0, 2.01], [1.01, 0, 1]]).tolist() == [
        True, True, False, False]
    ball = P.sphere(1)
    pts = RNG.uniform(-1.2, 1.2, (300, 3))
    r = np.linalg.norm(pts, axis=1)
    keep = np.abs(r - 1) > 1e-3
    np.testing.assert_array_equal(ball.contains(pts[keep]), r[keep] < 1)
    ring = P.torus(2, 0.5)
    assert ring.contains([[2, 0, 0], [0, -2.4, 0], [0, 0, 0], [2, 0, 0.6]]).tolist() == [
        True, True, False, False]


def test_placed_bodies_contain_in_world_coordinates():
    m = rotation_matrix([0, 0, 1], 90)
    box = P.box(1, 2, 3)
    placed = box.transformed(m, [10, 0, 0])  # a mesh moves its triangles
    cyl = P.cylinder(1, 2).transformed(m, [10, 0, 0])  # a revolution is wrapped
    assert placed.contains([[9.0, 0.5, 1.0], [10.5, 0.5, 1]]).tolist() == [True, False]
    assert cyl.contains([[10.5, 0.5, 1.0], [12, 0, 1]]).tolist() == [True, False]


def test_composite_keeps_a_hole_rim_and_removes_its_inside():
    plate = difference(P.rectangle(4, 4), P.disc(1).translated([2, 2]))
    assert isinstance(plate, Composite)
    assert plate.contains([[0.5, 0.5], [2, 2], [3, 2], [2.5, 2]]).tolist() == [True, False, True, False]


def test_assembly_contains_in_any_part_and_a_lamina_in_z0():
    asm = Assembly((P.box(1, 1, 1), P.rectangle(1, 1).translated([5, 0])))
    assert asm.contains([[0.5, 0.5, 0.5], [5.5, 0.5, 0], [5.5, 0.5, 0.1], [3, 0, 0]]).tolist() == [
        True, True, False, False]


def test_faceted_graded_and_particles_contain():
    both = union(P.sphere(1), P.sphere(1).translated([1, 0, 0]))
    assert isinstance(both, Faceted)
    assert both.contains([[1.5, 0, 0], [0.5, 0, 0], [3, 0, 0]]).tolist() == [True, True, False]
    graded = with_density_field(P.cylinder(1, 2), DensityField.from_expression("1 + z"))
    assert graded.contains([[0, 0, 1], [0, 0, 3]]).tolist() == [True, False]
    dots = ParticleSystem([1.0, 1.0], [[0, 0, 0], [1, 0, 0]])
    assert dots.contains([[1, 0, 0], [0.5, 0, 0]]).tolist() == [True, False]


# ------------------------------------------------------------------ is_polytope
@pytest.mark.parametrize("body, exact", [
    (P.box(1, 1, 1), True),
    (P.rectangle(1, 1), True),
    (P.disc(1), False),
    (P.prism(P.rectangle(1, 1), 1), True),
    (P.prism(P.disc(1), 1), False),
    (P.cylinder(1, 1), False),
    (P.box(1, 1, 1).transformed(rotation_matrix([1, 0, 0], 30)), True),
    (P.cylinder(1, 1).translated([1, 0, 0]), False),
    (ParticleSystem([1.0], [[0, 0, 0]]), True),
    (Assembly((P.box(1, 1, 1), P.sphere(1))), False),
])
def test_is_polytope(body, exact):
    assert body.is_polytope is exact
    assert with_density_field(P.box(1, 1, 1), lambda p: p[:, 0] + 1).is_polytope


def test_faceted_results_are_polytopes_only_where_no_curve_was_faceted():
    """The facets of a union of spheres are chords of them, not the body's own corners;
    a union of boxes keeps its exact corners."""
    assert not union(P.sphere(1), P.sphere(1).translated([1, 0, 0])).is_polytope
    assert union(P.box(1, 1, 1), P.box(1, 1, 1).translated([0.5, 0, 0])).is_polytope


# ------------------------------------------------------------------ density cells
@pytest.mark.parametrize("body", [P.disc(1), P.box(1, 2, 3), P.prism(P.disc(1), 2), P.sphere(1)])
def test_density_cells_integrate_the_measure(body):
    from plumbob.integrals.adaptive import integrate_field

    cells = body.density_cells()
    assert isinstance(cells, DensityCells) and cells.origin.shape == (body.dim,) and cells.size > 0
    result = integrate_field(cells.tiles(), lambda p: np.ones(len(p)), cells.origin, 0,
                             tolerance=1e-10, size=cells.size)
    assert result.mass == pytest.approx(body.mass_properties().measure, rel=1e-12)
    assert cells.corners().shape[1] == body.dim
    assert (cells.triangles is not None) == isinstance(body, MeshSolid)


def test_density_cells_of_an_open_mesh_refuse_when_tiled():
    # checked=True skips the constructor's closure check (which refuses it first)
    cells = MeshSolid(P.box(1, 1, 1).triangles[:-1], checked=True).density_cells()
    with pytest.raises(GeometryError, match="not closed"):
        cells.tiles()


def test_bodies_without_cells_say_why():
    with pytest.raises(DensityError, match="particles"):
        ParticleSystem([1.0], [[0, 0]]).density_cells()
    with pytest.raises(DensityError, match="faceted"):
        union(P.disc(1), P.disc(1).translated([1, 0])).density_cells()
    with pytest.raises(BodyQueryError, match="cannot be integrated over a Assembly|Assembly"):
        Assembly((P.box(1, 1, 1),)).density_cells()


# ------------------------------------------------------------------ densities
def test_densities_of_each_kind():
    assert P.box(1, 1, 1, density=2).densities() == {2.0}
    assert P.rectangle(1, 1, density=1000, thickness=0.002).densities() == {2.0}
    assert P.rectangle(1, 1).densities() == {None}
    assert Assembly((P.box(1, 1, 1, density=2), P.sphere(1))).densities() == {2.0, None}
    assert with_density_field(P.disc(1), lambda p: 1 + p[:, 0]).densities() == {"field"}
    assert ParticleSystem([1.0], [[0, 0]]).densities() == set()
    assert P.box(1, 1, 1, density=3).translated([1, 1, 1]).densities() == {3.0}


# ------------------------------------------------------------------ unimplemented questions
def test_the_contract_is_abstract_where_no_default_is_honest():
    assert Body.__abstractmethods__ == {"mass_properties", "hull_points", "contains",
                                        "is_polytope", "densities"}

    class Half(Body):
        kind, dim = "solid", 3

        def mass_properties(self):
            return P.box(1, 1, 1).mass_properties()

        def hull_points(self, tolerance=None):
            return P.box(1, 1, 1).hull_points()

    with pytest.raises(TypeError, match="contains.*densities.*is_polytope"):
        Half()


def test_an_unimplemented_question_is_an_error_never_a_default():
    blob = Blob()
    with pytest.raises(BodyQueryError, match="density field"):
        blob.density_cells()
    with pytest.raises(BodyQueryError):
        with_density_field(blob, lambda p: p[:, 0])
    with pytest.raises(GeometryError, match="boolean operations"):
        blob.surface()
    with pytest.raises(GeometryError, match="no plain 2D profile"):
        blob.exact_region()
    with pytest.raises(GeometryError, match="no outline"):
        blob.outline(1e-3)
    assert blob.as_mesh() is None and blob.assembly_parts() == ()
    assert issubclass(BodyQueryError, PlumbobError)


def test_stability_asks_the_body_whether_it_is_a_polytope():
    from plumbob.stability.support import is_polytope

    assert is_polytope(P.box(1, 1, 1), 1.0) and not is_polytope(P.sphere(1), 2.0)
    with pytest.raises(BodyQueryError, match="hull points are exact"):
        is_polytope(Shy(), 1.0)


def test_a_placed_body_passes_the_question_on():
    with pytest.raises(BodyQueryError, match="contains"):
        Shy().translated([1, 0, 0]).contains([[0, 0, 0]])
    assert Blob().translated([1, 0, 0]).contains([[1.5, 0.5, 0.5], [0.5, 0.5, 0.5]]).tolist() == [
        True, False]


# ------------------------------------------------------------------ surfaces and outlines
@pytest.mark.parametrize("body", [
    P.box(1, 2, 3), P.cylinder(1, 2), P.sphere(1).translated([1, 0, 0]),
    P.box(1, 2, 3).transformed(np.diag([1.0, 1.0, -1.0])),
    union(P.sphere(1), P.sphere(1).translated([1, 0, 0])),
], ids=["mesh", "cylinder", "placed", "mirrored", "faceted"])
def test_a_solids_surface_is_closed_outward_and_matches_its_volume(body):
    from plumbob.integrals.mesh import triangle_soup_moments

    surface = body.surface(256)
    volume = triangle_soup_moments(surface.triangles).m0
    exact = body.mass_properties().measure
    # a faceting at 256 chords a turn, in latitude and longitude, loses at most about
    # 4(1 - cos(pi/256)) = 3.0e-4 of a curved volume; a mesh's own surface is its volume
    assert volume == pytest.approx(exact, rel=1e-12 if surface.exact else 4 * (1 - np.cos(np.pi / 256)))
    assert (body.as_mesh() is not None) == surface.exact
    assert surface.exact == (body.is_polytope and not isinstance(body, Faceted))


def test_a_laminas_outline_follows_its_placement():
    disc = P.disc(1).transformed(np.array([[1.0, 0.0], [0.0, -1.0]]), np.array([2.0, 0.0]))
    (ring,) = disc.outline(1e-4)
    assert np.allclose(ring[0], ring[-1]) and np.allclose(np.linalg.norm(ring - [2, 0], axis=1), 1, atol=1e-4)
    x, y = ring[:, 0], ring[:, 1]
    assert 0.5 * np.sum(x[:-1] * y[1:] - x[1:] * y[:-1]) > 0  # counter-clockwise after the mirror


def test_an_assembly_lists_its_parts_and_nothing_else_does():
    parts = (P.box(1, 1, 1, name="a"), P.sphere(1, name="b").translated([3, 0, 0]))
    assert Assembly(parts).assembly_parts() == parts
    assert P.box(1, 1, 1).assembly_parts() == () == union(*parts).assembly_parts()


# ------------------------------------------------------------------ reprs
@pytest.mark.parametrize("body", [
    P.box(1, 2, 3, name="part"), P.disc(1), P.annulus(1, 2, density=7800, thickness=0.01),
    P.cylinder(1, 2), P.prism(P.rectangle(1, 1), 2), P.sphere(1).translated([1, 0, 0]),
    difference(P.rectangle(4, 4), P.disc(1).translated([2, 2])),
    union(P.sphere(1), P.sphere(1).translated([1, 0, 0])),
    Assembly((P.box(1, 1, 1, name="a"), P.sphere(1, name="b"))),
    with_density_field(P.sphere(1), DensityField.from_expression("1 + z")),
    ParticleSystem([1.0, 2.0], [[0, 0], [1, 1]]),
    MeshSolid(P.box(1, 1, 1).triangles[:, ::-1]),
    P.box(200, 1, 1).transformed(rotation_matrix([0, 0, 1], 90)),
])
def test_reprs_are_short_and_never_dump_arrays(body):
    text = repr(body)
    assert text.startswith(f"<{type(body).__name__}") and text.endswith(">")
    assert "\n" not in text and "array" not in text and "[" not in text
    assert len(text) < 200


def test_repr_says_what_the_body_is():
    assert repr(P.box(1, 2, 3, name="part", density=2700)) == (
        "<MeshSolid 'part' 12 triangles, volume 6 m³, density 2700 kg/m³>")
    assert repr(P.disc(1).region) == "<Region 1 ring of 2 edges (2 arcs)>"
    inside_out = MeshSolid(P.box(1, 1, 1).triangles[:, ::-1])
    assert repr(inside_out) == "<MeshSolid 12 triangles, no valid volume>"
    graded = with_density_field(P.box(1, 1, 1), DensityField.from_expression("1 + x"))
    assert isinstance(graded, GradedSolid) and "'1 + x' kg/m³" in repr(graded)
    assert repr(DensityField.from_expression("1 + x")) == "<DensityField '1 + x' of degree 1>"


# ------------------------------------------------------------------ the mesh kernels
def test_solid_angles_of_a_cube_face_sum_to_the_sphere():
    tri = P.box(2, 2, 2).triangles - 1.0  # centred on the origin
    omega = solid_angle(tri[:, 0], tri[:, 1], tri[:, 2])
    assert omega.sum() == pytest.approx(4 * np.pi, rel=1e-14)
    assert omega[:2].sum() == pytest.approx(4 * np.pi / 6, rel=1e-14)  # one face: a sixth


def test_winding_numbers_inside_outside_and_on_a_face():
    tri = P.box(1, 1, 1).triangles
    w = winding_numbers(np.array([[0.5, 0.5, 0.5], [0.5, 0.5, 1.0], [3, 3, 3]]), tri)[:, 0]
    np.testing.assert_allclose(w, [1.0, 0.5, 0.0], atol=1e-12)
    inverted = tri[:, ::-1]
    assert winding_numbers(np.array([[0.5, 0.5, 0.5]]), inverted)[0, 0] == pytest.approx(-1)


def test_triangle_distances_by_region():
    tri = np.array([[[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]])
    pts = np.array([[0.25, 0.25, -2], [-1, -1, 0], [2, 0, 1], [1, 1, 0]])
    np.testing.assert_allclose(triangle_distances(tri, pts), [2, np.sqrt(2), np.sqrt(2), np.sqrt(0.5)])
    flat = np.array([[[0.0, 0, 0], [1, 0, 0], [2, 0, 0]]])  # degenerate: its edges
    np.testing.assert_allclose(triangle_distances(flat, np.array([[1.0, 1, 0]])), [1.0])


def test_mesh_contains_many_points_in_chunks():
    sphere = P.sphere(1).to_geometry(64).to_mesh()
    tri = np.asarray(sphere.vert_properties)[np.asarray(sphere.tri_verts)]
    pts = RNG.uniform(-1, 1, (3000, 3))
    r = np.linalg.norm(pts, axis=1)
    keep = np.abs(r - 1) > 0.01
    np.testing.assert_array_equal(mesh_contains(tri, pts[keep], 0.0), r[keep] < 1)
