"""Every small mesh of trimesh's test models, read by the command line and compared with
trimesh (issue 10's acceptance, on the files kept in ``tests/data/trimesh_models``).

Each file ends in exit status 0 or 2 (run through ``cli.main`` in this process: the
time and memory limits of bad files are tested case by case in test_hostile_meshes). Where trimesh
calls it one watertight, consistently wound volume, plumbob reads it and agrees to
1e-9 in volume, centre of mass and inertia (in the file's own units: ``--units m
--units-override``, a 3MF's millimetres read as trimesh reads them).
Where trimesh's watertight volume is several bodies, plumbob agrees too unless the
bodies overlap, which it then says it united. Anything refused is refused in one line.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from hostile import assert_bad_input, run_in_process, run_limited

DATA = Path(__file__).parent / "data" / "trimesh_models"
SUFFIXES = {".stl", ".obj", ".ply", ".off", ".3mf", ".glb", ".gltf",
            ".zip", ".bz2", ".gz",  # archives holding one of the above
            ".dae", ".3dxml", ".xaml", ".msh"}  # formats refused by name
FILES = sorted((p for p in DATA.iterdir() if p.suffix.lower() in SUFFIXES),
               key=lambda p: p.name.lower())


def trimesh_verdict(path: Path):
    """('volume' | 'bodies' | 'open' | 'empty' | 'fails', trimesh's mesh or None)."""
    trimesh = pytest.importorskip("trimesh")  # an extra: plumbob reads these through it
    try:
        mesh = trimesh.load(str(path), force="mesh")
    except Exception:  # noqa: BLE001 - trimesh raises every kind on files it cannot load
        return "fails", None
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        return "empty", None
    if not (mesh.is_watertight and mesh.is_winding_consistent and mesh.is_volume):
        return "open", mesh
    return ("volume" if mesh.body_count == 1 else "bodies"), mesh


def disagreement(ours: dict, mesh) -> float:
    """Largest relative difference in volume, centre of mass (to the size) and inertia."""
    volume = abs(ours["volume"] - mesh.volume) / abs(mesh.volume)
    size = abs(mesh.volume) ** (1 / 3)
    centre = np.abs(np.subtract(ours["center_of_mass"], mesh.center_mass)).max() / size
    inertia = np.asarray(mesh.moment_inertia)
    moment = np.abs(np.subtract(ours["inertia"], inertia)).max() / np.abs(inertia).max()
    return float(max(volume, centre, moment))


def test_the_kept_models_are_here_with_their_licence():
    assert len(FILES) >= 90
    assert "MIT" in (DATA / "LICENSE.md").read_text()
    assert sum(p.stat().st_size for p in DATA.iterdir()) < 4 * 2**20


@pytest.mark.parametrize("path", FILES, ids=[p.name for p in FILES])
def test_model_reads_as_trimesh_says_or_is_refused_in_one_line(path, capsys):
    verdict, mesh = trimesh_verdict(path)
    outcome = run_in_process(capsys, "mass", path.name, "--json", "--units", "m",
                             "--units-override", cwd=DATA)
    if outcome.status == 2:
        line = assert_bad_input(outcome)
        assert verdict not in ("volume", "bodies"), f"refused a trimesh volume: {line}"
        return
    assert outcome.status == 0, outcome.stderr[-2000:]
    data = json.loads(outcome.stdout)
    assert np.isfinite(data["volume"]) and data["volume"] > 0
    if verdict == "volume":
        assert disagreement(data, mesh) <= 1e-9
    elif verdict == "bodies" and disagreement(data, mesh) > 1e-9:
        # overlapping bodies: trimesh counts the overlap twice, plumbob unites them
        assert any("united" in notice for notice in data["notices"])
        assert data["volume"] < mesh.volume


def test_a_solidworks_export_with_round_off_copies_is_one_watertight_body():
    outcome = run_limited("mass", "idler_riser.STL", "--json", "--units", "m",
                          "--units-override", cwd=DATA)
    assert outcome.status == 0, outcome.stderr
    data = json.loads(outcome.stdout)
    assert any(n.startswith("weld: merged") and "not identical" in n for n in data["notices"])
    _, mesh = trimesh_verdict(DATA / "idler_riser.STL")
    assert disagreement(data, mesh) <= 1e-9
    for name in ("angle_block.STL", "idler_riser.STL"):  # no false T-junctions either
        out = run_limited("mass", name, "--json", cwd=DATA)
        assert "T-junction" not in out.stderr and out.status == 0


def test_featuretype_3mf_closes_through_t_junctions():
    # trimesh calls it open: 18 of its edges are unshared. They form two slits along
    # straight edges (vertices lying on another triangle's edge), which span no area,
    # so the surface closes and the divergence theorem's volume is exact.
    outcome = run_limited("mass", "featuretype.3MF", "--json", "--units", "m",
                          "--units-override", cwd=DATA)
    data = json.loads(outcome.stdout)
    assert any("18 edges end at T-junctions" in n for n in data["notices"])
    _, mesh = trimesh_verdict(DATA / "featuretype.3MF")
    assert disagreement(data, mesh) <= 1e-9  # trimesh's sums over the same faces


def test_a_real_cad_file_with_a_triangle_deleted_is_refused_for_its_hole(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    mesh = trimesh.load(str(DATA / "idler_riser.STL"), process=False)
    broken = trimesh.Trimesh(mesh.vertices, mesh.faces[1:], process=False)
    broken.export(str(tmp_path / "broken.stl"))
    line = assert_bad_input(run_limited("mass", "broken.stl", cwd=tmp_path), "is open",
                            "3 boundary edges (1 hole)", "near")
    assert "overlapping" not in line


@pytest.mark.parametrize("name, member", [("ascii.stl.zip", "fuji_obj.stl"),
                                          ("rock.obj.bz2", "rock.obj"), ("cap.zip", "cap.glb")])
def test_a_packed_trimesh_volume_is_read_naming_its_member(name, member, capsys):
    verdict, mesh = trimesh_verdict(DATA / name)
    assert verdict in ("volume", "bodies")  # trimesh reads each as a watertight volume
    outcome = run_in_process(capsys, "mass", name, "--json", "--units", "m",
                             "--units-override", cwd=DATA)
    assert outcome.status == 0, outcome.stderr
    data = json.loads(outcome.stdout)
    assert disagreement(data, mesh) <= 1e-9
    assert f"read {member} from the archive" in data["notices"][0]


@pytest.mark.parametrize("name, format_name", [("blue_cube.dae", "COLLADA"),
                                               ("cube1.3dxml", "3DXML"), ("plane.xaml", "XAML"),
                                               ("insulated.msh", "Gmsh")])
def test_a_format_plumbob_does_not_read_is_refused_by_name(name, format_name, capsys):
    outcome = run_in_process(capsys, "mass", name, cwd=DATA)
    assert_bad_input(outcome, name, "unsupported file type", format_name, "STL, 3MF, OBJ or PLY")
