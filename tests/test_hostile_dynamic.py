"""Hostile settings of ``plumbob poses --dynamic``: refused in one line, exit 2, before
any drop (or the quasi-static poses) is computed — inside the harness's 10 s."""

from __future__ import annotations

import os

import pytest
from hostile import assert_bad_input, run_limited


@pytest.mark.parametrize(("args", "phrases"), [
    (["--drops", "1000000000"], ["drops", "1000000000"]),
    (["--restitution", "2"], ["restitution", "0.95"]),
    (["--overdamped", "--drop-height", "1"], ["overdamped", "drop height"]),
    (["--seed", "-1"], ["--seed"]),
    (["--seed", "1.5"], ["--seed", "whole"]),
    (["--friction", "0"], ["--friction"]),
    (["--plot", "poses.png"], ["--plot", "--dynamic"]),
])
def test_bad_dynamic_settings_are_one_line(args, phrases, shapes_dir):
    outcome = run_limited("poses", os.path.join(shapes_dir, "block.toml"), "--dynamic", *args)
    assert_bad_input(outcome, *phrases)


@pytest.mark.parametrize("option", [["--drops", "5"], ["--overdamped"], ["--jobs", "2"]])
def test_a_dynamic_setting_alone_is_one_line(option, shapes_dir):
    outcome = run_limited("poses", os.path.join(shapes_dir, "block.toml"), *option)
    assert_bad_input(outcome, option[0], "--dynamic")


@pytest.mark.parametrize(("jobs", "phrase"), [(2.5, "whole number"), (0, "at least 1"),
                                              (float("nan"), "whole number"), ("two", "whole number")])
def test_drop_poses_refuses_a_jobs_count_that_is_not_a_whole_number(jobs, phrase):
    """Refused before any work, as a StabilityError naming the setting (a fractional
    count once reached the process pool)."""
    from plumbob.bodies.primitives import box
    from plumbob.errors import StabilityError
    from plumbob.stability import drop_poses

    with pytest.raises(StabilityError, match=phrase):
        drop_poses(box(1.0, 2.0, 3.0), drops=4, jobs=jobs)
