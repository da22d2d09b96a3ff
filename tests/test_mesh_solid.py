"""The solid check: winding, shells (voids, islands, overlaps), repair, big meshes."""

import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "bad_inputs"))
from make_bad_inputs import cube  # noqa: E402

from plumbob import mesh  # noqa: E402
from plumbob.bodies.solid import MeshSolid  # noqa: E402
from plumbob.errors import GeometryError  # noqa: E402


def check_solid(triangles, **options):
    """:func:`plumbob.mesh.check_solid`, with the body a reader would build from its result."""
    checked = mesh.check_solid(triangles, **options)
    return MeshSolid(checked.triangles, moments=checked.moments), checked.notices


def notices_with(notices, text):
    return [n for n in notices if text in n]


def test_hidden_winding_error_is_found_on_small_meshes():
    # Top and bottom faces turned: their vector areas cancel, so the cheap test passes.
    tri = cube().copy()
    z_faces = np.isclose(tri[:, :, 2], tri[:, :1, 2]).all(axis=1)
    tri[z_faces] = tri[z_faces][:, ::-1]
    body, notices = check_solid(tri)
    assert body.mass_properties().volume == pytest.approx(1.0, rel=1e-15)
    assert notices_with(notices, "4 of 12 triangles were wound against their neighbours")


def test_void_is_kept_and_not_called_an_overlap():
    hollow = np.concatenate((cube(size=2.0), cube(size=1.0, offset=(0.5, 0.5, 0.5))[:, ::-1]))
    body, notices = check_solid(hollow)
    assert body.mass_properties().volume == pytest.approx(7.0, rel=1e-15)
    assert notices == ()


def test_ball_in_a_void_in_a_ball():
    tri = np.concatenate((cube(size=3.0), cube(size=2.0, offset=(0.5,) * 3)[:, ::-1],
                          cube(size=1.0, offset=(1.0,) * 3)))
    body, notices = check_solid(tri)
    assert body.mass_properties().volume == pytest.approx(27 - 8 + 1, rel=1e-15)
    assert notices == ()


def test_hollow_cube_inside_out_is_turned_as_a_whole():
    hollow = np.concatenate((cube(size=2.0), cube(size=1.0, offset=(0.5, 0.5, 0.5))[:, ::-1]))
    body, notices = check_solid(hollow[:, ::-1])
    assert body.mass_properties().volume == pytest.approx(7.0, rel=1e-15)
    assert notices_with(notices, "inside out")


def test_one_of_two_separate_shells_inside_out():
    tri = np.concatenate((cube(), cube(offset=(3, 0, 0))[:, ::-1]))
    body, notices = check_solid(tri)
    assert body.mass_properties().volume == pytest.approx(2.0, rel=1e-15)
    assert notices_with(notices, "1 of 2 shells pointed inward")


def test_touching_shells_are_not_an_overlap():
    tri = np.concatenate((cube(), cube(offset=(1, 0, 0))))
    body, notices = check_solid(tri)
    assert body.mass_properties().volume == pytest.approx(2.0, rel=1e-15)
    assert not notices_with(notices, "overlap")


def test_nested_duplicate_shells_are_united():
    tri = np.concatenate((cube(size=2.0), cube(size=1.0, offset=(0.5, 0.5, 0.5))))
    body, notices = check_solid(tri)
    props = body.mass_properties()
    assert props.volume == pytest.approx(8.0, rel=1e-12)
    assert props.center_of_mass == pytest.approx([1.0, 1.0, 1.0], rel=1e-12)
    assert notices_with(notices, "2 shells overlap; united with manifold3d (volume 9 → 8 m³)")


def test_t_junctions_close_geometrically():
    # The top face is cut into three triangles at the midpoint of one of its edges; the
    # neighbouring side face keeps that edge whole.
    tri = cube()
    top = np.isclose(tri[:, :, 2], 1.0).all(axis=1)
    m = [0.5, 0.0, 1.0]
    fan = np.array([[[0, 0, 1], m, [0, 1, 1]], [m, [1, 1, 1], [0, 1, 1]],
                    [m, [1, 0, 1], [1, 1, 1]]], dtype=float)
    tri = np.concatenate((tri[~top], fan))
    body, notices = check_solid(tri)
    assert body.mass_properties().volume == pytest.approx(1.0, rel=1e-15)
    assert notices_with(notices, "edges end at T-junctions")


def test_mobius_strip_is_not_orientable():
    n = 12
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    centre = np.stack((np.cos(t), np.sin(t), np.zeros(n)), axis=1)
    half = 0.3 * np.stack((np.cos(t / 2) * np.cos(t), np.cos(t / 2) * np.sin(t), np.sin(t / 2)), 1)
    a, b = centre + half, centre - half
    nxt = np.roll(np.arange(n), -1)
    a1, b1 = a[nxt], b[nxt]
    a1[-1], b1[-1] = b[0], a[0]  # the half twist
    tri = np.concatenate((np.stack((a, b, a1), 1), np.stack((b, b1, a1), 1)))
    with pytest.raises(GeometryError, match="non-orientable"):
        check_solid(tri)


def test_big_meshes_take_the_cheap_path(monkeypatch):
    monkeypatch.setattr(mesh.solid, "FULL_CHECK_LIMIT", 0)
    body, notices = check_solid(cube(2)[:, ::-1].astype(np.float32))
    assert body.triangles.dtype == np.float32
    assert body.mass_properties().volume == pytest.approx(1.0, rel=1e-7)
    assert notices_with(notices, "inside out") and notices_with(notices, "not checked for overlap")
    with pytest.raises(GeometryError, match="3 boundary edges"):  # failing the cheap test
        check_solid(cube(2)[1:])


def test_repair_closes_a_non_planar_hole_and_reports_it():
    # An octahedron without one face: the hole is a triangle, closed by a fan.
    v = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float)
    faces = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    tri = v[np.array(faces)]
    fine = np.concatenate([_subdivide(t) for t in tri])  # 8 × 16 triangles
    body, notices = check_solid(fine[1:], repair=True)
    assert body.mass_properties().volume == pytest.approx(4 / 3, rel=1e-14)
    assert notices_with(notices, "repair: closed 1 hole (3 boundary edges)")


def _subdivide(t: np.ndarray, k: int = 4) -> np.ndarray:
    """A triangle cut into k² similar triangles (same orientation)."""
    out = []
    p = lambda i, j: t[0] + (t[1] - t[0]) * i / k + (t[2] - t[0]) * j / k  # noqa: E731
    for i in range(k):
        for j in range(k - i):
            out.append([p(i, j), p(i + 1, j), p(i, j + 1)])
            if i + j < k - 1:
                out.append([p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)])
    return np.array(out)


def _finned_ball(fins: int = 150):
    """A closed icosphere with ``fins`` one-sided triangles standing on edges that share no
    vertex: each fin opens a hole of two edges and makes its edge non-manifold (a scan's
    stray faces). Returns the triangles and the fins' edges (their two corners)."""
    import trimesh

    ball = trimesh.creation.icosphere(subdivisions=4)
    vertices, faces = np.asarray(ball.vertices), np.asarray(ball.faces)
    used: set[int] = set()
    chosen = []
    for k, face in enumerate(faces):  # test set-up: a greedy pick of separate faces
        if used.isdisjoint(face.tolist()):
            chosen.append(k)
            used.update(face.tolist())
        if len(chosen) == fins:
            break
    a, b, c = (vertices[faces[chosen, i]] for i in range(3))
    normal = np.cross(b - a, c - a)
    tips = (a + b) / 2 + 0.01 * normal / np.linalg.norm(normal, axis=1)[:, None]
    fin_tri = np.stack((a, b, tips), axis=1)
    return np.concatenate((vertices[faces], fin_tri)), np.stack((a, b), axis=1)


def test_repair_that_cannot_close_says_what_is_left_and_where():
    """Issue 20, item 7: --repair filled the fins' holes, then the body was refused with
    "... repair it or pass --repair". Now: what repair did, the 150 non-manifold edges,
    a point on one of them, and what would fix it."""
    tri, fin_edges = _finned_ball()
    with pytest.raises(GeometryError) as caught:
        mesh.check_solid(tri, repair=True)
    message = str(caught.value)
    assert "pass --repair" not in message
    assert "--repair closed 150 holes (300 boundary edges)" in message
    assert "150 edges are shared by more than two triangles" in message
    assert "mesh editor" in message
    near = np.array([float(v) for v in message.split("near (")[1].split(")")[0].split(",")])
    midpoints = fin_edges.mean(axis=1)
    # 6 significant digits of a point of size ~1
    assert np.min(np.linalg.norm(midpoints - near, axis=1)) < 1e-5


def test_the_command_with_repair_names_the_file_and_never_advises_repair(tmp_path):
    from hostile import assert_bad_input, run_limited
    from make_bad_inputs import binary_stl

    tri, _ = _finned_ball()
    path = tmp_path / "scan.stl"
    path.write_bytes(binary_stl(tri))
    line = assert_bad_input(run_limited("mass", path, "--repair"), "scan.stl",
                            "150 edges are shared by more than two triangles")
    assert "pass --repair" not in line
    # without --repair, passing it is the right advice (it closes the holes)
    assert_bad_input(run_limited("mass", path), "scan.stl", "pass --repair")
