"""plumbob against trimesh over trimesh's own test models (issue 10's acceptance).

For every mesh file in the folder (the suffixes trimesh loads as 3D meshes, archives
included; drawings, images and point clouds are not meshes), ``plumbob mass FILE
--json --units m`` runs as its own process (60 s, 2 GiB at most) and trimesh loads
the file in this one. Each file ends in one of:

* ``agree``   trimesh calls it a watertight, consistently wound volume; plumbob
              reads it and volume, centre of mass and inertia agree to 1e-9;
* ``united``  trimesh calls it a volume of several bodies, which overlap: plumbob
              unites them (manifold3d) and says so, trimesh counts the overlap twice;
* ``read``    trimesh does not call it a volume; plumbob reads it (T-junctions, welded
              round-off, UV seams trimesh keeps split) — trimesh's own volume, where it
              has one, is shown for comparison;
* ``refused`` exit 2 with one line naming the defect;
* ``foreign`` exit 2 with one line: a format plumbob does not read (COLLADA, 3DXML,
              STEP, …);
* ``WRONG``   anything else: a refusal of a trimesh volume (for its format too), a
              disagreement, a traceback, an exit status other than 0 or 2, or more
              than one line.

Run: python bench/trimesh_corpus.py [FOLDER]   (default /work/trimesh_models/models);
``--smoke``: a folder of two small generated meshes instead (a torus and a truncated one).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
from collections import Counter

import numpy as np

MESH_SUFFIXES = (".stl", ".obj", ".ply", ".off", ".3mf", ".glb", ".gltf", ".dae", ".zae",
                 ".3dxml", ".xaml", ".ctm", ".msh", ".binvox", ".step", ".zip", ".bz2",
                 ".tar.gz")
SRC = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "src")
TOLERANCE = 1e-9


def mesh_files(folder: str) -> list[str]:
    """The mesh files directly in ``folder``, sorted by name."""
    names = sorted(os.listdir(folder), key=str.lower)
    return [os.path.join(folder, n) for n in names
            if os.path.isfile(os.path.join(folder, n)) and n.lower().endswith(MESH_SUFFIXES)]


def _limits() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (2 * 1024**3, 2 * 1024**3))


def run_plumbob(path: str) -> tuple[int, str, dict | None]:
    """Exit status, standard error and parsed JSON of ``plumbob mass PATH --json --units m``."""
    env = dict(os.environ, PYTHONPATH=SRC, OPENBLAS_NUM_THREADS="1")
    try:
        done = subprocess.run([sys.executable, "-m", "plumbob", "mass", path, "--json",
                               "--units", "m"], capture_output=True, text=True, timeout=60,
                              env=env, preexec_fn=_limits)
    except subprocess.TimeoutExpired:
        return -1, "timed out after 60 s", None
    data = None
    if done.returncode == 0:
        try:
            data = json.loads(done.stdout)
        except ValueError:
            data = None
    return done.returncode, done.stderr, data


def trimesh_reference(path: str) -> tuple[str, dict | None]:
    """What trimesh makes of the file: ('volume', properties) when it is one watertight,
    consistently wound body, ('bodies', properties) when it is several; else ('open',
    properties or None), ('empty', None) or ('fails', None)."""
    import trimesh

    try:
        mesh = trimesh.load(path, force="mesh")
    except Exception:  # noqa: BLE001 - trimesh raises every kind on files it cannot load
        return "fails", None
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        return "empty", None
    properties = {"volume": float(mesh.volume), "center_of_mass": mesh.center_mass,
                  "inertia": mesh.moment_inertia, "triangles": len(mesh.faces)}
    if not (mesh.is_watertight and mesh.is_winding_consistent and mesh.is_volume):
        return "open", properties
    return ("volume" if mesh.body_count == 1 else "bodies"), properties


def disagreement(ours: dict, theirs: dict) -> float:
    """Largest relative difference of volume, centre of mass (to the size) and inertia."""
    volume = abs(ours["volume"] - theirs["volume"]) / abs(theirs["volume"])
    size = abs(theirs["volume"]) ** (1 / 3)
    centre = np.abs(np.subtract(ours["center_of_mass"], theirs["center_of_mass"])).max() / size
    inertia = theirs["inertia"]
    moment = np.abs(np.subtract(ours["inertia"], inertia)).max() / np.abs(inertia).max()
    return float(max(volume, centre, moment))


def judge(path: str) -> tuple[str, str, str]:
    """(outcome, trimesh's verdict, detail) for one file."""
    verdict, reference = trimesh_reference(path)
    status, stderr, data = run_plumbob(path)
    lines = [line for line in stderr.splitlines() if line.strip()]
    if status == 2:
        if len(lines) != 1 or "Traceback" in stderr:
            return "WRONG", verdict, f"exit 2 but {len(lines)} lines"
        reason = lines[0].split(": ", 2)[-1]
        if verdict in ("volume", "bodies"):  # whatever the reason, a format included
            return "WRONG", verdict, "refused a trimesh volume: " + lines[0]
        if "unknown file type" in reason or "unsupported file type" in reason:
            return "foreign", verdict, reason.split(";")[0]
        return "refused", verdict, reason
    if status != 0 or data is None:
        return "WRONG", verdict, f"exit {status}: {(lines or [''])[-1][:120]}"
    if verdict not in ("volume", "bodies"):
        theirs = f" (trimesh {reference['volume']:.6g})" if reference else ""
        return "read", verdict, f"volume {data['volume']:.6g}{theirs}"
    error = disagreement(data, reference)
    if error <= TOLERANCE:
        return "agree", verdict, f"within {error:.1e}"
    if verdict == "bodies" and any("united" in n for n in data.get("notices", [])):
        return "united", verdict, (f"volume {data['volume']:.6g}, trimesh {reference['volume']:.6g}"
                                   " counts the overlap twice")
    return "WRONG", verdict, f"differs from trimesh by {error:.2g}"


def _smoke_folder() -> str:
    """A folder of two small STL files: a closed torus and the same torus cut open."""
    import tempfile

    from _common import torus_triangles, write_binary_stl

    folder = tempfile.mkdtemp(prefix="plumbob-corpus-")
    triangles = torus_triangles(400)
    write_binary_stl(os.path.join(folder, "torus.stl"), triangles)
    write_binary_stl(os.path.join(folder, "open.stl"), triangles[:-10])
    return folder


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", nargs="?", default="/work/trimesh_models/models")
    parser.add_argument("--smoke", action="store_true", help="two small generated meshes")
    args = parser.parse_args(argv)
    if args.smoke:
        args.folder = _smoke_folder()
    files = mesh_files(args.folder)
    counts: Counter = Counter()
    width = max(len(os.path.basename(f)) for f in files)
    print(f"{'file':<{width}}  {'trimesh':<7}  {'plumbob':<7}  detail")
    for path in files:  # one process per file
        outcome, verdict, detail = judge(path)
        counts[outcome] += 1
        print(f"{os.path.basename(path):<{width}}  {verdict:<7}  {outcome:<7}  {detail[:110]}",
              flush=True)
    print(f"\n{len(files)} mesh files: " + ", ".join(f"{counts[k]} {k}" for k in
                                                     ("agree", "united", "read", "refused",
                                                      "foreign", "WRONG")))
    if args.smoke:
        import shutil

        shutil.rmtree(args.folder, ignore_errors=True)
    return 1 if counts["WRONG"] else 0


if __name__ == "__main__":
    sys.exit(main())
