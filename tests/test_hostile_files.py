"""Hostile inputs that are not files at all: pipes, devices, folders."""

from __future__ import annotations

import os

import pytest
from hostile import assert_bad_input, run_limited


@pytest.mark.parametrize("command", ["mass", "check", "poses"])
def test_a_fifo_is_refused_without_blocking(tmp_path, command):
    fifo = tmp_path / "part.stl"
    os.mkfifo(fifo)
    assert_bad_input(run_limited(command, fifo), "pipe", "not a regular file")


@pytest.mark.parametrize("name", ["part.stl", "spec.toml", "outline.svg"])
def test_dev_zero_behind_a_link_is_refused(tmp_path, name):
    link = tmp_path / name
    link.symlink_to("/dev/zero")
    assert_bad_input(run_limited("mass", link), "device", "not a regular file")


def test_a_folder_is_refused(tmp_path):
    folder = tmp_path / "part.stl"
    folder.mkdir()
    assert_bad_input(run_limited("mass", folder), "folder")


def test_a_shipped_example_runs_inside_the_limits(shapes_dir):
    outcome = run_limited("mass", os.path.join(shapes_dir, "sculpture.toml"))
    assert outcome.status == 0, outcome.stderr
    assert "centre of mass" in outcome.stdout.lower() or "center" in outcome.stdout.lower()
