import numpy as np
import pytest
import trimesh
from conftest import rel
from hypothesis import given
from hypothesis import strategies as st

from plumbob.bodies import primitives as P
from plumbob.bodies.solid import MeshSolid
from plumbob.errors import GeometryError
from plumbob.integrals.mesh import mesh_field_moments, triangle_soup_moments


def icosphere(subdivisions=3, radius=1.0):
    return trimesh.creation.icosphere(subdivisions=subdivisions, radius=radius)


def irregular_mesh():
    box = trimesh.creation.box([1.0, 2.0, 0.7])
    cyl = trimesh.creation.cylinder(0.3, 2.0, sections=24)
    cyl.apply_transform(trimesh.transformations.rotation_matrix(0.6, [1, 0.3, 0]))
    cyl.apply_translation([0.4, 0.2, 0.1])
    return trimesh.boolean.union([box, cyl], engine="manifold")


@pytest.mark.parametrize("mesh", [icosphere(), irregular_mesh()], ids=["icosphere", "irregular"])
def test_agrees_with_trimesh_near_origin(mesh):
    assert mesh.is_watertight
    props = MeshSolid(mesh.triangles, density=1.0).mass_properties()
    assert props.volume == pytest.approx(mesh.volume, rel=1e-10)
    assert rel(props.center_of_mass, mesh.center_mass, scale=mesh.scale) < 1e-10
    assert rel(props.inertia, mesh.moment_inertia) < 1e-10


def test_far_from_origin_keeps_inertia_where_trimesh_does_not():
    mesh = icosphere(4)
    near = MeshSolid(mesh.triangles).mass_properties()
    far_mesh = mesh.copy()
    far_mesh.apply_translation([1e6, 1e6, 1e6])
    far = MeshSolid(far_mesh.triangles).mass_properties()
    assert rel(far.inertia, near.inertia) < 1e-9
    assert rel(far.center_of_mass - 1e6, near.center_of_mass, scale=1.0) < 1e-9
    # trimesh sums about the world origin and loses the tensor entirely out there.
    assert rel(far_mesh.moment_inertia, mesh.moment_inertia) > 1e-3


def test_refining_a_mesh_changes_nothing():
    mesh = irregular_mesh()
    coarse = MeshSolid(mesh.triangles).mass_properties()
    fine_mesh = mesh.subdivide().subdivide()
    fine = MeshSolid(fine_mesh.triangles).mass_properties()
    assert fine.volume == pytest.approx(coarse.volume, rel=1e-12)
    assert rel(fine.center_of_mass, coarse.center_of_mass, scale=mesh.scale) < 1e-12
    assert rel(fine.inertia, coarse.inertia) < 1e-12


def test_chunking_does_not_change_the_sum():
    tri = icosphere(3).triangles
    whole = triangle_soup_moments(tri, chunk=1 << 20)
    chunked = triangle_soup_moments(tri, origin=whole.origin, chunk=7)
    assert chunked.m0 == pytest.approx(whole.m0, rel=1e-13)
    assert rel(chunked.m2, whole.m2) < 1e-13


@pytest.mark.parametrize("chunk", [1, 7, 1 << 20])
def test_field_kernel_with_a_constant_density_is_the_uniform_kernel(chunk):
    """Both kernels walk the same chunk loop: ρ = 3 gives 3 × the uniform moments, the same
    volume and the same closure diagnostics, for any chunk size."""
    tri = irregular_mesh().triangles
    uniform = triangle_soup_moments(tri)
    field = mesh_field_moments(tri, lambda p: np.full(len(p), 3.0), uniform.origin, 0, chunk=chunk)
    assert field.exact and field.cells == len(tri)
    assert field.measure == pytest.approx(uniform.m0, rel=1e-13)
    assert field.mass == pytest.approx(3 * uniform.m0, rel=1e-13)
    assert rel(field.first, 3 * uniform.m1, scale=3 * uniform.m0) < 1e-13
    assert rel(field.second, 3 * uniform.m2) < 1e-13
    np.testing.assert_allclose(field.vector_area, uniform.vector_area, atol=1e-14 * uniform.area)
    assert field.surface_area == pytest.approx(uniform.area, rel=1e-13)
    assert field.evaluations == len(tri) * (8 + 3)  # degree-2 rule: 2³ points, and 3 corners


def test_field_kernel_chunking_and_float32_do_not_change_the_sums():
    tri = icosphere(3).triangles
    origin = np.array([0.1, -0.2, 0.05])
    density = lambda p: 2 + p[:, 0] * p[:, 1] - 0.5 * p[:, 2] ** 2  # noqa: E731
    whole = mesh_field_moments(tri, density, origin, 2, chunk=1 << 20)
    chunked = mesh_field_moments(tri, density, origin, 2, chunk=7)
    single = mesh_field_moments(tri.astype(np.float32), density, origin, 2)
    assert chunked.mass == pytest.approx(whole.mass, rel=1e-13)
    assert rel(chunked.second, whole.second) < 1e-13
    assert single.mass == pytest.approx(whole.mass, rel=1e-6)


def test_field_kernel_keeps_the_worst_invalid_samples():
    tri = icosphere(1).triangles
    r = mesh_field_moments(tri, lambda p: p[:, 2], np.zeros(3), 1)
    assert len(r.bad_values) and r.bad_values[0] == r.bad_values.min() < 0
    assert r.corner_values[0] == pytest.approx(-1.0)  # the south pole
    np.testing.assert_allclose(r.corner_points[0], [0, 0, -1], atol=1e-12)
    with pytest.raises(ValueError, match="one value per point"):
        mesh_field_moments(tri, lambda p: np.ones(2), np.zeros(3), 1)


def test_float32_input_is_accepted():
    tri = icosphere(2).triangles.astype(np.float32)
    props = MeshSolid(tri).mass_properties()
    assert props.volume == pytest.approx(icosphere(2).volume, rel=1e-6)


def test_void_as_inward_shell_subtracts():
    outer = icosphere(3, 2.0)
    inner = icosphere(3, 1.0)
    tri = np.concatenate([outer.triangles, inner.triangles[:, ::-1]])
    props = MeshSolid(tri).mass_properties()
    assert props.volume == pytest.approx(outer.volume - inner.volume, rel=1e-12)


def test_several_shells_add():
    a = trimesh.creation.box([1, 1, 1])
    b = trimesh.creation.box([1, 1, 1])
    b.apply_translation([5, 0, 0])
    props = MeshSolid(np.concatenate([a.triangles, b.triangles])).mass_properties()
    assert props.volume == pytest.approx(2.0, rel=1e-14)
    assert props.center_of_mass == pytest.approx([2.5, 0, 0])


def test_open_mesh_is_an_error_not_a_number():
    tri = trimesh.creation.box([1, 1, 1]).triangles[:-1]
    with pytest.raises(GeometryError, match="is open"):
        MeshSolid(tri).mass_properties()


def test_inside_out_mesh_is_an_error():
    tri = trimesh.creation.box([1, 1, 1]).triangles[:, ::-1]
    with pytest.raises(GeometryError, match="inside out"):
        MeshSolid(tri).mass_properties()


def test_tetrahedron_closed_form():
    p = np.array([[0.1, 0.2, 0.3], [2.0, 0.1, 0.4], [0.5, 1.7, 0.2], [0.6, 0.5, 1.9]])
    props = P.tetrahedron(*p).mass_properties()
    volume = abs(np.linalg.det(p[1:] - p[0])) / 6
    assert props.volume == pytest.approx(volume, rel=1e-13)
    assert rel(props.center_of_mass, p.mean(axis=0)) < 1e-13
    # Tonon (2004): ∫ r rᵀ over a tetrahedron about its centroid = V/20 Σ (pᵢ−c)(pᵢ−c)ᵀ.
    d = p - p.mean(axis=0)
    central = volume / 20 * d.T @ d
    expected = np.trace(central) * np.eye(3) - central
    assert rel(props.inertia, expected) < 1e-13


@given(st.integers(0, 2**32 - 1))
def test_splitting_a_body_sums_back(seed):
    """A box cut by a random plane: the two pieces' properties combine to the box's."""
    rng = np.random.default_rng(seed)
    box = trimesh.creation.box([1.0, 2.0, 3.0])
    normal = rng.normal(size=3)
    normal /= np.linalg.norm(normal)
    origin = rng.uniform(-0.3, 0.3, 3)
    a = box.slice_plane(origin, normal, cap=True)
    b = box.slice_plane(origin, -normal, cap=True)
    whole = MeshSolid(box.triangles).mass_properties()
    pieces = MeshSolid(a.triangles).mass_properties() + MeshSolid(b.triangles).mass_properties()
    assert pieces.volume == pytest.approx(whole.volume, rel=1e-10)
    assert rel(pieces.center_of_mass, whole.center_of_mass, scale=3.0) < 1e-10
    assert rel(pieces.inertia, whole.inertia) < 1e-9


@given(st.integers(0, 2**32 - 1))
def test_refining_random_triangles_changes_nothing(seed):
    """Split random triangles at random interior points (1 → 3): the solid is the same."""
    rng = np.random.default_rng(seed)
    tri = irregular_mesh().triangles
    chosen = rng.random(len(tri)) < 0.5
    a, b, c = (tri[chosen, i] for i in range(3))
    w = rng.dirichlet([1.0, 1.0, 1.0], size=chosen.sum())
    p = w[:, :1] * a + w[:, 1:2] * b + w[:, 2:] * c
    refined = np.concatenate([tri[~chosen], np.stack((a, b, p), 1), np.stack((b, c, p), 1),
                              np.stack((c, a, p), 1)])
    before = MeshSolid(tri).mass_properties()
    after = MeshSolid(refined).mass_properties()
    assert after.volume == pytest.approx(before.volume, rel=1e-12)
    assert rel(after.center_of_mass, before.center_of_mass, scale=2.0) < 1e-12
    assert rel(after.inertia, before.inertia) < 1e-11
