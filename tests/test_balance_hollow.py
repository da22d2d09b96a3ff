"""Hollowing so that it stands: the leaning figurine of issue 14, checked on the written
files by plumbob's own ``check`` and independently by trimesh (closure, walls, mass)."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

from plumbob.balance.cells import grid_cells
from plumbob.balance.hollow import hollow, write_hollow
from plumbob.bodies.csg import union
from plumbob.bodies.primitives import box, cylinder, sphere
from plumbob.bodies.solid import MeshSolid
from plumbob.errors import GeometryError, StabilityError
from plumbob.formats.writers import stl_bytes
from plumbob.massprops import rotation_matrix

MM = 1e-3
RHO = 1200.0  # kg/m³, a resin


class Below:
    """A target with one row: the centre of mass at most ``height`` m up."""

    def __init__(self, height: float):
        self.height = height

    def slack(self, points):
        return self.height - np.asarray(points, dtype=float).T[2:3]


def figurine(segments: int = 64):
    """A leaning figurine, mm: a 36 × 36 × 12 plinth, a body (r 9, 55 long) leaning 58°
    from its foot 6 mm off centre, and a head (r 11), its curves in ``segments`` chords a
    turn (3.6k triangles at 64). As a solid it topples."""
    plinth = box(36 * MM, 36 * MM, 12 * MM).translated([-18 * MM, -18 * MM, 0])
    lean = rotation_matrix([0, 1, 0], np.radians(58))
    foot = np.array([6 * MM, 0, 8 * MM])
    body = cylinder(9 * MM, 55 * MM).transformed(lean, foot)
    head = sphere(11 * MM).translated(lean @ np.array([0, 0, 55 * MM]) + foot)
    return union(plinth, body, head, segments=segments)


def _cli_json(capsys, *argv):
    from plumbob.cli import main

    assert main(list(argv)) in (0, None)
    return json.loads(capsys.readouterr().out)


@pytest.fixture(scope="module")
def carved_files(tmp_path_factory):
    """Issue 14's acceptance as a user types it, once for the module: the figurine written
    as an STL in mm, then `plumbob balance --wall 2mm --margin 3mm --out carved.stl
    --void void.stl`. Returns (source, carved, void, the report printed)."""
    import contextlib
    import io

    from plumbob.cli import main

    folder = tmp_path_factory.mktemp("figurine")
    source = folder / "figurine.stl"
    source.write_bytes(stl_bytes(figurine().shape.triangles, "figurine", MM))
    carved, void = folder / "carved.stl", folder / "void.stl"
    report = io.StringIO()
    with contextlib.redirect_stdout(report):
        status = main(["balance", str(source), "--units", "mm", "--density", str(RHO),
                       "--wall", "2mm", "--margin", "3mm", "--out", str(carved),
                       "--void", str(void)])
    assert status == 0
    return source, carved, void, report.getvalue()


@pytest.fixture(scope="module")
def cube_plan():
    """A 1 m cube of 1000 kg/m³, 0.1 m walls, its centre lowered to 0.45 m, 0.2 m cells."""
    return hollow(box(1, 1, 1, density=1000.0), wall=0.1, target=Below(0.45), cell_size=0.2)


def test_the_figurine_topples_as_given(carved_files, capsys):
    source = carved_files[0]
    out = _cli_json(capsys, "check", str(source), "--units", "mm", "--density", str(RHO), "--json")
    assert out["verdict"] == "topples"


def test_the_carved_figurine_stands_with_the_margin(carved_files, capsys):
    source, carved, _, report = carved_files
    out = _cli_json(capsys, "check", str(carved), "--units", "mm", "--density", str(RHO), "--json")
    assert out["verdict"] == "stands"
    assert out["margin"] >= 3 * MM
    solid = _cli_json(capsys, "mass", str(source), "--units", "mm", "--density", str(RHO),
                      "--json")
    assert out["mass"] < solid["mass"]
    # the report's numbers are the written file's (to the report's 6 digits)
    after = next(line for line in report.splitlines() if line.startswith("after (written)"))
    mass = re.search(r"mass ([0-9.e+-]+) (g|kg)\b", after)
    margin = re.search(r"margin ([0-9.e+-]+) (mm|m)\b", after)
    assert mass and margin, after
    unit = {"g": 1e-3, "kg": 1.0, "mm": MM, "m": 1.0}
    assert float(mass.group(1)) * unit[mass.group(2)] == pytest.approx(out["mass"], rel=1e-5)
    assert float(margin.group(1)) * unit[margin.group(2)] == pytest.approx(out["margin"],
                                                                           rel=1e-5)


def test_the_carved_and_void_meshes_are_closed(carved_files):
    import trimesh

    _, carved, void, _ = carved_files
    for path in (carved, void):
        mesh = trimesh.load(str(path))
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.is_volume


def test_walls_are_at_least_2mm_everywhere(carved_files):
    """Independently: points spread over the void's surface (and its corners), their
    distances to the figurine's outer surface by trimesh, and all inside it."""
    import trimesh

    source, _, void, _ = carved_files
    outer = trimesh.load(str(source))
    hole = trimesh.load(str(void))
    points, _ = trimesh.sample.sample_surface(hole, 1500, seed=7)
    points = np.concatenate((points, hole.vertices[:: max(1, len(hole.vertices) // 500)]))
    _, distance, _ = trimesh.proximity.closest_point(outer, points)
    assert outer.contains(points).all()
    assert distance.min() >= 2.0 - 1e-4  # mm; float32 corners


def test_mass_properties_agree_with_trimesh(carved_files, capsys):
    import trimesh

    _, carved, _, _ = carved_files
    out = _cli_json(capsys, "mass", str(carved), "--units", "mm", "--density", str(RHO), "--json")
    mesh = trimesh.load(str(carved))
    mesh.apply_scale(MM)
    mesh.density = RHO
    assert out["mass"] == pytest.approx(mesh.mass, rel=1e-9)
    assert np.allclose(out["center_of_mass"], mesh.center_mass, rtol=0, atol=1e-12)
    assert np.allclose(out["inertia"], mesh.moment_inertia, rtol=1e-7, atol=1e-15)


# ---------------------------------------------------------------- the plan itself
def test_least_and_lightest(cube_plan):
    cube = box(1, 1, 1, density=1000.0)
    least = cube_plan
    most = hollow(cube, wall=0.1, target=Below(0.45), cell_size=0.2, lightest=True)
    assert least.target_met and most.target_met
    assert most.removed_mass > least.removed_mass
    # the least removal is bounded below by taking mass from the interior's very top:
    # (500 − 0.9 m) / (1000 − m) ≤ 0.45  ⇒  m ≥ 50 / 0.45
    assert least.removed_mass >= 50 / 0.45
    for plan in (least, most):
        assert plan.after.center_of_mass[2] <= 0.45
        assert plan.after.mass == pytest.approx(1000 - plan.removed_mass, rel=1e-12)


def test_nothing_to_carve_when_the_target_is_met():
    plan = hollow(box(1, 1, 1, density=1000.0), wall=0.1, target=Below(0.6), cell_size=0.2)
    assert plan.void is None and plan.cut is None and plan.target_met
    assert plan.after.mass == pytest.approx(1000.0)


def test_an_unreachable_target_says_what_to_do_and_states_the_bound():
    """Below(0.2) on a 1 m cube with 0.1 m walls: the lowest centre any carve reaches, by
    emptying the interior above a height z (a closed form, minimised by scipy), is what
    the message quotes, as the least slack 0.2 − that height."""
    from scipy.optimize import minimize_scalar

    def height(z):  # the centre's height with the interior above z emptied (kg, m)
        return (500 - 320 * (0.81 - z * z)) / (1000 - 640 * (0.9 - z))

    lowest = minimize_scalar(height, bounds=(0.1, 0.9), method="bounded",
                             options={"xatol": 1e-10}).fun
    with pytest.raises(StabilityError, match="thinner walls") as error:
        hollow(box(1, 1, 1, density=1000.0), wall=0.1, target=Below(0.2), cell_size=0.2)
    found = re.search(r"reaches is a least slack of (-?[0-9.]+) mm", str(error.value))
    assert found, str(error.value)
    assert float(found.group(1)) * 1e-3 == pytest.approx(0.2 - lowest, rel=1e-3)


def test_a_wall_too_thick_for_the_body():
    with pytest.raises(GeometryError, match="thinner --wall"):
        hollow(box(1, 1, 1), wall=0.6, target=Below(0.45))


def test_write_takes_stl_or_3mf(tmp_path, cube_plan):
    plan = cube_plan
    with pytest.raises(GeometryError, match="STL or 3MF"):
        write_hollow(plan, str(tmp_path / "carved.obj"))
    assert not (tmp_path / "carved.obj").exists()
    written = write_hollow(plan, str(tmp_path / "carved.3mf"), void=str(tmp_path / "void.3mf"))
    assert (tmp_path / "void.3mf").exists()
    # a 3MF states its unit: read back at the same size and mass
    assert written.mass_properties.mass == pytest.approx(plan.after.mass, rel=1e-6)
    assert np.allclose(written.mass_properties.center_of_mass, plan.after.center_of_mass, atol=1e-6)
    assert written.verdict.stands


def test_cells_tile_the_interior():
    import manifold3d

    interior = manifold3d.Manifold.sphere(1.0, 64)
    cells = grid_cells(interior, 0.3)
    assert cells.volumes.sum() == pytest.approx(interior.volume(), rel=1e-9)
    centre = (cells.volumes[:, None] * cells.centres).sum(axis=0) / cells.volumes.sum()
    assert np.allclose(centre, 0.0, atol=1e-9)
    assert len({tuple(i) for i in cells.index.tolist()}) == len(cells)


def test_the_acceptance_runs_from_the_command_line(carved_files):
    """Issue 14's acceptance as a user types it (the module's fixture): `plumbob balance
    --wall 2mm --margin 3mm --out carved.stl` reports the hollowing and what it wrote, and
    `plumbob check carved.stl --margin 3mm` passes."""
    from plumbob.cli import main

    _, carved, void, report = carved_files
    assert "hollowing" in report and str(carved) in report
    assert main(["check", str(carved), "--units", "mm", "--margin", "3mm"]) == 0
    assert void.stat().st_size > 0


def test_the_written_body_has_the_original_density_so_no_note_assumes_one(tmp_path,
                                                                          cube_plan):
    from plumbob.bodies.base import DEFAULT_DENSITY_NOTE

    plan = cube_plan
    written = write_hollow(plan, str(tmp_path / "carved.stl"))
    assert DEFAULT_DENSITY_NOTE not in written.mass_properties.notes
    assert written.mass_properties.mass == pytest.approx(plan.after.mass, rel=1e-6)


def test_unsettled_corners_fall_back_to_a_deeper_level_set_that_keeps_the_wall(monkeypatch):
    """Should the interior's corners not settle on the exact offset, the level set is taken
    deeper by what its grid can hide (2 steps): checked independently, no point sampled on
    the interior's surface (or a corner of it) is nearer the figurine's surface than the
    wall (trimesh's closest points), and all lie inside it."""
    import trimesh

    from plumbob.balance import interior as module
    from plumbob.bodies.offset import manifold_triangles

    triangles = figurine(48).shape.triangles
    monkeypatch.setattr(module, "_projected", lambda *args: None)
    offset, inner, _ = module.carving_interior(MeshSolid(triangles, RHO), 2 * MM, None, 0.1)
    assert "deeper" in offset.method and offset.surface_error == 2 * offset.step
    outer = trimesh.Trimesh(**trimesh.triangles.to_kwargs(triangles))
    hole = trimesh.Trimesh(**trimesh.triangles.to_kwargs(manifold_triangles(inner)))
    points, _ = trimesh.sample.sample_surface(hole, 1500, seed=3)
    points = np.concatenate((points, hole.vertices[:: max(1, len(hole.vertices) // 500)]))
    _, distance, _ = trimesh.proximity.closest_point(outer, points)
    assert outer.contains(points).all()
    assert distance.min() >= 2 * MM
