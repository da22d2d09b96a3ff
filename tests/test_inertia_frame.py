"""The inertia tensor in another frame (``MassProperties.inertia_in``, ``plumbob mass
--frame``), about the centre of mass or any point: checked against closed forms (a box
about its corner, by the parallel-axis theorem, turned by R I Rᵀ), against the same body
turned and integrated again, and against the principal moments."""

from __future__ import annotations

import json
from fractions import Fraction as Q

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from plumbob.bodies.primitives import box
from plumbob.cli import main
from plumbob.errors import GeometryError
from plumbob.frames import frame_axes, rotation_matrix

A, B, C, RHO = 1.0, 2.0, 4.0, 500.0  # a box a × b × c, a corner at the origin
M = A * B * C * RHO


def _corner_tensor() -> np.ndarray:
    """The box about its corner, exact: I_xx = m (b² + c²) / 3, I_xy = −m a b / 4."""
    a, b, c, m = Q(1), Q(2), Q(4), Q(4000)
    t = [[m * (b * b + c * c) / 3, -m * a * b / 4, -m * a * c / 4],
         [-m * a * b / 4, m * (a * a + c * c) / 3, -m * b * c / 4],
         [-m * a * c / 4, -m * b * c / 4, m * (a * a + b * b) / 3]]
    return np.array([[float(v) for v in row] for row in t])


@pytest.fixture(scope="module")
def props():
    return box(A, B, C, density=RHO).mass_properties()


def test_about_the_corner_in_the_body_frame_is_the_closed_form(props):
    assert M == 4000
    assert np.allclose(props.inertia_in(np.eye(3), [0, 0, 0]), _corner_tensor(),
                       rtol=1e-12, atol=1e-12 * M)


def test_turned_45_degrees_about_z_it_is_r_i_r_transposed_in_closed_form(props):
    """x' = (1, 1, 0)/√2, y' = (−1, 1, 0)/√2: I_x'x' = (I_xx + 2 I_xy + I_yy) / 2,
    I_y'y' = (I_xx − 2 I_xy + I_yy) / 2, I_x'y' = (I_yy − I_xx) / 2, I_x'z = (I_xz + I_yz)/√2."""
    i = _corner_tensor()
    got = props.inertia_in(frame_axes(x=[1, 1, 0], y=[-1, 1, 0]), [0, 0, 0])
    want = np.array([
        [(i[0, 0] + 2 * i[0, 1] + i[1, 1]) / 2, (i[1, 1] - i[0, 0]) / 2,
         (i[0, 2] + i[1, 2]) / np.sqrt(2)],
        [(i[1, 1] - i[0, 0]) / 2, (i[0, 0] - 2 * i[0, 1] + i[1, 1]) / 2,
         (i[1, 2] - i[0, 2]) / np.sqrt(2)],
        [(i[0, 2] + i[1, 2]) / np.sqrt(2), (i[1, 2] - i[0, 2]) / np.sqrt(2), i[2, 2]]])
    assert np.allclose(got, want, rtol=1e-12, atol=1e-12 * M)


def test_the_principal_frame_about_the_centre_is_diagonal_with_the_principal_moments(props):
    diagonal = props.inertia_in("principal")
    assert np.allclose(diagonal, np.diag(props.principal_moments), atol=1e-12 * M)
    # the box about its centre: m (b² + c²)/12 …, ascending: a, b, c = 1, 2, 4
    assert np.allclose(np.sort(np.diag(diagonal)),
                       sorted([M * (B**2 + C**2) / 12, M * (A**2 + C**2) / 12,
                               M * (A**2 + B**2) / 12]), rtol=1e-12)


@settings(max_examples=15, deadline=None)
@given(st.floats(-3.0, 3.0), st.tuples(*[st.floats(-1.0, 1.0)] * 3),
       st.tuples(*[st.floats(-5.0, 5.0)] * 3))
def test_it_is_the_turned_body_integrated_again(props, angle, axis, point):
    """Independent path: turn the box by R (its points p → R p) and integrate it; its
    tensor about R q is R I_q Rᵀ, what inertia_in gives for the frame R about q."""
    if np.linalg.norm(axis) < 1e-3:
        return
    r = rotation_matrix(axis, angle)
    turned = box(A, B, C, density=RHO).transformed(r).mass_properties()
    want = turned.inertia_about(r @ np.asarray(point))
    assert np.allclose(props.inertia_in(r, point), want, rtol=1e-9, atol=1e-9 * np.abs(want).max())


def test_bad_frames_are_refused_by_name():
    with pytest.raises(GeometryError, match="right angles: x and y are 45° apart"):
        frame_axes(x=[1, 0, 0], y=[1, 1, 0])
    with pytest.raises(GeometryError, match="two of its axes"):
        frame_axes(x=[1, 0, 0])
    with pytest.raises(GeometryError, match="right-handed"):
        box(1, 1, 1).mass_properties().inertia_in(np.diag([1.0, 1.0, -1.0]))
    assert np.allclose(frame_axes(y=[0, 0, 2], z=[3, 0, 0]), [[0, 1, 0], [0, 0, 1], [1, 0, 0]])


def test_mass_frame_on_the_command_line(tmp_path, capsys, shapes_dir):
    """``--frame x=1,1,0 y=-1,1,0 --about 0,0,0`` on the seed's 1 × 1 × 4 block: the JSON
    is R I Rᵀ of the closed form about the corner; the text shows it; bad frames exit 2."""
    block = f"{shapes_dir}/block.toml"
    assert main(["mass", block, "--about", "0,0,0", "--frame", "x=1,1,0", "y=-1,1,0",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)["inertia_in_frame"]
    m = 4000.0
    corner = np.array([[m * 17 / 3, -m / 4, -m], [-m / 4, m * 17 / 3, -m], [-m, -m, m * 2 / 3]])
    r = np.array([[1, 1, 0], [-1, 1, 0], [0, 0, np.sqrt(2)]]) / np.sqrt(2)
    assert np.allclose(out["inertia"], r @ corner @ r.T, rtol=1e-12, atol=1e-9)
    assert np.allclose(out["axes"], r) and out["point"] == [0.0, 0.0, 0.0]
    assert main(["mass", block, "--frame", "principal"]) == 0
    text = capsys.readouterr().out
    assert "inertia (about centre, in principal axes)" in text
    for args in (["--frame", "x=1,0,0", "y=1,1,0"], ["--frame", "x=1,0,0"],
                 ["--frame", "principal", "x=1,0,0"]):
        assert main(["mass", block, *args]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "frame" in err
    with pytest.raises(SystemExit) as stop:  # PATH taken as a frame's word: said so
        main(["mass", "--frame", "x=1,1,0", "y=-1,1,0", block])
    assert stop.value.code == 2 and "give --frame after PATH" in capsys.readouterr().err
