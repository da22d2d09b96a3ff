"""Results describe themselves once: each declares its JSON keys (``Result.KEYS``: name,
unit, when, meaning), ``as_dict()`` keeps to them, and docs/cli.md's key tables are
generated from them — this test holds all three together."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from conftest import ROOT

from plumbob.batch.columns import _MASS
from plumbob.commands.mass_report import MassReport
from plumbob.commands.schema import DOCUMENTED, regenerate, result_class
from plumbob.energy import PoseChange, PotentialEnergy
from plumbob.loading import read
from plumbob.results import TYPES, Key, Result, key_table, undeclared_keys
from plumbob.stability.verdict import Verdict

#: the results whose keys docs/cli.md shows as generated tables, by the name in its marker
DECLARED = {name: result_class(name) for name in DOCUMENTED}
DOCS = Path(ROOT) / "docs" / "cli.md"
_BLOCK = re.compile(r"<!-- keys: (\w+) -->\n(.*?)\n<!-- /keys -->", re.S)


def test_the_docs_tables_are_the_declared_keys():
    text = DOCS.read_text(encoding="utf-8")
    blocks = dict(_BLOCK.findall(text))
    assert set(blocks) == set(DECLARED), "a key table in docs/cli.md without its result"
    for name, table in blocks.items():
        assert table == key_table(DECLARED[name].KEYS), (
            f"docs/cli.md's table of {name} differs from {name}.KEYS: regenerate the tables "
            "with python -m plumbob.commands.schema docs/cli.md")
    assert regenerate(text) == text


def test_the_generator_fills_an_empty_table_and_stops_at_its_end():
    text = "a\n<!-- keys: CrewTime -->\n<!-- /keys -->\nb\n<!-- keys: Pose -->\nold\n<!-- /keys -->\n"
    new = regenerate(text)
    assert new.startswith("a\n<!-- keys: CrewTime -->\n| key |") and "\nb\n<!-- keys: Pose -->" in new
    assert "old" not in new and regenerate(new) == new


def test_the_json_of_every_documented_result_is_generated_from_its_keys():
    """No hand-written dictionary beside the declaration: ``as_dict`` is
    :meth:`Result.as_dict`, which reads ``KEYS``."""
    handwritten = [name for name, cls in DECLARED.items()
                   if cls.as_dict is not Result.as_dict]
    assert not handwritten
    assert all(DECLARED[name].KEYS for name in DECLARED)


@pytest.mark.parametrize("shape", ["block", "l_shape", "mace_assembly", "graded_plate"])
@pytest.mark.parametrize("about", [None, (0.0, 0.0, 0.0)])
def test_the_mass_json_keeps_to_its_declared_keys(shape, about):
    reading = read(str(Path(ROOT) / "shapes" / f"{shape}.toml"))
    if about is not None and reading.body.dim == 2:
        about = about[:2]
    out = MassReport.of(reading, about=about, sizes=about is not None).as_dict()
    assert not undeclared_keys(out, MassReport.KEYS)
    order = [k.name for k in MassReport.KEYS]
    assert list(out) == sorted(out, key=order.index), "keys out of their declared order"


def test_every_declared_key_has_a_meaning_and_a_unique_name():
    for result in [*DECLARED.values(), PotentialEnergy, PoseChange]:
        names = [k.name for k in result.KEYS]
        assert len(names) == len(set(names))
        assert all(isinstance(k, Key) and k.doc and re.fullmatch(r"[a-z_0-9]+", k.name)
                   and k.type in (*TYPES, "") for k in result.KEYS)


def test_the_library_results_give_their_declared_keys():
    from plumbob.bodies.primitives import box
    from plumbob.dynamics.collisions import collide
    from plumbob.energy import lift_energy, pose_energy_change, potential_energy
    from plumbob.stability import resting_poses

    block = box(1, 1, 2, density=10.0)
    for result in (lift_energy(block), potential_energy(block), resting_poses(block),
                   resting_poses(block)[0], pose_energy_change(block, [1, 0, 0], [0, 0, -1]),
                   collide(1.0, [1.0, 0.0], 2.0, [0.0, 0.0])):
        out = result.as_dict()
        assert not undeclared_keys(out, type(result).KEYS), type(result).__name__
        assert list(out) == [k.name for k in type(result).KEYS if k.name in out]


def test_the_batch_mass_columns_are_declared_keys():
    """A batch row's mass columns are ``plumbob mass --json``'s keys (``units``, the
    unit the file was read in, is the batch table's own)."""
    names = {k.name for k in MassReport.KEYS}
    assert {f.key for f in _MASS} - {"units"} <= names


def test_the_undeclared_check_can_fail():
    assert undeclared_keys({"mass": 1.0, "weight": 2.0}, MassReport.KEYS) == [
        "weight", "kind (missing)", "center_of_mass (missing)", "inertia (missing)",
        "principal_moments (missing)", "principal_axes (missing)", "exact (missing)",
        "relative_error (missing)", "parts (missing)", "radii_of_gyration (missing)"]


#: check options that bring out every conditional key of the verdict between them
CHECKS = [{}, {"tilt_deg": 5.0, "toward_deg": 30.0, "friction": 0.4},
          {"require_tilt_deg": 40.0, "margin": 5.0}, {"down": [1.0, 0.2, -0.1]}]


@pytest.mark.parametrize("shape", ["block", "l_shape", "stepped_cylinder", "mace_assembly"])
@pytest.mark.parametrize("options", CHECKS)
def test_the_check_json_keeps_to_its_declared_keys(shape, options):
    from plumbob.stability import check

    body = read(str(Path(ROOT) / "shapes" / f"{shape}.toml")).body
    if body.dim == 2:
        options = {k: v for k, v in options.items() if k not in ("down", "tilt_deg", "toward_deg")}
    out = check(body, **options).as_dict()
    assert not undeclared_keys(out, Verdict.KEYS)
    order = [k.name for k in Verdict.KEYS]
    assert list(out) == sorted(out, key=order.index), "keys out of their declared order"


def test_the_batch_check_columns_are_declared_keys():
    """A batch row's check columns are ``plumbob check --json``'s keys (``slope``'s with
    a ``slope_`` prefix)."""
    from plumbob.batch.columns import _CHECK, _REQUIRE

    names = {k.name for k in Verdict.KEYS}
    assert {f.key for f in _CHECK + _REQUIRE} <= names


def test_the_batch_columns_are_made_from_the_declared_keys():
    """Every column of a results row but the table's own (the file, its status, the unit,
    the pose count) is a declared key of the result it comes from, of the declared form;
    a slope's, a load verdict's and the first pose's carry a prefix."""
    from plumbob.batch.columns import _FORMS, Field, pose_fields, result_fields
    from plumbob.batch.options import Options
    from plumbob.stability.checks import SlopeCheck
    from plumbob.stability.loaded import LoadVerdict
    from plumbob.stability.poses.result import Pose, Poses

    own = {"path", "name", "status", "error", "reason", "units", "poses", "pose", "notes",
           "notices", "file_size", "file_mtime_ns", "file_sha256"}
    declared = {k.name: k for k in (*MassReport.KEYS, *Verdict.KEYS)}
    declared |= {f"slope_{k.name}": k for k in SlopeCheck.KEYS}
    declared |= {f"load_{k.name}": k for k in LoadVerdict.KEYS}
    declared |= {k.name: k for k in LoadVerdict.KEYS if k.name.startswith(("over", "resist"))}
    declared |= {f"pose_{k.name}": k for k in Pose.KEYS} | {k.name: k for k in Pose.KEYS}
    declared |= {f"poses_{k.name}": k for k in Poses.KEYS}
    options = Options(check=True, poses=True, tilt=5.0, require_tilt=10.0,
                      load_options=(("force", [10.0, 0.0, 0.0], [0.0, 0.0, 0.5]),))
    for f in result_fields(options) + pose_fields():
        if f.key in own or f.key.startswith("std_") or f.key == "standard_passes":
            continue
        key = declared[f.key]
        assert f == Field(f.key, *_FORMS.get(key.type, (key.type, ()))), f
