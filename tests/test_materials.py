"""The material table and `plumbob materials`."""

from __future__ import annotations

import json
import math
import os
import re
import subprocess
import sys

import pytest
from conftest import ROOT

from plumbob.cli import main
from plumbob.errors import MaterialError
from plumbob.materials import (
    ALIASES,
    CATEGORIES,
    density_of,
    material,
    materials,
    resolve_density,
    sources,
)


def test_every_entry_is_complete_and_sourced():
    refs = sources()
    for name, m in materials().items():
        assert re.fullmatch(r"[a-z0-9_]+", name), name
        assert math.isfinite(m.density) and m.density > 0, name
        assert m.category in CATEGORIES, name
        assert m.description.strip(), name
        assert m.source in refs, f"{name}: source {m.source!r} has no citation"
        assert m.reference == refs[m.source]
    for alias, target in ALIASES.items():
        assert target in materials(), alias


def test_the_issue_asks_for_these_kinds():
    cats = {m.category for m in materials().values()}
    assert {"concrete", "stone", "metal", "wood", "plastic", "filament", "liquid"} <= cats
    for name in ("water", "concrete", "granite", "steel", "aluminium", "oak", "pla", "petg", "abs"):
        assert name in materials()


def test_wood_densities_follow_from_their_specific_gravity():
    """Wood Handbook: ρ(12 %) = 1000 · G · (1 + 0.12), G given in each description."""
    checked = 0
    for m in materials().values():
        found = re.search(r"G = ([0-9.]+)", m.description)
        if m.category == "wood" and found:
            assert m.density == pytest.approx(1000 * float(found.group(1)) * 1.12, abs=6), m.name
            checked += 1
    assert checked >= 10


def test_densities_against_independent_values():
    """Physical constants known independently of the table's sources."""
    assert density_of("water") == pytest.approx(998.2, abs=0.1)  # 20 °C
    assert density_of("ice") < density_of("water") < density_of("seawater")
    assert density_of("lead") / density_of("water") == pytest.approx(11.36, rel=0.01)
    assert density_of("gold") == pytest.approx(19300, rel=0.01)
    # described ranges contain the value
    for m in materials().values():
        rng = re.search(r"\((\d+)-(\d+)\)", m.description)
        if rng:
            lo, hi = map(float, rng.groups())
            assert lo <= m.density <= hi, m.name


def test_lookup_ignores_case_spaces_and_hyphens():
    assert material("Stainless Steel").name == "stainless_steel"
    assert material("douglas-fir").name == "douglas_fir"
    assert material("  PLA ").density == 1240
    assert material("aluminum").name == "aluminium"
    assert material("Teflon").name == "ptfe"


def test_unknown_material_suggests():
    with pytest.raises(MaterialError, match="did you mean granite"):
        material("granit")
    with pytest.raises(MaterialError, match="plumbob materials"):
        material("kryptonite")
    with pytest.raises(MaterialError):
        material(3)  # type: ignore[arg-type]


def test_resolve_density():
    assert resolve_density(1200) == 1200.0
    assert resolve_density("7.85e3") == 7850.0
    assert resolve_density("oak") == density_of("oak")
    with pytest.raises(Exception, match="positive"):
        resolve_density(-1)


def test_cli_lists_every_material(capsys):
    assert main(["materials"]) == 0
    out = capsys.readouterr().out
    for name in materials():
        assert re.search(rf"^{name}\s", out, re.M), name
    assert "sources:" in out and "Eurocode" in out


def test_cli_json(capsys):
    assert main(["materials", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [m["name"] for m in data["materials"]] == list(materials())
    steel = next(m for m in data["materials"] if m["name"] == "steel")
    assert steel == {"name": "steel", "density": 7850.0, "category": "metal",
                     "description": "structural (carbon) steel", "source": "EN1991"}
    assert set(data["sources"]) == {m.source for m in materials().values()}


def test_cli_filters(capsys):
    assert main(["materials", "--category", "filament", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert {m["category"] for m in data["materials"]} == {"filament"}
    assert "petg" in {m["name"] for m in data["materials"]}
    assert main(["materials", "pine"]) == 0
    out = capsys.readouterr().out
    assert "white_pine" in out and "steel" not in out
    # A search that matches nothing has not failed (exit 1 means a failed requirement):
    # it says so, with the nearest names, and exits 0; the JSON list is empty.
    assert main(["materials", "grnite"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("no material matches 'grnite'; try granite")
    assert main(["materials", "unobtainium", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["materials"] == []
    assert main(["materials", "--category", "cheese"]) == 2
    assert "unknown category" in capsys.readouterr().err


def test_materials_command_imports_nothing_heavy():
    code = ("import sys; from plumbob.cli import main; main(['materials', '--json']); "
            "heavy = [m for m in ('shapely', 'manifold3d', 'trimesh', 'scipy') "
            "if m in sys.modules]; sys.stderr.write(repr(heavy))")
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"))
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert result.returncode == 0, result.stderr
    assert result.stderr.strip().endswith("[]"), result.stderr
