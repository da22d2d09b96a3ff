"""Inertial blocks read back by the simulators' own parsers (MuJoCo, yourdfpy) give the
mass, centre and inertia plumbob computed, to 1e-9."""

import io
import os
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from conftest import SHAPES

from plumbob.cli import main
from plumbob.export.inertial import inertial_xml

TOL = 1e-9

# An irregular tetrahedron away from the origin: every product of inertia is non-zero.
TETRA = np.array([[0.3, -0.2, 0.5], [1.4, 0.1, 0.7], [0.6, 1.1, 0.4], [0.5, 0.3, 1.9]])


def _write_stl(path, vertices, faces):
    lines = ["solid t"]
    for f in faces:
        lines.append("facet normal 0 0 0\nouter loop")
        lines += [f"vertex {x!r} {y!r} {z!r}" for x, y, z in vertices[f].tolist()]
        lines.append("endloop\nendfacet")
    lines.append("endsolid t")
    path.write_text("\n".join(lines))


@pytest.fixture
def tetra_stl(tmp_path):
    faces = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])
    path = tmp_path / "tetra.stl"
    _write_stl(path, TETRA, faces)
    return str(path)


def _cli(capsys, *args):
    assert main(["mass", *args]) == 0
    return capsys.readouterr().out


def _expected(path):
    import plumbob

    return plumbob.load(path, units="m").with_default_density(2700.0).mass_properties()


def _close(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return float(np.max(np.abs(a - b))) <= TOL * max(1.0, float(np.max(np.abs(b))))


def test_mjcf_read_back_by_mujoco(capsys, tetra_stl):
    mujoco = pytest.importorskip("mujoco", reason="mujoco is in the [test] extra")
    props = _expected(tetra_stl)
    block = _cli(capsys, tetra_stl, "--units", "m", "--density", "2700", "--format", "mjcf")
    xml = f"<mujoco><worldbody><body name='part'>{block}</body></worldbody></mujoco>"
    model = mujoco.MjModel.from_xml_string(xml)
    b = model.body("part").id
    rot = np.zeros(9)
    mujoco.mju_quat2Mat(rot, model.body_iquat[b])
    rot = rot.reshape(3, 3)
    inertia = rot @ np.diag(model.body_inertia[b]) @ rot.T  # MuJoCo keeps principal axes
    assert abs(model.body_mass[b] - props.mass) <= TOL * props.mass
    assert _close(model.body_ipos[b], props.center_of_mass)
    assert _close(inertia / props.mass, props.inertia / props.mass)
    assert np.abs(props.inertia - np.diag(np.diag(props.inertia))).max() > 1e-3 * props.mass


def test_urdf_read_back_by_yourdfpy(capsys, tetra_stl):
    yourdfpy = pytest.importorskip("yourdfpy", reason="yourdfpy is in the [test] extra")
    props = _expected(tetra_stl)
    block = _cli(capsys, tetra_stl, "--units", "m", "--density", "2700", "--format", "urdf")
    urdf = f'<robot name="r"><link name="part">{block}</link></robot>'
    robot = yourdfpy.URDF.load(io.StringIO(urdf), load_meshes=False, build_scene_graph=False)
    inertial = robot.link_map["part"].inertial
    assert abs(inertial.mass - props.mass) <= TOL * props.mass
    assert np.allclose(inertial.origin[:3, :3], np.eye(3), rtol=0, atol=0)
    assert _close(inertial.origin[:3, 3], props.center_of_mass)
    assert _close(inertial.inertia, props.inertia)


def test_sdf_numbers(tetra_stl):
    props = _expected(tetra_stl)
    root = ET.fromstring(inertial_xml(props, "sdf"))
    pose = [float(v) for v in root.find("pose").text.split()]
    assert pose[3:] == [0, 0, 0] and _close(pose[:3], props.center_of_mass)
    assert float(root.find("mass").text) == props.mass
    t = {e.tag: float(e.text) for e in root.find("inertia")}
    tensor = [[t["ixx"], t["ixy"], t["ixz"]], [t["ixy"], t["iyy"], t["iyz"]],
              [t["ixz"], t["iyz"], t["izz"]]]
    assert np.array_equal(tensor, props.inertia)


def test_lamina_block_lies_in_z0():
    import plumbob

    props = plumbob.load(os.path.join(SHAPES, "l_shape.toml")).mass_properties()
    root = ET.fromstring(inertial_xml(props, "urdf"))
    xyz = [float(v) for v in root.find("origin").get("xyz").split()]
    assert xyz[2] == 0 and _close(xyz[:2], props.center_of_mass)


def test_unknown_format_is_refused():
    import plumbob

    props = plumbob.load(os.path.join(SHAPES, "block.toml")).mass_properties()
    with pytest.raises(ValueError, match="urdf, sdf, mjcf"):
        inertial_xml(props, "usd")


def test_the_batch_and_mass_commands_offer_every_format():
    from plumbob.batch.options import INERTIAL_FORMATS
    from plumbob.cli import build_parser
    from plumbob.export.inertial import FORMATS

    assert INERTIAL_FORMATS == FORMATS
    mass = build_parser("mass")._subparsers._group_actions[0].choices["mass"]
    (action,) = [a for a in mass._actions if a.dest == "format"]
    assert tuple(action.choices) == FORMATS
