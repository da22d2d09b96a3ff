"""The JSON of every command on the shipped shapes/ stays as it was recorded.

The golden files in ``tests/golden/`` were written by the commands before their JSON was
built from the results' ``as_dict()``; this test holds every later version to them: the
same keys in the same order, the same strings and flags, numbers equal to 1e-12 relative
(round-off is measured against the largest number of the same top-level value, so a
zero that comes out as 1e-17 still matches).

A simulation's two diagnostics are not outputs but measures of error, and are compared
with the tolerance their arithmetic gives them (``DIAGNOSTICS``): each is a difference of
nearly equal numbers, so its own relative round-off is large, and another numpy, scipy or
BLAS moves it without any change of the trajectory. ``max_constraint_error`` (how far the
rods drifted from their lengths, relative) is the integrator's error, held to the order of
its ``rtol`` (the spec's default, 1e-10): recorded as 3.1e-10, it may come out anywhere
within ``rtol`` of that and still say the same. ``newton_residual`` (|M a_G - F_ext|
relative to the forces) is round-off of a sum of a few forces: within 64 ulps of 1 of the
recorded value.

To record them again (only when a change of output is intended and documented)::

    PYTHONPATH=src python tests/test_cli_golden.py --regenerate
"""

from __future__ import annotations

import contextlib
import inspect
import io
import json
import math
import os
import sys

import pytest

from plumbob.dynamics.motion import simulate

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GOLDEN = os.path.join(ROOT, "tests", "golden")
REL = 1e-12
#: The simulation's default tolerance (``plumbob.dynamics.motion.simulate``'s rtol).
SIMULATION_RTOL = inspect.signature(simulate).parameters["rtol"].default
#: Top-level keys that measure an error rather than report a result: absolute tolerance.
DIAGNOSTICS = {"max_constraint_error": SIMULATION_RTOL,
               "newton_residual": 64 * sys.float_info.epsilon}

BODIES = ("block", "earth_moon", "graded_plate", "l_shape", "mace", "mace_assembly",
          "mace_throw", "pyramid_cheops", "sculpture", "semicircle", "spring_pair",
          "stepped_cylinder", "triangle")
# Particles lying flat in the plane they would rest on have nothing to stand on (exit 2).
CHECKABLE = tuple(b for b in BODIES if b not in ("earth_moon", "mace", "mace_throw",
                                                   "spring_pair"))


def _cases() -> dict[str, tuple[int, list[str]]]:
    """name -> (exit status, argv without --json); paths relative to the repository."""
    cases: dict[str, tuple[int, list[str]]] = {}
    for body in BODIES:
        spec = f"shapes/{body}.toml"
        cases[f"mass.{body}"] = (0, ["mass", spec])
        cases[f"lift.{body}"] = (0, ["lift", spec])
        if body in CHECKABLE:
            cases[f"check.{body}"] = (0, ["check", spec])
    cases["mass.stepped_cylinder.material"] = (0, ["mass", "shapes/stepped_cylinder.toml",
                                                  "--material", "oak"])
    cases["check.block.design"] = (0, ["check", "shapes/block.toml", "--require-tilt", "10",
                                       "--friction", "0.2"])
    cases["check.block.fails"] = (1, ["check", "shapes/block.toml", "--require-tilt", "15"])
    cases["check.block.slope"] = (0, ["check", "shapes/block.toml", "--tilt", "15", "--toward",
                                      "90", "--friction", "0.3"])
    cases["check.block.down"] = (0, ["check", "shapes/block.toml", "--down", "1,0,0",
                                     "--g", "10"])
    cases["check.block.pose"] = (0, ["check", "shapes/block.toml", "--pose", "2"])
    cases["check.sculpture.slope"] = (0, ["check", "shapes/sculpture.toml", "--tilt", "5"])
    cases["check.stepped_cylinder.friction"] = (0, ["check", "shapes/stepped_cylinder.toml",
                                                    "--friction", "0.5"])
    cases["lift.pyramid_cheops.crew"] = (0, ["lift", "shapes/pyramid_cheops.toml", "--crew",
                                             "1000"])
    cases["lift.block.work"] = (0, ["lift", "shapes/block.toml", "--datum", "-1",
                                    "--work-per-day", "5000", "--crew", "3", "--g", "9.8"])
    cases["simulate.spring_pair"] = (0, ["simulate", "shapes/spring_pair.toml", "--until", "5",
                                         "--samples", "11"])
    cases["simulate.mace_throw"] = (0, ["simulate", "shapes/mace_throw.toml", "--until", "1.6",
                                        "--samples", "9"])
    cases["collide.example6"] = (0, ["collide", "--m1", "0.17", "--v1", "5,0", "--m2", "0.17",
                                     "--v2", "0,0"])
    cases["collide.example8"] = (0, ["collide", "--m1", "9", "--v1", "0.5,0.866", "--m2", "1",
                                     "--normal", "0,1", "--e", "0.8"])
    cases["collide.wall"] = (0, ["collide", "--m1", "0.1", "--v1", "3,-4", "--m2", "inf",
                                 "--normal", "0,-1", "--e", "0.5"])
    cases["collide.coalesce3d"] = (0, ["collide", "--m1", "2", "--v1", "1,2,3", "--m2", "3",
                                       "--v2", "-1,0,1", "--e", "0"])
    cases["materials.oak"] = (0, ["materials", "oak"])
    return cases


CASES = _cases()


def _run(argv: list[str]) -> tuple[int, str]:
    from plumbob.cli import main

    out = io.StringIO()
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        with contextlib.redirect_stdout(out):
            status = main([*argv, "--json"])
    finally:
        os.chdir(cwd)
    return status, out.getvalue()


def _largest(value) -> float:
    if isinstance(value, bool) or value is None or isinstance(value, str):
        return 0.0
    if isinstance(value, (int, float)):
        return abs(float(value))
    if isinstance(value, list):
        return max((_largest(v) for v in value), default=0.0)
    if isinstance(value, dict):
        return max((_largest(v) for v in value.values()), default=0.0)
    return 0.0


def _compare(got, want, where: str, scale: float) -> None:
    if isinstance(want, dict):
        assert isinstance(got, dict), f"{where}: {got!r} is not an object"
        assert list(got) == list(want), f"{where}: keys {list(got)} != {list(want)}"
        for key in want:
            _compare(got[key], want[key], f"{where}.{key}", scale)
    elif isinstance(want, list):
        assert isinstance(got, list) and len(got) == len(want), f"{where}: {got!r} != {want!r}"
        for k, (g, w) in enumerate(zip(got, want, strict=True)):
            _compare(g, w, f"{where}[{k}]", scale)
    elif isinstance(want, bool) or want is None or isinstance(want, str):
        assert got == want and type(got) is type(want), f"{where}: {got!r} != {want!r}"
    else:
        assert isinstance(got, (int, float)) and not isinstance(got, bool), \
            f"{where}: {got!r} is not a number"
        assert math.isclose(got, want, rel_tol=REL, abs_tol=REL * scale), \
            f"{where}: {got!r} != {want!r}"


@pytest.mark.parametrize("name", sorted(CASES))
def test_json_unchanged(name: str) -> None:
    status, argv = CASES[name]
    with open(os.path.join(GOLDEN, f"{name}.json"), encoding="utf-8") as f:
        want = json.load(f)
    got_status, text = _run(argv)
    assert got_status == status
    got = json.loads(text)
    assert isinstance(want, dict)
    assert list(got) == list(want), f"keys {list(got)} != {list(want)}"
    for key in want:
        if key in DIAGNOSTICS:
            assert isinstance(got[key], float) and got[key] >= 0, (key, got[key])
            assert abs(got[key] - want[key]) <= DIAGNOSTICS[key], (key, got[key], want[key])
        else:
            _compare(got[key], want[key], key, _largest(want[key]))


def test_every_golden_file_has_a_case() -> None:
    files = {f[: -len(".json")] for f in os.listdir(GOLDEN) if f.endswith(".json")}
    assert files == set(CASES)


def _regenerate() -> None:
    os.makedirs(GOLDEN, exist_ok=True)
    for name, (status, argv) in CASES.items():
        got_status, text = _run(argv)
        assert got_status == status, (name, got_status)
        with open(os.path.join(GOLDEN, f"{name}.json"), "w", encoding="utf-8") as f:
            f.write(text)
        print(name, len(text))


if __name__ == "__main__" and sys.argv[1:] == ["--regenerate"]:
    _regenerate()
