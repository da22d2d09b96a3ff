"""What a person types by mistake gets an answer that fixes it: a folder given as a
file, a mistyped option or command, and the poses table that says once what it left out."""

from __future__ import annotations

import json
import os

import pytest
from conftest import SHAPES

from plumbob.cli import main


def _refused(capsys, argv: list[str]) -> str:
    """The one stderr line of a refused command line (exit 2)."""
    try:
        status = main(argv)
    except SystemExit as stop:  # argparse refuses before any command runs
        status = stop.code
    assert status == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    return err.strip()


def test_a_folder_as_path_points_at_batch(capsys):
    err = _refused(capsys, ["mass", SHAPES])
    assert "is a folder" in err and "plumbob batch" in err and "unknown file type" not in err


@pytest.mark.parametrize(("typed", "meant"), [("--requre-tilt", "--require-tilt"),
                                              ("--materal", "--material"),
                                              ("--jsn", "--json")])
def test_a_mistyped_option_gets_a_did_you_mean_and_the_subcommands_help(capsys, typed, meant):
    err = _refused(capsys, ["check", os.path.join(SHAPES, "block.toml"), typed, "10"])
    assert f"unrecognized argument {typed}; did you mean {meant}" in err
    assert "plumbob check --help" in err


def test_a_mistyped_command_gets_a_did_you_mean(capsys):
    err = _refused(capsys, ["chek", "x"])
    assert "did you mean check?" in err


def test_an_option_nothing_resembles_is_named_as_it_is(capsys):
    err = _refused(capsys, ["mass", os.path.join(SHAPES, "block.toml"), "--zzz"])
    assert "unrecognized arguments: --zzz" in err and "did you mean" not in err


def test_poses_top_says_once_what_it_left_out(capsys):
    """The block has 6 poses: --top 3 shows 3 and says once that 3 more are not shown;
    the JSON says it in ``more``, its probabilities adding up to 1 with those shown."""
    block = os.path.join(SHAPES, "block.toml")
    assert main(["poses", block, "--top", "3"]) == 0
    out = capsys.readouterr().out
    assert out.count("more pose(s)") == 1 and "3 more pose(s)" in out
    assert main(["poses", block, "--top", "3", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["more"]["poses"] == 3
    shown = sum(p["probability"] for p in result["poses"])
    assert shown + result["more"]["probability"] == pytest.approx(1.0, abs=1e-12)
    assert not any("more pose" in n for n in result.get("notes", []))


@pytest.mark.parametrize("columns", ["40", "120", ""])
def test_help_wraps_as_argparse_would(monkeypatch, columns):
    """plumbob finds the terminal's width without importing shutil (a command's start-up):
    the help it prints is argparse's own, at any width."""
    import argparse

    from plumbob.cli import build_parser

    monkeypatch.setenv("COLUMNS", columns)
    for name in ("poses", None):
        top = build_parser(name)
        parser = top._subcommand(name) if name else top
        ours = parser.format_help()
        monkeypatch.setattr(type(parser), "_get_formatter",
                            argparse.ArgumentParser._get_formatter)
        assert parser.format_help() == ours
        monkeypatch.undo()
        monkeypatch.setenv("COLUMNS", columns)
