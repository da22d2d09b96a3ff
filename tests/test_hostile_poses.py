"""Hostile `plumbob poses` option values: one line, exit 2, never a traceback or a hang."""

import os

import pytest
from conftest import ROOT
from hostile import assert_bad_input, run_limited

BLOCK = os.path.join(ROOT, "shapes", "block.toml")


@pytest.mark.parametrize(("args", "phrases"), [
    (["--top", "0"], ("--top", "at least 1")),
    (["--min-probability", "1.5"], ("--min-probability", "at most 1")),
    (["--min-probability", "nan"], ("--min-probability",)),
    (["--roll-angle", "-1"], ("--roll-angle", "negative")),
    (["--export-format", "obj", "--export", "out"], ("--export-format",)),
])
def test_bad_option_values(tmp_path, args, phrases):
    assert_bad_input(run_limited("poses", BLOCK, *args, cwd=tmp_path), *phrases)


def test_export_into_a_file_is_a_clear_error(tmp_path):
    (tmp_path / "taken").write_text("not a folder")
    outcome = run_limited("poses", BLOCK, "--export", str(tmp_path / "taken"), cwd=tmp_path)
    assert_bad_input(outcome, "it is a file, not a folder")


def test_a_lamina_has_no_mesh_to_export(tmp_path):
    sculpture = os.path.join(ROOT, "shapes", "sculpture.toml")
    outcome = run_limited("poses", sculpture, "--export", str(tmp_path / "x"), cwd=tmp_path)
    assert_bad_input(outcome, "lamina", "no surface of triangles")
    assert not (tmp_path / "x").exists()
