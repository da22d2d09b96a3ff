"""A STEP solid whose faces cross one another is refused in one line naming the file
(exit 2), in bounded time: OpenCASCADE's Boolean self-interference check, run in the
child for parts of up to step_worker.SELF_CHECK_FACES faces, and said when left out."""

from __future__ import annotations

import time

import pytest
import step_models as M

pytest.importorskip("OCP", reason="the plumbob[cad] extra (cadquery-ocp-novtk)")

from plumbob.cli import main  # noqa: E402
from plumbob.formats import step as S  # noqa: E402
from plumbob.formats import step_worker  # noqa: E402


@pytest.fixture(scope="module")
def pierced(tmp_path_factory):
    return M.write_shape(M.pierced_cube(), tmp_path_factory.mktemp("si") / "pierced.step")


def test_the_pierced_cube_passes_every_check_but_the_self_intersection_one():
    # what makes the test genuine: the topology check and the volume let it through
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    shape = M.pierced_cube()
    assert BRepCheck_Analyzer(shape).IsValid()
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props, 1e-12, True)
    assert props.Mass() == pytest.approx(600.0, rel=1e-9)
    assert step_worker._solid_defect(shape) is None
    assert step_worker._crosses_itself(shape) is True


def test_a_self_intersecting_solid_is_refused_by_the_child(pierced):
    start = time.perf_counter()
    result = step_worker.read(pierced, S.DEVIATION)  # the child's verdict, here
    assert "self-intersecting solid: its faces cross one another" in result.get("defect", "")
    assert time.perf_counter() - start < 2.0


def test_the_refusal_is_one_line_naming_the_file(pierced, capsys):
    assert main(["mass", pierced]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and pierced in err and "self-intersecting solid" in err


def test_a_valid_solid_with_holes_is_not_taken_for_one(tmp_path):
    shape = M.box_with_holes(90.0, 50.0, 12.0, 4.0, [(20.0, 15.0), (60.0, 40.0)])
    assert step_worker._crosses_itself(shape) is False
    assert step_worker._crosses_itself(M.torus(40.0, 7.5)) is False


def test_a_part_with_too_many_faces_is_not_checked_and_that_is_said(tmp_path, monkeypatch):
    monkeypatch.setattr(step_worker, "SELF_CHECK_FACES", 2)  # a cylinder has 3 faces
    path = M.write_shape(M.cylinder(10.0, 30.0), tmp_path / "cylinder.step")
    result = step_worker.read(path, S.DEVIATION)
    assert result["parts"][0]["self_checked"] is False
    reading = S._reading(path, result["parts"], 1e-3, (), "mm")
    assert any("not checked for faces crossing each other" in n for n in reading.notices)
    monkeypatch.setattr(step_worker, "SELF_CHECK_FACES", 500)
    reading = S._reading(path, step_worker.read(path, S.DEVIATION)["parts"], 1e-3, (), "mm")
    assert not any("not checked" in n for n in reading.notices)
