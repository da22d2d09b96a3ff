"""Hostile command-line options (issue 10): NaN and infinite values, results that
overflow, values out of range, work beyond the limits, names with control characters.

Each case ends in one line and exit status 2 within the harness's limits (10 s,
1 GiB) — or, where the input is legitimate, in the right answer — never in ``nan``,
``inf`` or JSON ``null`` with exit status 0, and never in exit status 1 (which means
only "a requirement failed").
"""

from __future__ import annotations

import json
import os

import pytest
from hostile import assert_bad_input, run_limited
from hypothesis import given, settings
from hypothesis import strategies as st

PLATE = "POLYGON ((0 0, 2 0, 2 1, 0 1, 0 0))"


@pytest.fixture
def block(shapes_dir):
    return os.path.join(shapes_dir, "block.toml")


@pytest.fixture
def spring_pair(shapes_dir):
    return os.path.join(shapes_dir, "spring_pair.toml")


@pytest.fixture
def plate(tmp_path):
    path = tmp_path / "plate.wkt"
    path.write_text(PLATE)
    return path


# (command and options after PATH, phrases the one line must name)
BODY_CASES = [
    (["lift", "--datum", "nan"], ["--datum", "finite"]),
    (["lift", "--datum", "inf"], ["--datum", "finite"]),
    (["lift", "--datum", "-inf", "--json"], ["--datum", "finite"]),
    (["lift", "--datum", "1e308", "--json"], ["lift energy", "overflows"]),
    (["lift", "--g", "1e308"], ["lift energy", "overflows"]),
    (["lift", "--g", "nan"], ["--g"]),
    (["lift", "--crew", "1", "--work-per-day", "1e-308"], ["person-days", "overflows"]),
    (["check", "--g", "1e308", "--json"], ["overflows", "weight M g"]),
    (["check", "--g", "-9.81"], ["--g", "positive"]),
    (["check", "--g", "0"], ["--g", "positive"]),
    (["check", "--require-tilt", "100"], ["--require-tilt", "0 to 90"]),
    (["check", "--require-tilt", "-1"], ["--require-tilt", "0 to 90"]),
    (["check", "--require-tilt", "nan"], ["--require-tilt", "finite"]),
    (["check", "--tilt", "5", "--toward", "nan"], ["--toward", "finite"]),
    (["check", "--tilt", "5", "--toward", "1e999"], ["--toward", "finite"]),
    (["check", "--tilt", "95"], ["tilt", "90"]),
    (["check", "--down", "nan,0,-1"], ["--down", "finite"]),
    (["check", "--down", "1e999,0,-1"], ["--down", "finite"]),
    (["check", "--down", "0,0,0"], ["--down", "zero vector"]),
    (["lift", "--crew", "1e3"], ["--crew", "whole number"]),
    (["check", "--friction", "inf"], ["--friction", "finite"]),
    (["check", "--tolerance", "nan"], ["--tolerance", "finite"]),
    (["check", "--pose", "0"], ["--pose", "between 1 and"]),
    (["check", "--tolerance", "1e308"], ["contact tolerance", "not small beside the body"]),
    (["report", "--require-tilt", "100"], ["--require-tilt", "0 to 90"]),
    (["mass", "--material", ""], ["--material", "empty"]),
    (["mass", "--material", "   "], ["--material", "empty"]),
    (["mass", "--density", "nan"], ["--density", "positive finite"]),
]


@pytest.mark.parametrize(("options", "phrases"), BODY_CASES,
                         ids=[" ".join(c[0]) or "none" for c in BODY_CASES])
def test_a_bad_option_on_a_body_is_one_line_exit_2(block, options, phrases):
    assert_bad_input(run_limited(options[0], block, *options[1:]), *phrases)


@pytest.mark.parametrize("options", [["mass", "--density", "1e308"],
                                     ["mass", "--density", "1e308", "--json"],
                                     ["check", "--density", "1e305", "--g", "1e10"]],
                         ids=["mass text", "mass json", "check weight"])
def test_a_density_whose_mass_overflows_is_refused(plate, options):
    """The plate gives no density, so --density applies; 2e308 kg is no answer."""
    assert_bad_input(run_limited(options[0], plate, "--units", "m", *options[1:]),
                     "overflows")


SIMULATE_CASES = [
    (["--until", "1e300"], ["double precision", "--until"]),
    (["--until", "1e-300"], ["double precision", "or more"]),
    (["--until", "1e6"], ["oscillations", "MAX_PERIODS", "or less"]),
    (["--until", "nan"], ["--until", "finite"]),
    (["--until", "-1"], ["--until", "positive"]),
    (["--until", "1", "--samples", "1e12"], ["--samples", "limit"]),
    (["--until", "1", "--samples", "1e7"], ["--samples", "limit"]),
    (["--until", "1", "--samples", "1"], ["--samples", "at least 2"]),
    (["--until", "1", "--samples", "2.5"], ["--samples", "whole number"]),
]


@pytest.mark.parametrize(("options", "phrases"), SIMULATE_CASES,
                         ids=[" ".join(c[0]) for c in SIMULATE_CASES])
def test_a_simulation_beyond_what_can_be_integrated_is_refused_at_once(spring_pair, options,
                                                                       phrases):
    assert_bad_input(run_limited("simulate", spring_pair, *options), *phrases)


def test_the_spring_pair_over_a_long_but_faithful_run_is_right(spring_pair):
    """Within the limits the separation still follows the seed's closed form:
    2 (l0 + P/(4k)(1 − cos ωt)), ω = √(2k/m), m = 2, k = 50, l0 = 0.5, P = 10."""
    import numpy as np

    outcome = run_limited("simulate", spring_pair, "--until", "200", "--samples", "41", "--json",
                          timeout=60)
    assert outcome.status == 0, outcome.stderr
    data = json.loads(outcome.stdout)
    t = np.array(data["times"])
    x = np.array(data["positions"])[:, :, 0]
    exact = 2 * (0.5 + 10 / 200 * (1 - np.cos(np.sqrt(50.0) * t)))
    assert np.max(np.abs(x[:, 1] - x[:, 0] - exact)) < 1e-4


COLLIDE_CASES = [
    (["--m1", "1", "--v1", "1e308,0", "--m2", "1", "--v2", "-1e308,0"], ["double precision"]),
    (["--m1", "nan", "--v1", "1,0", "--m2", "1"], ["--m1"]),
    (["--m1", "1", "--v1", "nan,0", "--m2", "1"], ["--v1"]),
    (["--m1", "1", "--v1", "1,0", "--m2", "1", "--e", "inf"], ["restitution"]),
]


@pytest.mark.parametrize(("options", "phrases"), COLLIDE_CASES,
                         ids=[" ".join(c[0]) for c in COLLIDE_CASES])
def test_a_bad_collision_is_one_line_exit_2(options, phrases):
    assert_bad_input(run_limited("collide", *options), *phrases)


BATCH_CASES = [
    (["--timeout", "1e308"], ["--timeout", "a week"]),
    (["--timeout", "nan"], ["--timeout", "finite"]),
    (["--down", "0,0,0", "--check"], ["--down", "zero vector"]),
    (["--require-tilt", "100", "--check"], ["--require-tilt", "0 to 90"]),
    (["--material", ""], ["--material", "empty"]),
    (["--toward", "nan", "--tilt", "5", "--check"], ["--toward", "finite"]),
]


@pytest.mark.parametrize(("options", "phrases"), BATCH_CASES,
                         ids=[" ".join(c[0]) for c in BATCH_CASES])
def test_a_bad_batch_option_is_refused_before_any_file(tmp_path, block, options, phrases):
    out = tmp_path / "rows.csv"
    assert_bad_input(run_limited("batch", block, "--out", out, *options), *phrases)
    assert not out.exists()


def test_a_batch_output_in_a_missing_folder_is_refused_before_any_file(tmp_path, block):
    assert_bad_input(run_limited("batch", block, "--out", tmp_path / "nowhere" / "rows.csv"),
                     "--out", "folder does not exist")


def test_a_material_search_that_matches_nothing_is_not_a_failed_requirement():
    outcome = run_limited("materials", "grnite")
    assert outcome.status == 0, outcome.stderr
    assert outcome.stdout.startswith("no material matches 'grnite'; try granite")
    listed = run_limited("materials", "unobtainium", "--json")
    assert listed.status == 0 and json.loads(listed.stdout)["materials"] == []


CONTROL = "a\x1b[31m\x07b"


def test_a_file_name_with_control_characters_is_escaped_in_the_error(tmp_path):
    line = assert_bad_input(run_limited("mass", tmp_path / f"{CONTROL}.stl"), "no such file")
    assert "\x1b" not in line and "\x07" not in line
    assert "a\\x1b[31m\\x07b.stl" in line


def test_a_file_name_with_control_characters_is_escaped_in_the_report(tmp_path):
    path = tmp_path / f"{CONTROL}.wkt"
    path.write_text(PLATE)
    for command in ("mass", "check", "lift"):
        outcome = run_limited(command, path, "--units", "m")
        assert outcome.status == 0, outcome.stderr
        assert "\x1b" not in outcome.stdout + outcome.stderr
        assert "\x07" not in outcome.stdout + outcome.stderr
        assert "a\\x1b[31m\\x07b" in outcome.stdout


def test_part_names_with_control_characters_are_escaped(tmp_path):
    spec = tmp_path / "parts.toml"
    spec.write_text('[shape]\nkind = "assembly"\n'
                    '[[part]]\nname = "left\\u001b[2Jwipe"\ntype = "sphere"\nradius = 1\n'
                    'material = "oak"\n'
                    '[[part]]\nname = "right\\nforged line"\ntype = "sphere"\nradius = 1\n'
                    'at = [5, 0, 0]\nmaterial = "steel"\n')
    outcome = run_limited("mass", spec)
    assert outcome.status == 0, outcome.stderr
    assert "left\\x1b[2Jwipe" in outcome.stdout and "right\\nforged line" in outcome.stdout
    assert "\x1b" not in outcome.stdout and "\nforged line" not in outcome.stdout
    data = json.loads(run_limited("mass", spec, "--json").stdout)  # JSON escapes its own way
    assert [p["name"] for p in data["part_properties"]] == ["left\x1b[2Jwipe",
                                                            "right\nforged line"]


def test_an_unknown_material_with_control_characters_is_escaped(block):
    line = assert_bad_input(run_limited("mass", block, "--material", "oak\x1b[0m"),
                            "unknown material")
    assert "\x1b" not in line


@pytest.mark.parametrize(("error", "phrase"), [(RecursionError("maximum recursion depth"),
                                                "nested too deeply"),
                                               (MemoryError(), "too large for this machine")])
def test_recursion_and_memory_errors_are_one_clear_line_status_3(monkeypatch, capsys, error,
                                                                 phrase):
    """A limit that was not checked is a bug (3), said in words, never a traceback."""
    from plumbob import cli

    def broken(args):
        raise error

    _break_mass(monkeypatch, broken)
    monkeypatch.delenv("PLUMBOB_DEBUG", raising=False)
    assert cli.main(["mass", "shapes/block.toml"]) == cli.INTERNAL_ERROR
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and phrase in err and "plumbob.limits" in err


def test_an_internal_error_message_is_escaped(monkeypatch, capsys):
    from plumbob import cli

    def broken(args):
        raise KeyError("part\x1b[2J")

    _break_mass(monkeypatch, broken)
    monkeypatch.delenv("PLUMBOB_DEBUG", raising=False)
    assert cli.main(["mass", "shapes/block.toml"]) == cli.INTERNAL_ERROR
    err = capsys.readouterr().err
    assert "\x1b" not in err and "KeyError" in err


def _break_mass(monkeypatch, broken) -> None:
    """Make ``plumbob mass`` run ``broken`` (as an unforeseen bug would)."""
    from plumbob import cli
    from plumbob.commands import mass

    monkeypatch.setattr(mass, "run", broken)
    parser = cli.build_parser("mass")
    monkeypatch.setattr(cli, "build_parser", lambda command=None: parser)


def test_standard_output_is_escaped_even_where_a_report_forgot(monkeypatch, capsys):
    """The last line of defence: a command printing a raw name still cannot drive the
    terminal; newlines (the layout) pass."""
    from plumbob import cli

    def careless(args):
        print("title: part\x1b[2Jname\nsecond line\x07")
        return 0

    _break_mass(monkeypatch, careless)
    assert cli.main(["mass", "shapes/block.toml"]) == 0
    assert capsys.readouterr().out == "title: part\\x1b[2Jname\nsecond line\\x07\n"


@settings(max_examples=200, deadline=None)
@given(st.lists(st.sampled_from(["a", "é", "m³", " ", "\n", "\x1b", "\x07", "\t", "\r", "\x00",
                                 "\u2028", "{", '"']), max_size=30).map("".join))
def test_the_escaping_stream_writes_each_line_as_printable_gives_it(text):
    """What the commands' standard output writes: each line as :func:`printable` gives it,
    lines printable or not (the fast path for text all printable but its newlines)."""
    import io

    from plumbob.cli import _Escaping
    from plumbob.errors import printable

    out = io.StringIO()
    _Escaping(out).write(text)
    assert out.getvalue() == "\n".join(printable(line) for line in text.split("\n"))
