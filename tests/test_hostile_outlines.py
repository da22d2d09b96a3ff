"""Hostile 2-D outlines: spec polygons, CSV, GeoJSON, DXF and SVG files that once gave a
silent wrong number, a traceback or a hang. Each case is written into ``tmp_path`` and
run as a user would (``python -m plumbob``, 10 s, 1 GiB): one line and exit 2, or the
right answer (checked against a closed form)."""

from __future__ import annotations

import json

import ezdxf
import pytest
from hostile import assert_bad_input, run_limited

SQUARE = "[[0, 0], [4, 0], [4, 4], [0, 4]]"


def _spec(tmp_path, part: str) -> str:
    path = tmp_path / "shape.toml"
    path.write_text(f'[[part]]\nname = "plate"\n{part}\n')
    return str(path)


# ------------------------------------------------------------------ spec polygons
SPEC_POLYGONS = {
    "bow-tie": ('type = "polygon"\nvertices = [[0, 0], [2, 0], [0, 1], [2, 1]]',
                ("part 1 (plate)", "crosses itself", "(1, 0.5)")),
    "hole outside": (f'type = "polygon"\nvertices = {SQUARE}\n'
                     'holes = [[[5, 5], [6, 5], [6, 6], [5, 6]]]',
                     ("part 1 (plate)", "hole outside its outer boundary")),
    "crossing holes": (f'type = "polygon"\nvertices = {SQUARE}\n'
                       'holes = [[[1, 1], [2, 1], [2, 2], [1, 2]], '
                       '[[1.5, 1.5], [3, 1.5], [3, 3], [1.5, 3]]]',
                       ("part 1 (plate)", "hole 2 crosses or touches hole 1")),
    "nested holes": (f'type = "polygon"\nvertices = {SQUARE}\n'
                     'holes = [[[1, 1], [3, 1], [3, 3], [1, 3]], '
                     '[[1.5, 1.5], [2.5, 1.5], [2.5, 2.5], [1.5, 2.5]]]',
                     ("part 1 (plate)", "hole inside another hole")),
    "hole across the edge": (f'type = "polygon"\nvertices = {SQUARE}\n'
                             'holes = [[[3, 1], [5, 1], [5, 2], [3, 2]]]',
                             ("hole 1 crosses or touches the outer boundary",)),
    "flat hole": (f'type = "polygon"\nvertices = {SQUARE}\nholes = [[[1, 1], [2, 1], [3, 1]]]',
                  ("hole 1 has zero area",)),
    "twisted outline": ('type = "outline"\nvertices = [[0, 0], [2, 0], [0, 1], [2, 1]]\n'
                        'bulges = [0.2, 0, 0, 0]', ("part 1 (plate)", "crosses itself")),
    "bulge 1e300": ('type = "outline"\nvertices = [[0, 0], [1, 0], [1, 1]]\n'
                    'bulges = [1e300, 0, 0]', ("part 1 (plate)", "bulge of 1e+300")),
    "pyramid on a bow-tie": ('type = "pyramid"\nbase = [[0, 0], [2, 0], [0, 1], [2, 1]]\n'
                             'height = 1', ("part 1 (plate)", "the base crosses itself")),
}


@pytest.mark.parametrize("case", list(SPEC_POLYGONS))
def test_spec_polygon_defects_are_named(tmp_path, case):
    part, phrases = SPEC_POLYGONS[case]
    assert_bad_input(run_limited("mass", _spec(tmp_path, part)), *phrases)


# ------------------------------------------------------------------ CSV
CSV_ROWS = {
    "units in the first row": ("0mm,0mm\n1,0\n1,1\n0,1\n", ("line 1", "'0mm,0mm'")),
    "nan in the first row": ("nan,0\n1,0\n1,1\n0,1\n", ("line 1", "not a finite number")),
    "inf after a header": ("x,y\n0,0\n1,inf\n0,1\n", ("line 3", "not a finite number")),
    "three columns": ("x,y\n0,0,0\n1,0,0\n0,1,0\n", ("line 2", "not two numbers")),
    "two points": ("0,0\n1,1\n", ("ring 1", "only 2 points")),
}


@pytest.mark.parametrize("case", list(CSV_ROWS))
def test_csv_data_is_never_dropped_as_a_header(tmp_path, case):
    text, phrases = CSV_ROWS[case]
    path = tmp_path / "ring.csv"
    path.write_text(text)
    assert_bad_input(run_limited("mass", path), *phrases)


def test_3000_identical_outlines_are_one_lamina_promptly(tmp_path):
    path = tmp_path / "same.csv"
    path.write_text("\n\n".join(["0,0\n2,0\n2,1\n0,1"] * 3000))
    outcome = run_limited("mass", path, "--json")
    assert outcome.status == 0, outcome.stderr
    assert json.loads(outcome.stdout)["area"] == 2.0
    assert "dropped 2999 duplicate outline(s)" in outcome.stderr


def test_outlines_nested_3000_deep_are_refused_before_the_work(tmp_path):
    path = tmp_path / "rings.csv"
    path.write_text("\n\n".join(f"{-i},{-i}\n{i},{-i}\n{i},{i}\n{-i},{i}" for i in range(1, 3001)))
    assert_bad_input(run_limited("mass", path), "pairs of outlines", "limit")


# ------------------------------------------------------------------ GeoJSON
GEOJSON_RINGS = {
    "booleans": ("[[true, false], [1, 0], [1, 1], [true, false]]", ("true, not a number",)),
    "strings": ('[["0", "0"], [1, 0], [1, 1], ["0", "0"]]', ('"0", not a number',)),
    "null": ("[[null, 0], [1, 0], [1, 1], [0, 0]]", ("null, not a number",)),
    "NaN": ("[[NaN, 0], [1, 0], [1, 1], [0, 0]]", ("not a finite number",)),
    "Infinity": ("[[0, 0], [Infinity, 0], [1, 1], [0, 0]]", ("not a finite number",)),
    "huge integer": (f"[[0, 0], [1{'0' * 400}, 0], [1, 1], [0, 0]]", ("too large",)),
}


@pytest.mark.parametrize("case", list(GEOJSON_RINGS))
def test_geojson_coordinates_must_be_numbers(tmp_path, case):
    ring, phrases = GEOJSON_RINGS[case]
    path = tmp_path / "shape.geojson"
    path.write_text(f'{{"type": "Polygon", "coordinates": [{ring}]}}')
    assert_bad_input(run_limited("mass", path), *phrases)


def test_geojson_nested_too_deep(tmp_path):
    path = tmp_path / "deep.geojson"
    doc = '{"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [1, 1], [0, 0]]]}'
    for _ in range(100):
        doc = f'{{"type": "GeometryCollection", "geometries": [{doc}]}}'
    path.write_text(doc)
    assert_bad_input(run_limited("mass", path), "nesting depth")


# ------------------------------------------------------------------ DXF
def _dxf(tmp_path, build, name="d.dxf") -> str:
    doc = ezdxf.new()
    doc.header["$INSUNITS"] = 6
    build(doc, doc.modelspace())
    path = tmp_path / name
    doc.saveas(path)
    return str(path)


def _fan_out(doc, msp):  # block k places block k-1 ten times: 10⁷ triangles from ~25 KB
    doc.blocks.new("B0").add_lwpolyline([(0, 0), (1, 0), (1, 1)], close=True)
    for k in range(1, 8):
        block = doc.blocks.new(f"B{k}")
        for i in range(10):
            block.add_blockref(f"B{k - 1}", (i * 3**k, 0))
    msp.add_blockref("B7", (0, 0))


def _self_reference(doc, msp):
    block = doc.blocks.new("A")
    block.add_lwpolyline([(0, 0), (1, 0), (1, 1)], close=True)
    block.add_blockref("A", (2, 0))
    msp.add_blockref("A", (0, 0))


def _huge_array(doc, msp):
    doc.blocks.new("SQ").add_lwpolyline([(0, 0), (1, 0), (1, 1), (0, 1)], close=True)
    msp.add_blockref("SQ", (0, 0)).grid(size=(30000, 30000), spacing=(2, 2))


DXF_BLOCKS = {
    "nested INSERT fan-out": (_fan_out, ("block copies", "limit")),
    "block inside itself": (_self_reference, ("block 'A'", "itself")),
    "MINSERT of 9e8 copies": (_huge_array, ("block copies 900000000", "limit")),
}


@pytest.mark.parametrize("case", list(DXF_BLOCKS))
def test_dxf_block_expansion_is_counted_before_it_is_done(tmp_path, case):
    build, phrases = DXF_BLOCKS[case]
    assert_bad_input(run_limited("mass", _dxf(tmp_path, build)), *phrases)


def _patched(tmp_path, find: str, replace: str, after: str = "") -> str:
    """A small DXF with one group's text replaced (ezdxf will not write bad numbers)."""
    path = _dxf(tmp_path, lambda doc, msp: msp.add_lwpolyline(
        [(0, 0, 0), (1, 0, 0), (1, 1, 0)], format="xyb", close=True), name="base.dxf")
    text = open(path).read()
    start = text.index(after) if after else 0
    assert find in text[start:]
    text = text[:start] + text[start:].replace(find, replace, 1)
    bad = tmp_path / "bad.dxf"
    bad.write_text(text)
    return str(bad)


@pytest.mark.parametrize("value, phrases", [
    ("1e999", ("$INSUNITS", "'1e999' is not a whole number")),
    ("99", ("$INSUNITS = 99", "no unit code")),
])
def test_dxf_bad_insunits(tmp_path, value, phrases):
    path = _patched(tmp_path, "$INSUNITS\n 70\n6\n", f"$INSUNITS\n 70\n{value}\n")
    line = assert_bad_input(run_limited("mass", path), *phrases[1:])
    assert "line" in line or "$INSUNITS" in line


@pytest.mark.parametrize("value, shown", [("1e999", "inf"), ("nan", "nan"), ("4.5", "4.5")])
def test_dxf_insunits_as_a_float_is_refused_in_one_line(tmp_path, value, shown):
    """$INSUNITS written with a float's group code (40): ezdxf reads 1e999 as inf, which
    int() cannot convert (an OverflowError, exit 3, before)."""
    path = _patched(tmp_path, "$INSUNITS\n 70\n6\n", f"$INSUNITS\n 40\n{value}\n")
    assert_bad_input(run_limited("mass", path), "bad.dxf", f"$INSUNITS = {shown}",
                     "no unit code", "--units")


@pytest.mark.parametrize("bulge, phrases", [
    ("1e300", ("bulge of 1e+300",)),
    ("1e999", ("not a finite number",)),
    ("nan", ("not a finite number",)),
])
def test_dxf_absurd_bulges(tmp_path, bulge, phrases):
    path = _patched(tmp_path, " 10\n1.0\n 20\n0.0\n", f" 10\n1.0\n 20\n0.0\n 42\n{bulge}\n",
                    after="AcDbPolyline")
    assert_bad_input(run_limited("mass", path), "LWPOLYLINE", *phrases)


# ------------------------------------------------------------------ SVG
def _svg(tmp_path, body: str, name="d.svg") -> str:
    path = tmp_path / name
    path.write_text('<svg xmlns="http://www.w3.org/2000/svg" '
                    f'xmlns:xlink="http://www.w3.org/1999/xlink">{body}</svg>')
    return str(path)


def _use_fan_out(levels: int = 10) -> str:
    parts = ['<defs><path id="l0" d="M0 0 L1 0 L1 1 Z"/>']
    for k in range(1, levels + 1):
        uses = "".join(f'<use xlink:href="#l{k - 1}" x="{i}"/>' for i in range(10))
        parts.append(f'<g id="l{k}">{uses}</g>')
    return "".join(parts) + f'</defs><use href="#l{levels}"/>'


def _use_chain(depth: int, top_first: bool = False) -> str:
    """A chain of ``<use>`` ``depth`` long; ``top_first``: the outermost defined first, so a
    walk of the document meets the whole chain at once."""
    links = [f'<g id="l{k}"><use href="#l{k - 1}"/></g>' for k in range(1, depth + 1)]
    links = links[::-1] if top_first else links
    return ('<defs><path id="l0" d="M0 0 L1 0 L1 1 Z"/>' + "".join(links)
            + f'</defs><use href="#l{depth}"/>')


SVG_USES = {
    "10 levels of ten <use>": (_use_fan_out(), ("<use> copies", "limit")),
    "<use> inside what it uses": ('<g id="a"><rect width="1" height="1"/><use href="#a"/></g>',
                                  ("'#a'", "endless loop")),
    "<use> chain 100 deep": (_use_chain(100), ("<use> nesting depth", "limit")),
    "<use> chain 5000 deep": (_use_chain(5000, top_first=True), ("<use> nesting depth", "limit")),
}


@pytest.mark.parametrize("case", list(SVG_USES))
def test_svg_use_expansion_is_counted_before_it_is_done(tmp_path, case):
    body, phrases = SVG_USES[case]
    path = _svg(tmp_path, body)
    assert len(open(path, "rb").read()) < 200_000
    assert_bad_input(run_limited("mass", path), *phrases)


def test_svg_entity_bomb_is_refused_by_defusedxml(tmp_path):
    path = tmp_path / "bomb.svg"
    path.write_text('<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY a "aaaaaaaaaa">'
                    '<!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">]>'
                    '<svg xmlns="http://www.w3.org/2000/svg"><text>&b;</text></svg>')
    assert_bad_input(run_limited("mass", path), "entities")


def test_svg_t_standing_on_its_stem_rests_on_its_stem(tmp_path):
    """SVG's y runs down the page; a T drawn with its stem at the bottom of the page stands
    on the stem's end: support [40, 60] mm at the bottom, centre of mass 52.857 mm above it
    (bar 80 × 20 mm centred 70 mm up, stem 20 × 60 mm centred 30 mm up)."""
    path = tmp_path / "t.svg"
    path.write_text('<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" '
                    'viewBox="0 0 100 100"><path d="M 10 10 H 90 V 30 H 60 V 90 H 40 V 30 '
                    'H 10 Z"/></svg>')
    outcome = run_limited("check", path, "--json")
    assert outcome.status == 0, outcome.stderr
    result = json.loads(outcome.stdout)
    support = sorted(x for x, _ in result["support_polygon"])
    assert support == pytest.approx([0.040, 0.060], abs=1e-15)
    assert [y for _, y in result["support_polygon"]] == pytest.approx([-0.090] * 2, abs=1e-15)
    height = (1600 * 70 + 1200 * 30) / 2800 * 1e-3
    assert result["com_height"] == pytest.approx(height, rel=1e-12)
    assert result["verdict"] == "stands"


def _deep_chain(doc, msp):  # 100 blocks, each placing the next once
    doc.blocks.new("C0").add_lwpolyline([(0, 0), (1, 0), (1, 1)], close=True)
    for k in range(1, 101):
        doc.blocks.new(f"C{k}").add_blockref(f"C{k - 1}", (1, 0))
    msp.add_blockref("C100", (0, 0))


def test_dxf_blocks_nested_past_the_depth_limit(tmp_path):
    assert_bad_input(run_limited("mass", _dxf(tmp_path, _deep_chain)), "block nesting depth")


def _missing_block(doc, msp):
    msp.add_blockref("NOPE", (0, 0))
    msp.add_circle((0, 0), 1)


def test_dxf_reference_to_a_missing_block_is_not_dropped_silently(tmp_path):
    assert_bad_input(run_limited("mass", _dxf(tmp_path, _missing_block)), "INSERT",
                     "without required BLOCK")


@pytest.mark.parametrize("shape", ['<circle r="-1"/>', '<ellipse rx="1" ry="-2"/>',
                                   '<rect width="-2" height="1"/>'])
def test_svg_negative_sizes_are_errors_not_their_magnitudes(tmp_path, shape):
    assert_bad_input(run_limited("mass", _svg(tmp_path, shape)), "is negative")


# ------------------------------------------------------------------ WKT, WKB
TRIANGLE_WKT = "POLYGON ((0 0, 1 0, 1 1, 0 0))"


def _nested_wkb(levels: int) -> bytes:
    import struct

    import shapely

    return struct.pack("<BII", 1, 7, 1) * levels + shapely.from_wkt(TRIANGLE_WKT).wkb


NESTED = {  # GEOS parses collections recursively in C: these once killed the process
    "deep.wkt": ("GEOMETRYCOLLECTION (" * 100_000 + TRIANGLE_WKT + ")" * 100_000).encode(),
    "deep.wkb": _nested_wkb(100_000),
    "deep_hex.wkb": _nested_wkb(100_000).hex().encode(),
}


@pytest.mark.parametrize("name", list(NESTED))
def test_geometry_collections_nested_deep_are_refused_not_a_crash(tmp_path, name):
    path = tmp_path / name
    path.write_bytes(NESTED[name])
    assert_bad_input(run_limited("mass", path), "geometry nesting depth", "limit")


@pytest.mark.parametrize("name, data", [
    ("ok.wkt", f"GEOMETRYCOLLECTION (GEOMETRYCOLLECTION ({TRIANGLE_WKT}))".encode()),
    ("ok.wkb", _nested_wkb(3)),
])
def test_geometry_collections_nested_a_little_are_read(tmp_path, name, data):
    path = tmp_path / name
    path.write_bytes(data)
    outcome = run_limited("mass", path, "--json")
    assert outcome.status == 0, outcome.stderr
    assert json.loads(outcome.stdout)["area"] == 0.5


def _curve_wkb() -> bytes:
    import struct

    points = [(0, 0), (1, 1), (2, 0), (1, -1), (0, 0)]
    ring = struct.pack("<BII", 1, 8, len(points)) + b"".join(struct.pack("<dd", *p)
                                                           for p in points)
    return struct.pack("<BII", 1, 10, 1) + ring  # CURVEPOLYGON (CIRCULARSTRING …)


WKT_WKB = {
    "curve.wkt": (b"CURVEPOLYGON (CIRCULARSTRING (0 0, 1 1, 2 0, 1 -1, 0 0))", ("curved",)),
    "curve.wkb": (_curve_wkb(), ("curved",)),
    "overflow.wkt": (b"POLYGON ((0 0, 1e400 0, 1 1, 0 0))", ("not a finite number",)),
    "truncated.wkb": (_nested_wkb(0)[:30], ("not valid WKB",)),
}


@pytest.mark.parametrize("name", list(WKT_WKB))
def test_wkt_wkb_that_shapely_cannot_take(tmp_path, name):
    data, phrases = WKT_WKB[name]
    path = tmp_path / name
    path.write_bytes(data)
    assert_bad_input(run_limited("mass", path), *phrases)


def _same_circles(doc, msp):
    for _ in range(3000):
        msp.add_circle((0, 0), 1)


def _nested_circles(doc, msp):
    for radius in range(1, 3001):
        msp.add_circle((0, 0), radius)


def test_3000_identical_circles_are_one_disc_promptly(tmp_path):
    import math

    outcome = run_limited("mass", _dxf(tmp_path, _same_circles), "--json")
    assert outcome.status == 0, outcome.stderr
    assert json.loads(outcome.stdout)["area"] == pytest.approx(math.pi, rel=1e-15)
    assert "dropped 2999 duplicate outline(s)" in outcome.stderr


def test_3000_nested_circles_are_refused_before_they_are_flattened(tmp_path):
    assert_bad_input(run_limited("mass", _dxf(tmp_path, _nested_circles)), "pairs of outlines")


@pytest.mark.parametrize("depth", [300, 3000])
def test_svg_groups_nested_too_deeply_are_refused_by_a_named_limit(tmp_path, depth):
    """svgelements follows groups by recursion and once ended in a bare RecursionError
    near 1 000 levels: the depth is counted first, without recursion."""
    body = "<g>" * depth + '<rect width="5" height="5"/>' + "</g>" * depth
    assert_bad_input(run_limited("mass", _svg(tmp_path, body)),
                     "depth of its element tree", "limit of 256", "ungroup")


def test_svg_groups_nested_a_little_deeply_are_read(tmp_path):
    body = "<g>" * 200 + '<rect width="4" height="5"/>' + "</g>" * 200
    result = run_limited("mass", _svg(tmp_path, body), "--json", "--units", "mm")
    assert result.status == 0, result.stderr
    assert json.loads(result.stdout)["area"] == pytest.approx(20e-6, rel=1e-12)


def test_the_vectorised_screen_misses_no_polygon_that_validity_refuses():
    """A file of many polygons asks ``validity_error`` (one polygon at a time) only for
    those ``suspects`` flags: so every polygon it would refuse must be flagged."""
    import shapely

    from plumbob.bodies.validity import suspects, validity_error

    square = [(0, 0), (1, 0), (1, 1), (0, 1)]
    cases = [shapely.Polygon(square),
             shapely.Polygon([(0, 0), (2, 2), (2, 0), (0, 2)]),  # a bow-tie
             shapely.Polygon([(0, 0), (1, 1), (2, 2)]),  # on a line
             shapely.Polygon(square, [[(2, 2), (3, 2), (3, 3)]]),  # a hole outside
             shapely.Polygon([(0, 0), (4, 0), (4, 4), (0, 4)],
                             [[(1, 1), (3, 1), (3, 3), (1, 3)], [(1.5, 1.5), (2, 1.5), (2, 2)]]),
             shapely.Polygon([(0, 0), (4, 0), (4, 4), (0, 4)], [[(1, 1), (2, 2), (3, 3)]]),  # flat hole
             shapely.MultiPolygon([shapely.box(0, 0, 2, 2), shapely.box(1, 1, 3, 3)]),  # overlap
             shapely.MultiPolygon([shapely.box(0, 0, 1, 1), shapely.box(2, 0, 3, 1)]),
             shapely.Polygon([(0, 0), (1e-9, 0), (1e-9, 1e-9), (0, 1e-9)]),  # tiny, but a square
             shapely.Polygon([(0, 0), (1, 0), (1, 1e-16), (0, 1e-16)])]  # a sliver of no area
    flagged = suspects(cases)
    refused = [validity_error(g, "p") is not None for g in cases]
    assert refused == [False, True, True, True, True, True, True, False, False, True]
    assert all(flagged[refused]), (flagged, refused)
    assert not flagged[0] and not flagged[7] and not flagged[8]  # the good ones cost nothing
