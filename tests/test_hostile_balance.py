"""Bad input to balance and check --solve-for: one line, exit status 2, never a hang;
and --solve-for on every shipped spec with parameters ends in an answer or one line."""

import os

import pytest
from conftest import SHAPES
from hostile import assert_bad_input, run_limited

from plumbob.spec.loader import spec_parameters

BLOCK = os.path.join(SHAPES, "block.toml")
SCULPTURE = os.path.join(SHAPES, "sculpture.toml")

CASES = {
    "no target": (["balance", BLOCK], ("give a target",)),
    "negative margin": (["balance", BLOCK, "--margin", "-1"], ("must not be negative",)),
    "margin not a length": (["balance", BLOCK, "--margin", "3 furlongs"], ("length",)),
    "margin unknown unit": (["balance", BLOCK, "--margin", "3parsec"], ("unknown length unit",)),
    "toward without tilt": (["balance", BLOCK, "--margin", "0.1", "--toward", "90"],
                            ("--toward needs --tilt",)),
    "tilt and require-tilt": (["balance", BLOCK, "--tilt", "5", "--require-tilt", "5"],
                              ("not both",)),
    "tilt of 90": (["balance", BLOCK, "--require-tilt", "90"], ("between 0° and 90°",)),
    "unknown material": (["balance", BLOCK, "--require-tilt", "20", "--ballast-material",
                          "unobtainium"], ("unobtainium",)),
    "material lighter than the body": (["balance", BLOCK, "--require-tilt", "20",
                                        "--ballast-material", "pine"], ("not denser",)),
    "missing region": (["balance", BLOCK, "--require-tilt", "20", "--ballast-region",
                        "nowhere.stl"], ("nowhere.stl",)),
    "pose out of range": (["balance", BLOCK, "--margin", "0.1", "--target-pose", "99"],
                          ("--target-pose must be between 1 and",)),
    "point support": (["balance", BLOCK, "--margin", "0.1", "--down", "1,1,-1"],
                      ("single point",)),
    "solve for an unknown name": (["check", SCULPTURE, "--require-tilt", "10", "--solve-for",
                                   "base_width"], ("base_width", "a, h, foot")),
    "solve for without a requirement": (["check", SCULPTURE, "--solve-for", "foot"],
                                        ("needs a requirement",)),
    "solve for with two requirements": (["check", SCULPTURE, "--solve-for", "foot",
                                         "--margin", "0.1", "--require-tilt", "5"],
                                        ("one requirement",)),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_bad_input(case, tmp_path):
    args, phrases = CASES[case]
    assert_bad_input(run_limited(*args, cwd=tmp_path), *phrases)


@pytest.mark.parametrize(("args", "phrase"), [
    (["balance", BLOCK, "--margin", "0.6"], "too narrow"),
    (["check", BLOCK, "--require-tilt", "20", "--solve-for", "h"], "stays short")],
    ids=["unreachable margin", "solve for a scale"])
def test_a_target_nothing_reaches_is_a_failed_requirement_in_one_line(args, phrase, tmp_path):
    """No ballast, no value of the parameter reaches it: exit status 1 (a requirement not
    met, as a failed check is), never 2 (bad input); one line, nothing on stdout."""
    outcome = run_limited(*args, cwd=tmp_path)
    assert outcome.status == 1 and outcome.stdout == "" and len(outcome.lines) == 1
    assert phrase in outcome.lines[0] and "Traceback" not in outcome.stderr


def test_solve_for_on_a_mesh(tmp_path):
    mesh = tmp_path / "cube.stl"
    mesh.write_text("solid c\nendsolid c\n", encoding="utf-8")
    assert_bad_input(run_limited("check", str(mesh), "--margin", "0.1", "--solve-for", "a",
                                 cwd=tmp_path), "spec")


# each shipped spec's first parameter (every parameter of every spec takes minutes: the
# searches that find no answer rebuild the body some 40 times)
SPEC_PARAMETERS = [(name, next(iter(parameters)))
                   for name in sorted(os.listdir(SHAPES)) if name.endswith(".toml")
                   for parameters in [spec_parameters(os.path.join(SHAPES, name))]
                   if parameters]


def _a_little_above(path: str) -> float:
    """Two degrees more critical tilt than the spec has (30° where it has none to check)."""
    import plumbob

    try:
        return min(max(plumbob.check(path).critical_tilt_deg, 0.0) + 2.0, 89.0)
    except plumbob.PlumbobError:
        return 30.0


@pytest.mark.parametrize(("name", "parameter"), SPEC_PARAMETERS)
def test_solve_for_every_shipped_parameter(name, parameter, tmp_path):
    """A design requirement a little above what each spec has: an answer (0, 1) or one
    line naming why not (2) — never an internal error, never a hang. (A search that
    finds no value at all, the longest kind, is test_bad_input's "stays short" case.)"""
    path = os.path.join(SHAPES, name)
    outcome = run_limited("check", path, "--require-tilt", f"{_a_little_above(path):.6g}",
                          "--solve-for", parameter, "--json", cwd=tmp_path, timeout=60)
    if outcome.status == 2:
        assert_bad_input(outcome)
    elif outcome.status == 1 and not outcome.stdout:  # no value reaches it: one line
        assert len(outcome.lines) == 1 and "meets the requirement" in outcome.lines[0]
    else:
        assert outcome.status in (0, 1), outcome.stderr[-2000:]
        assert '"solution"' in outcome.stdout
