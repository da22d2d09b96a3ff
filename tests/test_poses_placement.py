"""Placements (issue 11): every pose's transform rests the body on z = 0, and the placed
meshes `poses --export` writes read back with the same mass properties, placed."""

import json
import os

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st

from plumbob.bodies.primitives import box, cylinder, rectangle
from plumbob.bodies.solid import MeshSolid
from plumbob.cli import main
from plumbob.export.placed import export_poses
from plumbob.loading import read
from plumbob.stability import poses_from_points, resting_poses

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def shape(name: str) -> str:
    return os.path.join(ROOT, "shapes", name)


def random_body(seed, n=12):
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(n, 3)) * [1.0, 0.7, 0.45] + rng.normal(size=3) * 5
    return X, rng.dirichlet(np.full(n, 4.0)) @ X


def check_placement(pose, points, com, size):
    """The transform is rigid, rests the points on z = 0 on the named face, and puts the
    centre of mass on the z axis at the pose's height."""
    T = pose.transform
    assert T.shape == (4, 4) and np.array_equal(T[3], [0, 0, 0, 1])
    R = T[:3, :3]
    assert np.allclose(R.T @ R, np.eye(3), atol=1e-12) and np.linalg.det(R) == pytest.approx(1)
    pts3 = np.pad(points, ((0, 0), (0, 3 - points.shape[1])))
    placed = pts3 @ R.T + T[:3, 3]
    assert placed[:, 2].min() == pytest.approx(0.0, abs=1e-9 * size)
    face = np.pad(pose.face, ((0, 0), (0, 3 - pose.face.shape[1]))) @ R.T + T[:3, 3]
    assert np.allclose(face[:, 2], 0.0, atol=1e-6 * size)
    c = np.pad(com, (0, 3 - len(com))) @ R.T + T[:3, 3]
    assert np.allclose(c, [0, 0, pose.com_height], atol=1e-9 * size)
    # the down direction is the world's −z
    assert np.allclose(R @ np.pad(pose.down, (0, 3 - len(pose.down))), [0, 0, -1], atol=1e-12)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 100_000), st.integers(5, 30))
def test_every_transform_rests_the_body_on_its_face(seed, n):
    X, com = random_body(seed, n)
    ps = poses_from_points(X, com)
    size = float(np.linalg.norm(np.ptp(X, axis=0)))
    for pose in ps.poses:
        check_placement(pose, X, com, size)


def test_the_seed_block_and_a_rolling_cylinder_are_placed():
    block = box(1, 1, 4)
    for pose in resting_poses(block):
        check_placement(pose, block.hull_points(), block.mass_properties().center_of_mass, 4.3)
    side = resting_poses(cylinder(1.0, 2.0))[0]
    assert side.kind == "rolling"  # one representative placement: lying on its side
    assert side.transform[2, :3] @ [0, 0, 1] == pytest.approx(0.0, abs=1e-12)
    assert side.transform[2, 3] == pytest.approx(side.com_height)


def test_a_lamina_stands_upright_in_the_xz_plane():
    plate = rectangle(2.0, 1.0)
    props = plate.mass_properties()
    for pose in resting_poses(plate):
        check_placement(pose, plate.hull_points(), np.asarray(props.center_of_mass)[:2], 2.3)
        assert np.allclose(pose.transform[1, :3], [0, 0, -1])  # its plane: y = 0


def test_transform_is_in_the_json_row_major(capsys):
    assert main(["poses", shape("block.toml"), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    pose = data["poses"][0]
    T = np.array(pose["transform"])
    assert T.shape == (4, 4) and pose["kind"] == "face" and pose["axis"] is None
    com = np.array(data["center_of_mass"])
    assert np.allclose(T[:3, :3] @ com + T[:3, 3], [0, 0, pose["com_height"]])


# ------------------------------------------------------------------- --export
def invariants(props):
    """Mass, the centre, and the inertia's rotation invariants (trace, principal moments)."""
    moments = np.linalg.eigvalsh(np.asarray(props.inertia))
    return props.mass, np.asarray(props.center_of_mass), moments


@pytest.mark.parametrize("fmt", ["stl", "3mf"])
def test_exported_poses_read_back_placed_with_the_same_mass_properties(tmp_path, fmt):
    mesh = trimesh.creation.box((10.0, 20.0, 30.0))
    mesh.apply_transform(trimesh.transformations.euler_matrix(0.4, 0.9, -0.3))
    mesh.apply_translation([5.0, -7.0, 12.0])
    source = tmp_path / "part.stl"
    mesh.export(source)
    reading = read(str(source), units="mm")
    body = reading.body
    props = body.mass_properties()
    ps = resting_poses(body, props=props)
    paths = export_poses(body, ps.poses, str(tmp_path / "out"), fmt, "mm")
    assert [os.path.basename(p) for p in paths] == [
        f"pose-{k:02d}-p{p.probability:.4f}.{fmt}" for k, p in enumerate(ps.poses, 1)]
    assert not [f for f in os.listdir(tmp_path / "out") if f.startswith(".")]  # no leftovers
    mass, _, moments = invariants(props)
    for path, pose in zip(paths, ps.poses):
        placed = read(path, units="mm" if fmt == "stl" else None).body.mass_properties()
        m2, c2, moments2 = invariants(placed)
        assert m2 == pytest.approx(mass, rel=1e-6)
        assert np.allclose(moments2, moments, rtol=1e-5)
        assert np.allclose(c2, [0, 0, pose.com_height], atol=1e-6 * 0.04)
        assert read(path, units="mm" if fmt == "stl" else None).body.hull_points()[:, 2].min() \
            == pytest.approx(0.0, abs=1e-7)


def test_export_of_a_shape_without_triangles_uses_its_geometry(tmp_path):
    paths = export_poses(cylinder(0.1, 0.3), resting_poses(cylinder(0.1, 0.3)).poses,
                         str(tmp_path), "stl")
    assert len(paths) == 3
    body = read(paths[0]).body
    sagitta = 0.1 * (1 - np.cos(np.pi / 128))  # the 128-segment surface vs the true one
    assert body.hull_points()[:, 2].min() == pytest.approx(0.0, abs=sagitta)


def test_a_lamina_cannot_be_exported_as_a_mesh(tmp_path):
    from plumbob.errors import PlumbobError

    with pytest.raises(PlumbobError, match="cannot export"):
        export_poses(rectangle(1, 2), resting_poses(rectangle(1, 2)).poses, str(tmp_path))


# ---------------------------------------------------------------- the command
def test_top_and_min_probability_summarise_the_rest(capsys):
    assert main(["poses", shape("block.toml"), "--top", "2", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["poses"]) == 2 and data["more"]["poses"] == 4
    assert data["more"]["probability"] == pytest.approx(
        1 - sum(p["probability"] for p in data["poses"]), abs=1e-12)
    assert main(["poses", shape("block.toml"), "--min-probability", "0.2"]) == 0
    out = capsys.readouterr().out
    assert "2 more pose(s) with total probability" in out


def test_the_command_exports_the_shown_poses(tmp_path, capsys):
    mesh = trimesh.creation.cylinder(0.5, 2.0, sections=64)
    source = tmp_path / "cyl.stl"
    mesh.export(source)
    folder = tmp_path / "placed"
    assert main(["poses", str(source), "--top", "2", "--export", str(folder),
                 "--export-format", "3mf"]) == 0
    out = capsys.readouterr().out
    assert "rolls about (0, 0, 1)" in out and "3 stable pose(s)" in out
    names = sorted(os.listdir(folder))
    assert len(names) == 2 and names[0].startswith("pose-01-p0.89") and names[0].endswith(".3mf")


def test_roll_angle_zero_gives_every_facet(tmp_path, capsys):
    mesh = trimesh.creation.cylinder(0.5, 2.0, sections=64)
    source = tmp_path / "cyl.stl"
    mesh.export(source)
    assert main(["poses", str(source), "--roll-angle", "0", "--json"]) == 0
    assert len(json.loads(capsys.readouterr().out)["poses"]) == 66


def test_the_old_hull_tolerance_spelling_still_works(capsys):
    assert main(["poses", shape("stepped_cylinder.toml"), "--hull-tolerance", "0.001",
                 "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["poses"]


def test_the_mesh_pose_is_the_same_as_the_bodys():
    mesh = trimesh.creation.box((1.0, 2.0, 3.0))
    body = MeshSolid(np.asarray(mesh.triangles))
    reference = resting_poses(box(1, 2, 3))
    assert np.allclose(resting_poses(body).probabilities, reference.probabilities, atol=1e-12)


def test_the_commands_default_roll_angle_is_the_librarys():
    from plumbob.commands.poses import ROLL_ANGLE
    from plumbob.stability.poses.families import ROLL_ANGLE_DEG

    assert ROLL_ANGLE == ROLL_ANGLE_DEG
