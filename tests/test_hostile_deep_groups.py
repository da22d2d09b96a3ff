"""Groups nested 300 deep are a legitimate spec (issue 20, item 6): the nesting limit
bounds the work of reading and building (MAX_SPEC_NESTING), not how deep an assembly's
groups may go. Each group here moves its contents 1 mm: the square ends 0.3 m along x."""

from __future__ import annotations

import json

from hostile import run_limited


def test_groups_nested_300_deep_are_read_and_placed(tmp_path):
    depth = 300
    lines = ['[shape]\nkind = "lamina"\n']
    for level in range(1, depth + 1):
        lines.append("[[" + ".".join(["part"] * level) + "]]\nat = [0.001, 0]\n")
    lines.append("[[" + ".".join(["part"] * (depth + 1)) + ']]\ntype = "rectangle"\n'
                 "width = 1\nheight = 1\n")
    path = tmp_path / "deep.toml"
    path.write_text("".join(lines))
    outcome = run_limited("mass", path, "--json")
    assert outcome.status == 0, outcome.stderr
    out = json.loads(outcome.stdout)
    # 300 moves of 1 mm: 0.3 + 0.5 (the square's centre). Each move rounds every
    # coordinate (|x| < 1.3) by at most half an ulp, so corners, centre and area carry at
    # most ~depth ulps: 4 × depth × eps allows for the area's products.
    tolerance = 4 * depth * 2.2e-16
    assert abs(out["center_of_mass"][0] - 0.8) < tolerance
    assert abs(out["center_of_mass"][1] - 0.5) < tolerance
    assert abs(out["area"] - 1.0) < tolerance
