"""Numbers out of double precision's range (issue 20, item 6): radii of 1e200–1e300,
densities of 1e308, positions at 1e300, a sampling tolerance of 1e-300, a GLB placed by a
huge matrix, NaN in WKT, an OBJ face index of 1e23, a simulation asked for rtol 1e-300.

Each is refused at its root, naming the file and the place, in one line with exit status
2 (or, where the input is legitimate, answered) — and no numpy or scipy warning text ever
reaches standard error: the CLI turns a ``RuntimeWarning`` that escapes the library into
the one line (:func:`plumbob.cli._warnings_caught`).
"""

from __future__ import annotations

import os
import warnings

import numpy as np
import pytest
from hostile import assert_bad_input, run_in_process, run_limited

import plumbob
from plumbob.bodies import primitives as P
from plumbob.errors import PlumbobError

SOLID = '[shape]\nkind = "solid"\n{shape}\n[[part]]\n{part}\n'
BOX = 'type = "box"\nwidth = {w}\nlength = 1\nheight = 1'


def _spec(tmp_path, text: str, name: str = "s.toml") -> str:
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def _no_warning_text(outcome) -> None:
    assert "Warning" not in outcome.stderr and "warn" not in outcome.stderr, outcome.stderr


SPEC_CASES = {
    "sphere of radius 1e200": (SOLID.format(shape="", part='type = "sphere"\nradius = 1e200'),
                               ["part 1.radius", "1e+200 m", "largest length"]),
    "sphere of radius 1e300": (SOLID.format(shape="", part='type = "sphere"\nradius = 1e300'),
                               ["part 1.radius", "1e+300 m", "largest length"]),
    "a box at 1e300": (SOLID.format(shape="", part=BOX.format(w=1) + "\nat = [1e300, 0, 0]"),
                       ["part 1.at[1]", "largest length"]),
    "particles at ±1e300": ('[shape]\nkind = "particles"\n[[particle]]\nmass = 1\n'
                            'position = [1e300, 0, 0]\n[[particle]]\nmass = 1\n'
                            'position = [-1e300, 0, 1]\n',
                            ["particle 1.position[1]", "largest length"]),
    "a box of density 1e308": (SOLID.format(shape="density = 1e308", part=BOX.format(w=3)),
                               ["s.toml", "double precision"]),
}


@pytest.mark.parametrize("command", ["mass", "check"])
@pytest.mark.parametrize("case", list(SPEC_CASES))
def test_numbers_beyond_double_precision_end_in_one_line(tmp_path, capsys, case, command):
    text, phrases = SPEC_CASES[case]
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a warning escaping the command fails the test
        outcome = run_in_process(capsys, command, _spec(tmp_path, text))
    assert_bad_input(outcome, *phrases)
    _no_warning_text(outcome)


def test_a_huge_radius_leaves_stderr_clean_in_a_real_process(tmp_path):
    """The same, end to end: what a user's terminal shows."""
    text = SPEC_CASES["sphere of radius 1e200"][0]
    outcome = run_limited("check", _spec(tmp_path, text))
    assert_bad_input(outcome, "part 1.radius", "largest length")
    _no_warning_text(outcome)


def test_the_library_refuses_a_huge_primitive_by_its_size():
    """Not "the profile has no area to revolve" (what the overflow gave before)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for make in (lambda: P.sphere(1e200), lambda: P.box(1e300, 1, 1),
                     lambda: P.cylinder(1, 1e51)):
            with pytest.raises(PlumbobError, match="largest length"):
                make()
    assert P.sphere(1e50).mass_properties().volume == pytest.approx(4 / 3 * np.pi * 1e150,
                                                                    rel=1e-12)


def test_a_sampling_tolerance_of_1e_300_is_answered_without_a_warning(capsys, shapes_dir):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        outcome = run_in_process(capsys, "poses", os.path.join(shapes_dir, "stepped_cylinder.toml"),
                                 "--hull-tolerance", "1e-300")
    assert outcome.status == 0, outcome.stderr
    # plumbob's own notes only (what it assumed), never numpy's division by zero
    assert all(line.startswith("plumbob: note: ") for line in outcome.lines), outcome.stderr
    _no_warning_text(outcome)


def test_a_glb_placed_by_a_huge_matrix_is_refused_by_its_coordinates(tmp_path, capsys):
    import trimesh

    scene = trimesh.Scene()
    matrix = np.eye(4)
    matrix[:3, :3] *= 1e300
    scene.add_geometry(trimesh.creation.box(), transform=matrix)
    path = tmp_path / "huge.glb"
    scene.export(path)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        outcome = run_in_process(capsys, "mass", path)
    assert_bad_input(outcome, "huge.glb", "coordinates reach", "--units")


@pytest.mark.parametrize("wkt", ["POLYGON ((0 0, 1 0, NaN 1, 0 0))",
                                 "POLYGON ((0 0, 1 0, 1 NaN, 0 1, 0 0))"])
def test_nan_in_wkt_names_the_point(tmp_path, capsys, wkt):
    """GEOS raised its own exception on NaN (exit 3), or numpy warned."""
    path = tmp_path / "nan.wkt"
    path.write_text(wkt)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        outcome = run_in_process(capsys, "mass", path)
    assert_bad_input(outcome, "nan.wkt", "point 3", "not a finite number")


@pytest.mark.parametrize("index, shown", [("99999999999999999999999", "1e+23"),
                                          ("-99999999999999999999", "-1e+20")])
def test_an_obj_face_index_beyond_int64_names_its_line(tmp_path, capsys, index, shown):
    """The index was cast to int64 before it was checked (an invalid-cast warning)."""
    path = tmp_path / "huge.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n"
                    f"f 2 3 {index}\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        outcome = run_in_process(capsys, "mass", path)
    assert_bad_input(outcome, "huge.obj", "line 8", f"face index {shown}", "refers to no vertex")


def test_a_simulation_tolerance_below_double_precision_is_refused(tmp_path, capsys):
    """scipy raised rtol 1e-300 to 100 ulps with a warning, then overflowed."""
    path = _spec(tmp_path, 'kind = "simulation"\ngravity = [0.0, -9.81]\n[solver]\n'
                 'rtol = 1e-300\n[[particle]]\nname = "A"\nmass = 1\nposition = [0, 0]\n'
                 '[[particle]]\nname = "B"\nmass = 1\nposition = [1, 0]\n'
                 '[[rod]]\nbetween = ["A", "B"]\nlength = 1\n', "sim.toml")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        outcome = run_in_process(capsys, "simulate", path, "--until", "1")
    assert_bad_input(outcome, "sim.toml", "solver.rtol", "1e-300", "1e-13")


def test_a_warning_that_escapes_a_command_becomes_the_one_line(capsys, monkeypatch, shapes_dir):
    """The CLI's net: whatever numpy warns about, the user sees one line naming the file,
    exit status 2, and no warning text."""
    import plumbob.commands.mass as mass

    def overflowing(args):
        return int(np.float64(1e308) * 10 > 0)  # numpy: overflow encountered in scalar multiply

    monkeypatch.setattr(mass, "run", overflowing)
    outcome = run_in_process(capsys, "mass", os.path.join(shapes_dir, "block.toml"))
    assert_bad_input(outcome, "block.toml", "double precision", "overflow encountered")


def test_load_of_a_huge_spec_raises_a_plumbob_error_without_warnings(tmp_path):
    text = SPEC_CASES["sphere of radius 1e300"][0]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(PlumbobError, match="largest length"):
            plumbob.load(_spec(tmp_path, text))


def test_a_batch_row_fails_an_overflow_without_a_warning(tmp_path):
    """A batch worker measures each file as the command does: the overflow fails the row
    ("failed", with the reason) and no warning text reaches the worker's stderr."""
    from plumbob.batch.options import Options
    from plumbob.batch.rows import process_file

    path = _spec(tmp_path, SPEC_CASES["a box of density 1e308"][0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        row = process_file(path, Options()).row
    assert row["status"] == "failed", row
    assert "double precision" in row["reason"] and "overflow" in row["reason"]
