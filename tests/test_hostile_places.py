"""Messages that name the file and the place (issue 20, item 6): a hole larger than its
body, a density field negative or NaN somewhere, a region of zero area. Each said what
was wrong but neither where nor in which file ("parts: the difference is empty: the parts
do not overlap", "density '1 - 3*x' is negative ...")."""

from __future__ import annotations

import pytest
from hostile import assert_bad_input, run_in_process

LAMINA = '[shape]\nkind = "lamina"\n{shape}\n'
SQUARE = '[[part]]\ntype = "rectangle"\nwidth = 1\nheight = 1\n'

CASES = {
    "a hole larger than its body": (
        LAMINA.format(shape="") + SQUARE + '[[part]]\ntype = "rectangle"\nwidth = 2\n'
        'height = 2\nop = "subtract"\n',
        ["part 2 (subtract)", "difference is empty", "covers all of the body"]),
    "a sphere removed from a smaller box": (
        '[shape]\nkind = "solid"\n[[part]]\ntype = "box"\nwidth = 1\nlength = 1\nheight = 1\n'
        '[[part]]\ntype = "sphere"\nradius = 5\nop = "subtract"\n',
        ["part 2 (subtract)", "covers all of the body"]),
    "parts 2 to 3 removed together": (
        LAMINA.format(shape="") + SQUARE + '[[part]]\ntype = "rectangle"\nwidth = 2\n'
        'height = 2\nop = "subtract"\n[[part]]\ntype = "disc"\nradius = 0.1\nop = "subtract"\n',
        ["part 2 to part 3 (subtract)", "covers all of the body"]),
    "an intersection of apart parts": (
        LAMINA.format(shape="") + SQUARE + SQUARE + 'at = [5, 5]\nop = "intersect"\n',
        ["part 2 (intersect)", "intersection is empty"]),
    "a negative density field": (LAMINA.format(shape='density = "1 - 3*x"') + SQUARE,
                                 ["shape.density", "'1 - 3*x' is negative", "at (1, 0)"]),
    "a NaN density field": ('[shape]\nkind = "solid"\ndensity = "sqrt(x - 0.5)"\n[[part]]\n'
                            'type = "box"\nwidth = 1\nlength = 1\nheight = 1\n',
                            ["shape.density", "not finite (nan"]),
    "a part's negative density field": (
        LAMINA.format(shape="") + SQUARE + 'density = "x - 0.5"\n',
        ["part 1.density", "'x - 0.5' is negative"]),
    "a polygon of zero area": (
        LAMINA.format(shape="") + '[[part]]\ntype = "polygon"\n'
        'vertices = [[0, 0], [1, 0], [2, 0]]\n', ["part 1", "zero area"]),
}


@pytest.mark.parametrize("case", list(CASES))
def test_the_message_names_the_file_and_the_place(tmp_path, capsys, case):
    text, phrases = CASES[case]
    path = tmp_path / "spec.toml"
    path.write_text(text)
    line = assert_bad_input(run_in_process(capsys, "mass", path), *phrases)
    assert line.startswith(f"plumbob: {path}: "), line


@pytest.mark.parametrize("name, text, phrases", [
    ("zero.wkt", "POLYGON ((0 0, 1 0, 2 0, 0 0))", ["the polygon has zero area"]),
    ("zero.csv", "0,0\n1,0\n2,0\n", ["ring 1 (line 1) has zero area"]),
    ("zero.geojson", '{"type":"FeatureCollection","features":[{"type":"Feature","properties":'
     '{"name":"flat"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[1,0],[2,0],[0,0]]]}},'
     '{"type":"Feature","properties":{"name":"ok"},"geometry":{"type":"Polygon","coordinates":'
     '[[[0,0],[1,0],[1,1],[0,0]]]}}]}', ["polygon 'flat' has zero area"]),
])
def test_a_zero_area_region_in_a_file_names_the_file_and_the_outline(tmp_path, capsys, name,
                                                                        text, phrases):
    path = tmp_path / name
    path.write_text(text)
    line = assert_bad_input(run_in_process(capsys, "mass", path), *phrases)
    assert line.startswith(f"plumbob: {path}: "), line
