"""Where a body set down on a point, a line or a sliver of contact comes to rest.

Each answer is checked against one worked out independently: closed forms for a
hemisphere (the centre of mass comes to lie straight below the centre of its dome) and
for a sphere-capped body with its centre of mass off the axis, the exact geometry of a
box or a finely faceted cylinder falling over an edge, and the rank the pose has in
:func:`resting_poses`.
"""

import json

import numpy as np
import pytest

from plumbob.bodies.csg import Assembly
from plumbob.bodies.primitives import box, cylinder, hemisphere, sphere
from plumbob.bodies.solid import MeshSolid
from plumbob.stability import check, resting_poses
from plumbob.stability.poses.settling import SETTLE_STANDS_DEG, settle
from plumbob.stability.support import contact_kind
from plumbob.tolerances import SLIVER

ANGLE = 1e-9  # degrees: the settling of exact geometry, to round-off of its angles


def _down(tilt_deg: float, z: float = -1.0) -> np.ndarray:
    """Down turned ``tilt_deg`` from ±z toward +x."""
    a = np.radians(tilt_deg)
    return np.array([np.sin(a), 0.0, z * np.cos(a)])


def _angle(a, b) -> float:
    a, b = np.asarray(a, float), np.asarray(b, float)
    return float(np.degrees(np.arctan2(np.linalg.norm(np.cross(a, b)), a @ b)))


@pytest.mark.parametrize("tilt", [0.5, 10.0, 40.0, 85.0])
def test_a_hemisphere_on_its_dome_rocks_back_upright(tilt):
    """Dome down (down = +z here: the flat face is at z = 0, the dome above), its centre of
    mass 3r/8 below the dome's centre: it rocks back to rest on the dome's pole, turning
    exactly the angle it was set down at — where the old verdict said it topples."""
    body = hemisphere(1.0)
    v = check(body, _down(tilt, z=1.0))
    s = v.settling
    assert s is not None and s.contact == "point"
    assert s.pose_kind == "rocking" and s.stays and s.exact and s.own_face
    assert s.angle_deg == pytest.approx(tilt, abs=1e-7)
    assert np.allclose(s.down, [0, 0, 1], atol=1e-9)
    assert v.verdict == "stands" and np.allclose(v.down, [0, 0, 1], atol=1e-9)
    # the pose it names is the rocking pose of resting_poses, by rank
    poses = resting_poses(body)
    assert poses[s.pose - 1].kind == "rocking"
    # the centre of mass falls from its height where set down to 5r/8 at rest
    a = np.radians(tilt)
    assert s.com_height == pytest.approx(1 - 3 / 8, rel=1e-12)
    assert s.drop == pytest.approx((1 - 3 / 8 * np.cos(a)) - 5 / 8, rel=1e-9, abs=1e-12)
    assert v.critical_tilt_deg == pytest.approx(poses[s.pose - 1].critical_tilt_deg)
    assert f"settles {tilt:.3g}° into pose {s.pose}" == s.phrase


def test_a_sphere_capped_body_settles_with_its_centre_straight_above_the_contact():
    """A hemisphere (radius 1, dome toward +z) with a box on its flat face off the axis:
    at rest the centre of mass lies on the line from the dome's centre to the contact,
    down = c / |c| (closed form from the parts' masses and centres)."""
    rho_h, rho_b = 1000.0, 300.0
    cap = hemisphere(1.0, density=rho_h)
    block = box(0.4, 0.4, 0.2, density=rho_b).translated([0.3, -0.2, -0.2])
    body = Assembly((cap, block))
    m_h, c_h = rho_h * 2 / 3 * np.pi, np.array([0.0, 0.0, 3 / 8])
    m_b, c_b = rho_b * 0.4 * 0.4 * 0.2, np.array([0.5, 0.0, -0.1])
    c = (m_h * c_h + m_b * c_b) / (m_h + m_b)
    assert np.allclose(body.mass_properties().center_of_mass, c, rtol=0, atol=1e-12)
    rest = c / np.linalg.norm(c)
    for start in ([0.0, 0.0, 1.0], [0.3, 0.4, 1.0], [-0.5, 0.1, 1.0]):
        v = check(body, start)
        s = v.settling
        assert s.contact == "point" and s.pose_kind == "rocking" and s.stays
        assert np.allclose(s.down, rest, rtol=0, atol=1e-9)
        assert s.angle_deg == pytest.approx(_angle(start, rest), abs=1e-7)
        assert v.verdict == "stands"


@pytest.mark.parametrize("tilt", [1.0, 10.0, 30.0, 60.0])
def test_a_hemisphere_on_its_rim_falls_back_onto_its_face(tilt):
    """Flat face down, tipped ``tilt`` onto its rim: it touches at one point of the rim,
    the old verdict said it topples "over by" atan(…); it falls back onto its flat face,
    turning exactly ``tilt``. There its critical tilt is atan(r / (3r/8))."""
    v = check(hemisphere(1.0), _down(tilt))
    s = v.settling
    assert s.contact == "point" and s.pose_kind == "face" and s.exact
    assert s.angle_deg == pytest.approx(tilt, abs=ANGLE)
    assert np.array_equal(s.down, [0.0, 0.0, -1.0])
    # the rim is sampled to within the contact tolerance (1e-6 of the size): the margin r
    # to within it, the tilt atan(r / h) to within h / (r² + h²) of that
    h, size = 3 / 8, hemisphere(1.0).size
    within = np.degrees(h / (1 + h * h) * 1e-6 * size)
    assert s.critical_tilt_deg == pytest.approx(np.degrees(np.arctan(8 / 3)), abs=within)
    assert s.stays == (tilt <= SETTLE_STANDS_DEG)
    if s.stays:
        assert v.verdict == "stands" and v.critical_tilt_deg == pytest.approx(
            s.critical_tilt_deg)
    else:  # the verdict where it was set down, and where it goes
        assert v.verdict == "topples" and np.allclose(v.down, _down(tilt))
        assert s.phrase.startswith(f"rolls {tilt:.3g}° onto pose {s.pose}, where it stands")


def _faceted_cylinder(sections: int = 256) -> MeshSolid:
    trimesh = pytest.importorskip("trimesh")
    return MeshSolid(trimesh.creation.cylinder(radius=1.0, height=2.0,
                                               sections=sections).triangles)


def test_a_finely_faceted_cylinder_on_its_rim():
    """A 256-sided prism (radius 1, height 2, centre at the origin) tipped onto its rim:
    10° falls back onto its end (exactly 10°, a polytope's face); 60° goes over onto its
    side, a face within half a facet (180°/256) of the smooth answer, 30°."""
    body = _faceted_cylinder()
    back = check(body, _down(10.0))
    assert back.settling.contact in ("point", "line")
    assert back.verdict == "stands" and back.settling.stays
    assert back.settling.angle_deg == pytest.approx(10.0, abs=ANGLE)
    assert np.allclose(back.down, [0, 0, -1], atol=1e-12)
    assert back.critical_tilt_deg == pytest.approx(45.0, abs=180 / 256)  # atan(1/1)
    over = check(body, _down(60.0))
    s = over.settling
    assert over.verdict == "topples" and not s.stays and s.exact
    assert s.pose_kind == "rolling"
    assert abs(s.angle_deg - 30.0) <= 180 / 256
    assert abs(s.down[2]) < 1e-12  # on its side
    assert resting_poses(body)[s.pose - 1].kind == "rolling"


def test_a_box_that_really_goes_over():
    """1 × 1 × 4 upright, tipped 30° onto an edge of its base (its critical tilt is
    atan(1/4) = 14.04°): it goes over onto its long side, turning exactly 60°; tipped 10°
    it falls back onto its end, turning 10°."""
    body = box(1, 1, 4)
    over = check(body, _down(30.0))
    assert over.support.kind == "segment" and over.settling.contact == "line"
    assert over.verdict == "topples" and not over.settling.stays
    assert over.settling.angle_deg == pytest.approx(60.0, abs=ANGLE)
    assert np.allclose(over.settling.down, [1, 0, 0], atol=1e-15)
    # lying on a 1 × 4 side, its centre 0.5 above it and 0.5 from the long edges: 45°
    assert over.settling.critical_tilt_deg == pytest.approx(45.0, rel=1e-12)
    assert over.summary == (f"topples (rolls 60° onto pose {over.settling.pose}, where it "
                            "stands, critical tilt 45°)")
    back = check(body, _down(10.0))
    assert back.verdict == "stands" and back.settling.angle_deg == pytest.approx(10, abs=ANGLE)
    assert back.critical_tilt_deg == pytest.approx(np.degrees(np.arctan(0.25)), rel=1e-12)
    assert np.allclose(back.settling.down_from, _down(10.0), atol=1e-15)


def test_a_ball_and_a_cylinder_on_its_side_roll_where_they_are():
    ball = check(sphere(1.0), [0.3, 0.2, -1.0])
    assert ball.verdict == "neutral" and ball.settling.pose_kind == "rolling"
    assert ball.settling.angle_deg == 0.0 and ball.settling.stays
    side = check(cylinder(1.0, 2.0), [1.0, 0.0, 0.0])
    assert side.verdict == "neutral" and side.settling.angle_deg == 0.0
    assert side.settling.contact == "line"
    # tipped 80° onto its rim, a cylinder (r = 1, h = 2) goes on over onto its side, 10°
    tipped = check(cylinder(1.0, 2.0), _down(80.0))
    assert tipped.settling.pose_kind == "rolling" and tipped.verdict == "neutral"
    assert tipped.settling.angle_deg == pytest.approx(10.0, abs=1e-9)
    assert not tipped.settling.exact  # a sampled side: near its facets


def test_a_faceted_bowl_settles_into_its_pose_not_onto_a_facet():
    """A scan-like bottom: a 20 480-triangle icosphere cut level at z = 0.3 (a weighted
    ball), turned 3° about x. Set down with −z it touches on one facet; it rocks into its
    rocking pose, the smooth answer (its axis down: 3°) within the facets' angular size,
    and its critical tilt is the rocker's from resting_poses, not a facet's hundredth of a
    degree."""
    trimesh = pytest.importorskip("trimesh")
    mesh = trimesh.creation.icosphere(subdivisions=5).slice_plane([0, 0, 0.3], [0, 0, -1],
                                                                  cap=True)
    mesh.apply_transform(trimesh.transformations.rotation_matrix(np.radians(3), [1, 0, 0]))
    body = MeshSolid(mesh.triangles)
    v = check(body)
    s = v.settling
    assert s.contact in ("point", "line", "sliver") and s.pose_kind == "rocking"
    assert v.verdict == "stands" and s.stays and s.own_face
    facet = np.degrees(mesh.face_adjacency_angles.max())
    assert abs(s.angle_deg - 3.0) <= 2 * facet
    pose = resting_poses(body)[s.pose - 1]
    assert np.array_equal(s.down, pose.down)
    assert v.critical_tilt_deg == pytest.approx(pose.critical_tilt_deg)
    assert v.critical_tilt_deg > 5.0


def test_slivers_and_what_is_not_one():
    """A plate standing on an edge narrower than SLIVER of its size touches on a sliver;
    it settles 0° into the pose it stands in and its verdict is the plain one."""
    thin = SLIVER / 4
    plate = box(1.0, thin, 1.0)
    v = check(plate)
    assert v.settling is not None and v.settling.contact == "sliver"
    assert v.settling.angle_deg == 0.0 and v.settling.stays and v.verdict == "stands"
    assert v.margin == pytest.approx(thin / 2, rel=1e-12)
    assert check(box(1.0, 4 * SLIVER, 1.0)).settling is None
    assert contact_kind(check(box(1, 1, 1)).support, box(1, 1, 1).size) is None


def test_settle_names_the_pose_resting_poses_ranks():
    body = box(1, 2, 3)
    poses = resting_poses(body)
    for k, pose in enumerate(poses):
        tipped = pose.down + 0.2 * np.cross(pose.down, [0.3, 0.5, 0.8])  # a few degrees off
        s, same = settle(body, tipped)
        assert len(same) == len(poses)
        assert s.pose == k + 1 and np.array_equal(s.down, pose.down)


def test_check_json_has_the_settling(tmp_path):
    from plumbob.cli import main

    spec = tmp_path / "dome.toml"
    spec.write_text('[shape]\nname = "dome"\nkind = "solid"\n'
                    '[[part]]\ntype = "hemisphere"\nradius = 1\n', encoding="utf-8")
    import contextlib
    import io

    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(["check", str(spec), "--down", "0.5,0,0.8660254037844386", "--json"]) == 0
    got = json.loads(out.getvalue())
    assert got["verdict"] == "stands" and np.allclose(got["down"], [0, 0, 1], atol=1e-9)
    settles = got["settles"]
    assert list(settles) == ["contact", "down_from", "down", "angle_deg", "pose", "pose_kind",
                             "verdict", "critical_tilt_deg", "com_height", "drop", "stays",
                             "exact", "own_face"]
    assert settles["angle_deg"] == pytest.approx(30.0, abs=1e-7)
    docs = open("docs/cli.md", encoding="utf-8").read()
    for key in settles:
        assert f"`{key}`" in docs, key
    text = io.StringIO()
    with contextlib.redirect_stdout(text):
        main(["check", str(spec), "--down", "0.5,0,0.8660254037844386"])
    assert "stands (settles 30° into pose 1)" in text.getvalue()


def test_the_picture_says_where_it_settles():
    pytest.importorskip("matplotlib")
    from plumbob.plot.check import plot_check

    v = check(hemisphere(1.0), _down(30.0, z=1.0))
    fig = plot_check(v, hemisphere(1.0))
    assert "stands (settles 30° into pose 1)" in fig._suptitle.get_text()
    over = check(box(1, 1, 4), _down(30.0))
    fig = plot_check(over, box(1, 1, 4))
    assert "topples (rolls 60° onto pose" in fig._suptitle.get_text()
