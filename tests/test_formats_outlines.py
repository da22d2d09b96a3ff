"""Laminas from SVG, DXF, GeoJSON, WKT, WKB and CSV, checked against closed forms."""

import json

import ezdxf
import numpy as np
import pytest
import shapely
from conftest import rel
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from plumbob.bodies.csg import Assembly
from plumbob.bodies.lamina import Lamina
from plumbob.errors import FormatError, GeometryError
from plumbob.formats import read

SVG = '<svg xmlns="http://www.w3.org/2000/svg"{attrs}>{body}</svg>'


def svg_file(tmp_path, body, attrs="", name="d.svg") -> str:
    path = tmp_path / name
    path.write_text(SVG.format(attrs=attrs, body=body))
    return str(path)


def dxf_file(tmp_path, build, units=6, name="d.dxf") -> str:
    doc = ezdxf.new()
    doc.header["$INSUNITS"] = units
    build(doc, doc.modelspace())
    path = tmp_path / name
    doc.saveas(path)
    return str(path)


def semicircle_props(a: float):
    """Area, centroid height and inertia (σ = 1) of the half disc y ≥ 0 of radius a."""
    area = np.pi * a * a / 2
    cy = 4 * a / (3 * np.pi)
    ixx = np.pi * a**4 / 8 - area * cy * cy
    iyy = np.pi * a**4 / 8
    return area, cy, np.diag([ixx, iyy, ixx + iyy])


def assert_semicircle(props, a):
    area, cy, inertia = semicircle_props(a)
    assert props.exact
    assert props.area == pytest.approx(area, rel=1e-14)
    assert abs(props.center_of_mass[1] - cy) <= 1e-12 * cy
    assert abs(props.center_of_mass[0]) <= 1e-15 * a
    assert rel(props.inertia, inertia) < 1e-12


# ------------------------------------------------------------------ exact curves
def test_semicircle_as_svg_arc_is_exact(tmp_path):
    a = 1.5
    # drawn above the x axis on the page (through y = −a, SVG's y runs down): y ≥ 0 when read
    path = svg_file(tmp_path, f'<path d="M {a} 0 A {a} {a} 0 0 0 -{a} 0 Z"/>')
    assert_semicircle(read(path, units="m").body.mass_properties(), a)


def test_semicircle_as_dxf_bulge_arc_and_line_is_exact(tmp_path):
    a = 1.5

    def bulge(doc, msp):
        msp.add_lwpolyline([(a, 0, 1.0), (-a, 0, 0.0)], format="xyb", close=True)

    def arc(doc, msp):
        msp.add_arc((0, 0), a, 0, 180)
        msp.add_line((-a, 0), (a, 0))

    for build in (bulge, arc):
        reading = read(dxf_file(tmp_path, build, name=f"{build.__name__}.dxf"))
        assert_semicircle(reading.body.mass_properties(), a)
        assert "units: meter (from the file)" in reading.notices


def test_quadratic_bezier_is_raised_exactly(tmp_path):
    # y = 1 - x² over [-1, 1]: area 4/3, centroid height 2/5, ∫y² dA = 32/105
    # drawn above the axis on the page (SVG's y runs down): y = 1 − x² when read, y up
    props = read(svg_file(tmp_path, '<path d="M -1 0 Q 0 -2 1 0 Z"/>'), units="m").body \
        .mass_properties()
    assert props.exact
    assert props.area == pytest.approx(4 / 3, rel=1e-14)
    assert props.center_of_mass == pytest.approx([0.0, 0.4], rel=1e-14, abs=1e-15)
    assert props.inertia[0, 0] == pytest.approx(32 / 105 - 4 / 3 * 0.16, rel=1e-13)


def test_cubic_bezier_from_svg_and_dxf_spline(tmp_path):
    # x = 3t² − 2t³, y = 3t(1 − t): area under it 18 ∫ t²(1−t)² dt = 3/5
    svg = read(svg_file(tmp_path, '<path d="M 0 0 C 0 1 1 1 1 0 Z"/>'), units="m").body

    def spline(doc, msp):
        msp.add_open_spline([(0, 0), (0, 1), (1, 1), (1, 0)], degree=3)
        msp.add_line((1, 0), (0, 0))

    dxf = read(dxf_file(tmp_path, spline)).body
    for body in (svg, dxf):
        props = body.mass_properties()
        assert props.exact
        assert props.area == pytest.approx(0.6, rel=1e-14)
        assert props.center_of_mass[0] == pytest.approx(0.5, rel=1e-14)


def test_rounded_rect_and_mirrored_circle(tmp_path):
    body = '<rect x="0" y="0" width="4" height="2" rx="0.5"/>' \
           '<circle cx="1" cy="2" r="1" transform="translate(10 0) scale(1,-1)"/>'
    reading = read(svg_file(tmp_path, body), units="m")
    parts = reading.body.parts
    rect, circle = (p.mass_properties() for p in parts)
    assert rect.exact and circle.exact
    assert rect.area == pytest.approx(8 - (4 - np.pi) * 0.25, rel=1e-14)
    assert rect.center_of_mass == pytest.approx([2.0, -1.0], rel=1e-14)  # y flipped up
    assert circle.area == pytest.approx(np.pi, rel=1e-14)
    assert circle.center_of_mass == pytest.approx([11.0, 2.0], rel=1e-14)


def test_elliptical_arcs_are_close_and_say_so(tmp_path):
    body = '<ellipse cx="0" cy="0" rx="3" ry="1" transform="rotate(20)"/>'
    props = read(svg_file(tmp_path, body), units="m").body.mass_properties()
    error = abs(props.area - 3 * np.pi) / (3 * np.pi)
    assert not props.exact
    assert error < 1e-10
    assert error <= props.relative_error < 1e-9
    assert any("elliptical arcs" in n for n in props.notes)
    # a circle squashed by a transform is an ellipse too
    squashed = read(svg_file(tmp_path, '<circle r="1" transform="scale(2 1)"/>', name="s.svg"),
                    units="m").body.mass_properties()
    assert squashed.area == pytest.approx(2 * np.pi, rel=1e-10) and not squashed.exact


# ------------------------------------------------------------------ SVG units and nesting
def test_svg_units_from_width_and_viewbox(tmp_path):
    square = '<rect x="10" y="10" width="10" height="10"/>'
    mm = svg_file(tmp_path, square, ' width="100mm" height="100mm" viewBox="0 0 100 100"')
    reading = read(mm)
    assert reading.body.mass_properties().area == pytest.approx(1e-4, rel=1e-14)
    assert any("one user unit is 1 mm" in n for n in reading.notices)
    inches = svg_file(tmp_path, square, ' width="2in" viewBox="0 0 200 200"', name="in.svg")
    assert read(inches).body.mass_properties().area == pytest.approx((0.254e-3 * 10) ** 2,
                                                                      rel=1e-14)
    bare = svg_file(tmp_path, square, name="bare.svg")
    reading = read(bare)
    assert reading.body.mass_properties().area == pytest.approx((10 * 0.0254 / 96) ** 2,
                                                                 rel=1e-14)
    assert any("no physical size" in n for n in reading.notices)
    assert read(mm, units="cm").body.mass_properties().area == pytest.approx(1e-2, rel=1e-14)


def test_even_odd_nesting_makes_holes_and_islands(tmp_path):
    body = ('<rect id="plate" x="0" y="0" width="10" height="10"/>'
            '<circle cx="5" cy="5" r="3"/>'
            '<rect id="island" x="4" y="4" width="2" height="2"/>')
    reading = read(svg_file(tmp_path, body), units="m")
    assert isinstance(reading.body, Assembly)
    parts = {p.name: p.mass_properties() for p in reading.body.parts}
    assert parts["plate"].area == pytest.approx(100 - 9 * np.pi, rel=1e-14)
    assert parts["plate"].center_of_mass == pytest.approx([5.0, -5.0], rel=1e-14)  # y up
    assert parts["island"].area == pytest.approx(4.0, rel=1e-14)


def test_subpaths_with_holes_in_one_path(tmp_path):
    d = "M 0 0 H 4 V 4 H 0 Z M 1 1 V 3 H 3 V 1 Z"  # the hole runs either way
    props = read(svg_file(tmp_path, f'<path d="{d}"/>'), units="m").body.mass_properties()
    assert props.area == pytest.approx(12.0, rel=1e-15)


# ------------------------------------------------------------------ DXF
def test_dxf_entities_and_units(tmp_path):
    def build(doc, msp):
        msp.add_circle((1, 2), 2)  # exact: two bulge arcs
        msp.add_line((10, 0), (14, 0))  # a stadium from lines and arcs
        msp.add_arc((14, 1), 1, 270, 90)
        msp.add_line((14, 2), (10, 2))
        msp.add_arc((10, 1), 1, 90, 270)
        msp.add_ellipse((30, 0), major_axis=(3, 0), ratio=0.5)

    reading = read(dxf_file(tmp_path, build, units=4))
    assert "units: millimeter (from the file)" in reading.notices
    circle, stadium, ellipse = sorted((p.mass_properties() for p in reading.body.parts),
                                      key=lambda m: m.center_of_mass[0])
    assert circle.exact and circle.area == pytest.approx(4 * np.pi * 1e-6, rel=1e-15)
    assert circle.center_of_mass == pytest.approx([1e-3, 2e-3], rel=1e-15)
    assert stadium.exact and stadium.area == pytest.approx((8 + np.pi) * 1e-6, rel=1e-14)
    assert stadium.center_of_mass == pytest.approx([12e-3, 1e-3], rel=1e-14)
    assert not ellipse.exact
    assert ellipse.area == pytest.approx(np.pi * 3 * 1.5 * 1e-6, rel=1e-10)


def test_dxf_mirrored_ocs_blocks_duplicates_and_leftovers(tmp_path):
    def build(doc, msp):
        msp.add_circle((2, 0), 1, dxfattribs={"extrusion": (0, 0, -1)})  # at x = −2 in WCS
        msp.add_lwpolyline([(0, 5, 0.5), (2, 5, 0), (2, 7, 0), (0, 7, 0)], format="xyb",
                           close=True, dxfattribs={"extrusion": (0, 0, -1)})
        block = doc.blocks.new("DISC")
        block.add_circle((0, 0), 1)
        msp.add_blockref("DISC", (10, 10))
        msp.add_circle((20, 0), 1)
        msp.add_circle((20, 0), 1)  # drawn twice
        msp.add_line((30, 0), (31, 1))  # a construction line

    reading = read(dxf_file(tmp_path, build))
    parts = [p.mass_properties() for p in reading.body.parts]
    centres = sorted(tuple(np.round(p.center_of_mass, 12)) for p in parts)
    assert (-2.0, 0.0) in centres and (10.0, 10.0) in centres and (20.0, 0.0) in centres
    assert len(parts) == 4
    mirrored = next(p for p in parts if p.center_of_mass[1] > 4)
    # a square whose bottom edge bulges outward (bulge 0.5 ⇒ sweep 4·atan 0.5)
    sweep = 4 * np.arctan(0.5)
    r = 1 / np.sin(sweep / 2)
    segment = r * r / 2 * (sweep - np.sin(sweep))
    assert mirrored.area == pytest.approx(4 + segment, rel=1e-14)
    assert mirrored.center_of_mass[0] < 0  # x mirrored into WCS
    assert any("duplicate" in n for n in reading.notices)
    assert any("ignored 1 open piece" in n for n in reading.notices)


def test_dxf_rational_spline_is_flattened_with_a_bound(tmp_path):
    def build(doc, msp):  # a quarter circle as a rational quadratic, closed by two lines
        w = np.sqrt(0.5)
        msp.add_rational_spline([(1, 0), (1, 1), (0, 1)], weights=[1, w, 1], degree=2)
        msp.add_line((0, 1), (0, 0))
        msp.add_line((0, 0), (1, 0))

    props = read(dxf_file(tmp_path, build)).body.mass_properties()
    assert not props.exact
    error = abs(props.area - np.pi / 4) / (np.pi / 4)
    assert error <= props.relative_error < 1e-6


# ------------------------------------------------------------------ polygon formats
def test_geojson_features_holes_and_names(tmp_path):
    doc = {"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"name": "house"}, "geometry": {
            "type": "Polygon", "coordinates": [[[0, 0], [10, 0], [10, 10], [0, 10], [0, 0]],
                                               [[2, 2], [2, 4], [4, 4], [4, 2], [2, 2]]]}},
        {"type": "Feature", "id": "sheds", "properties": {}, "geometry": {
            "type": "MultiPolygon", "coordinates": [[[[20, 0], [22, 0], [22, 1], [20, 1]]],
                                                    [[[30, 0], [31, 0], [31, 3], [30, 3]]]]}},
        {"type": "Feature", "properties": {}, "geometry": {
            "type": "LineString", "coordinates": [[0, 0], [1, 1]]}},
    ]}
    path = tmp_path / "site.geojson"
    path.write_text(json.dumps(doc))
    reading = read(str(path), units="ft")
    body = reading.body
    assert isinstance(body, Assembly)
    parts = {p.name: p.mass_properties() for p in body.parts}
    ft2 = 0.3048**2
    assert parts["house"].area == pytest.approx(96 * ft2, rel=1e-14)
    assert parts["house"].center_of_mass == pytest.approx(
        (np.array([5, 5]) * 100 - np.array([3, 3]) * 4) / 96 * 0.3048, rel=1e-14)
    assert parts["sheds"].area == pytest.approx(5 * ft2, rel=1e-14)
    assert any("ignored geometries without area (1 LineString)" in n for n in reading.notices)


def test_geojson_in_degrees_draws_a_notice(tmp_path):
    ring = [[13.4, 52.5], [13.4001, 52.5], [13.4001, 52.5001], [13.4, 52.5001], [13.4, 52.5]]
    path = tmp_path / "lonlat.geojson"
    path.write_text(json.dumps({"type": "Polygon", "coordinates": [ring]}))
    assert any("longitude/latitude" in n for n in read(str(path)).notices)


def test_wkt_wkb_and_hex_wkb_agree(tmp_path):
    polygon = shapely.from_wkt("POLYGON ((0 0, 4 0, 4 3, 0 3, 0 0), (1 1, 1 2, 2 2, 2 1, 1 1))")
    (tmp_path / "p.wkt").write_text(polygon.wkt)
    (tmp_path / "p.wkb").write_bytes(polygon.wkb)
    (tmp_path / "h.wkb").write_text(polygon.wkb_hex)
    for name in ("p.wkt", "p.wkb", "h.wkb"):
        props = read(str(tmp_path / name), units="mm").body.mass_properties()
        assert props.area == pytest.approx(11e-6, rel=1e-14)
        assert props.center_of_mass == pytest.approx(
            (np.array([2, 1.5]) * 12 - np.array([1.5, 1.5])) / 11 * 1e-3, rel=1e-14)


def test_wkt_without_area_is_refused(tmp_path):
    (tmp_path / "l.wkt").write_text("LINESTRING (0 0, 1 1)")
    with pytest.raises(FormatError, match="LINESTRING, which has no area"):
        read(str(tmp_path / "l.wkt"))


@pytest.mark.parametrize("text", [
    "x,y\n0,0\n4,0\n4,4\n0,4\n\n1,1\n1,3\n3,3\n3,1\n",
    "0;0\r\n4;0\r\n4;4\r\n0;4\r\n\r\n1;1\r\n1;3\r\n3;3\r\n3;1\r\n",
    "X\tY\n0\t0\n4\t0\n4\t4\n0\t4\n  \n1 1\n1 3\n3 3\n3 1",
])
def test_csv_rings_with_a_hole(tmp_path, text):
    path = tmp_path / "ring.csv"
    path.write_text(text)
    body = read(str(path)).body
    assert isinstance(body, Lamina)
    props = body.mass_properties()
    assert props.area == 12.0
    assert props.center_of_mass == pytest.approx([2.0, 2.0], rel=1e-15)


def test_touching_hole_and_self_crossing_ring(tmp_path):
    (tmp_path / "bow.csv").write_text("0,0\n3,3\n3,0\n0,3\n")
    with pytest.raises(GeometryError, match=r"crosses itself at \(1.5, 1.5\)"):
        read(str(tmp_path / "bow.csv"))


def test_dxf_polyline_bulges_and_a_half_ellipse_chain(tmp_path):
    def build(doc, msp):
        square = msp.add_polyline2d([(0, 0), (2, 0), (2, 2), (0, 2)], close=True)
        list(square.vertices)[-1].dxf.bulge = 1.0  # the closing edge: a half circle outward
        msp.add_ellipse((10, 0), major_axis=(2, 0), ratio=0.5, start_param=0, end_param=np.pi)
        msp.add_line((8, 0), (12, 0))

    parts = sorted((p.mass_properties() for p in read(dxf_file(tmp_path, build)).body.parts),
                   key=lambda m: m.center_of_mass[0])
    square, half = parts
    assert square.exact and square.area == pytest.approx(4 + np.pi / 2, rel=1e-14)
    assert square.center_of_mass[0] == pytest.approx((4 * 1 - np.pi / 2 * 4 / (3 * np.pi))
                                                     / (4 + np.pi / 2), rel=1e-13)
    assert not half.exact
    assert half.area == pytest.approx(np.pi, rel=1e-10)
    assert half.center_of_mass[1] == pytest.approx(4 * 1 / (3 * np.pi), rel=1e-9)


# ------------------------------------------------------------------ round 3: what was dropped
def test_dxf_minsert_places_every_copy(tmp_path):
    def build(doc, msp):
        doc.blocks.new("SQ").add_lwpolyline([(0, 0), (1, 0), (1, 1), (0, 1)], close=True)
        msp.add_blockref("SQ", (0, 0)).grid(size=(3, 4), spacing=(2, 3))  # 3 rows × 4 columns

    body = read(dxf_file(tmp_path, build)).body
    assert len(body.parts) == 12
    props = body.mass_properties()
    assert props.area == 12.0
    # columns at x = 0, 3, 6, 9 and rows at y = 0, 2, 4, each square's centre ½ in
    assert props.center_of_mass == pytest.approx([4.5 + 0.5, 2.0 + 0.5], rel=1e-15)


def test_dxf_full_ellipse_alone_is_read(tmp_path):
    a, b = 2.0, 0.5
    path = dxf_file(tmp_path, lambda doc, msp: msp.add_ellipse((1, 1), major_axis=(a, 0),
                                                              ratio=b / a))
    props = read(path).body.mass_properties()
    area = np.pi * a * b
    assert abs(props.area - area) <= props.relative_error * area
    assert props.relative_error < 1e-9
    assert props.center_of_mass == pytest.approx([1.0, 1.0], rel=1e-12)
    expected = np.diag([area * b * b / 4, area * a * a / 4, area * (a * a + b * b) / 4])
    assert rel(props.inertia, expected) < 1e-9


def _green(curve, lo: float, hi: float, breaks) -> tuple[float, np.ndarray]:
    """Area and centroid of the region a closed parametric curve bounds, by Green's theorem
    with Gauss-Legendre per knot span (exact for polynomial pieces)."""
    nodes, weights = np.polynomial.legendre.leggauss(12)
    spans = np.unique(np.clip(breaks, lo, hi))
    area, first = 0.0, np.zeros(2)
    for t0, t1 in zip(spans[:-1], spans[1:]):
        t = (t1 - t0) / 2 * nodes + (t0 + t1) / 2
        (x, y), (dx, dy) = curve(t).T, curve.derivative()(t).T
        w = weights * (t1 - t0) / 2
        area += w @ (x * dy - y * dx) / 2
        first += [w @ (x * x * dy) / 2, -(w @ (y * y * dx)) / 2]
    return area, first / area


def test_dxf_closed_periodic_spline_is_exact_against_scipy(tmp_path):
    from scipy.interpolate import BSpline

    corners = [(0, 0), (3, -0.5), (4, 1), (3, 2.5), (1, 3), (-1, 1.5)]

    def build(doc, msp):
        msp.add_spline().set_closed([(x, y, 0) for x, y in corners], degree=3)

    props = read(dxf_file(tmp_path, build)).body.mass_properties()
    control = np.array(corners + corners[:3], dtype=float)
    knots = np.arange(len(control) + 4, dtype=float)  # ezdxf's uniform knots, scaled
    n = len(control)
    doc = ezdxf.readfile(dxf_file(tmp_path, build, name="again.dxf"))
    stored = np.asarray(next(iter(doc.modelspace())).knots, dtype=float)
    assert np.allclose(np.diff(stored), np.diff(stored)[0])  # uniform, as assumed
    curve = BSpline(knots, control, 3)
    area, centre = _green(curve, knots[3], knots[n], knots)
    assert props.exact
    assert props.area == pytest.approx(abs(area), rel=1e-13)
    assert props.center_of_mass == pytest.approx(centre, rel=1e-12)


def test_dxf_removed_spline_is_an_error(tmp_path):
    def build(doc, msp):  # periodic with n + 1 knots: ezdxf's auditor removes it
        spline = msp.add_spline()
        spline.dxf.degree = 3
        spline.control_points = [(0, 0), (2, 0), (2, 1), (0, 1), (-1, 0.5)]
        spline.knots = list(range(6))
        spline.dxf.flags = spline.CLOSED | spline.PERIODIC

    with pytest.raises(FormatError, match="ezdxf had to remove.*SPLINE"):
        read(dxf_file(tmp_path, build))


def test_dxf_units_cover_every_insunits_code(tmp_path):
    square = lambda doc, msp: msp.add_lwpolyline([(0, 0), (1, 0), (1, 1), (0, 1)], close=True)  # noqa: E731
    reading = read(dxf_file(tmp_path, square, units=9))  # mils
    assert reading.body.mass_properties().area == pytest.approx(2.54e-5 ** 2, rel=1e-15)
    assert "units: mil (from the file)" in reading.notices


@given(degree=st.integers(1, 4), count=st.integers(5, 9), seed=st.integers(0, 10**6))
@settings(max_examples=40, deadline=None)
def test_clamped_bspline_is_the_same_curve(degree, count, seed):
    from scipy.interpolate import BSpline

    from plumbob.formats.curves import clamped_bspline

    rng = np.random.default_rng(seed)
    control = rng.normal(size=(count, 2))
    knots = np.sort(rng.integers(0, 6, size=count + degree + 1)).astype(float)
    assume(knots[degree] < knots[count])  # a domain to evaluate on
    c, k = clamped_bspline(control, knots, degree)
    # on [start, end): scipy evaluates the end of an unclamped domain outside it
    t = np.linspace(knots[degree], knots[count], 101)[:-1]
    assert np.allclose(k[:degree + 1], knots[degree]) and np.allclose(k[-degree - 1:], knots[count])
    assert np.abs(BSpline(k, c, degree)(t) - BSpline(knots, control, degree)(t)).max() < 1e-12


def test_plumbob_polygon_refuses_what_would_integrate_wrongly():
    from plumbob.bodies.primitives import polygon

    with pytest.raises(GeometryError, match=r"crosses itself at \(1, 0.5\) m"):
        polygon([[0, 0], [2, 0], [0, 1], [2, 1]])  # area 0 by the shoelace, not a lamina
    with pytest.raises(GeometryError, match="hole outside its outer boundary"):
        polygon([[0, 0], [1, 0], [1, 1], [0, 1]], holes=[[[5, 5], [6, 5], [6, 6]]])
    touching = polygon([[0, 0], [4, 0], [4, 4], [0, 4]], holes=[[[0, 2], [1, 1], [1, 3]]])
    assert touching.mass_properties().area == 15.0  # a hole touching at one point is fine


@pytest.mark.parametrize("header", ["x,y", "X (mm); Y (mm)", '"x"\t"y"', "east north"])
def test_csv_header_of_words_is_skipped(tmp_path, header):
    path = tmp_path / "ring.csv"
    path.write_text(f"{header}\n0,0\n2,0\n2,1\n")
    assert read(str(path)).body.mass_properties().area == 1.0


def test_csv_first_row_in_exponent_form_is_data(tmp_path):
    path = tmp_path / "ring.csv"
    path.write_text("1e0,0\n3,0\n3,1\n")
    assert read(str(path)).body.mass_properties().area == 1.0


def test_geojson_multipolygon_whose_parts_overlap(tmp_path):
    path = tmp_path / "m.geojson"
    square = [[0, 0], [2, 0], [2, 2], [0, 2], [0, 0]]
    moved = [[x + 1, y] for x, y in square]
    path.write_text(json.dumps({"type": "MultiPolygon", "coordinates": [[square], [moved]]}))
    with pytest.raises(GeometryError, match="polygon 2's outer boundary overlaps polygon 1's"):
        read(str(path))


@given(copies=st.integers(2, 6), seed=st.integers(0, 10**6))
@settings(max_examples=25, deadline=None)
def test_duplicates_are_dropped_whatever_their_start_and_direction(tmp_path_factory, copies,
                                                                   seed):
    rng = np.random.default_rng(seed)
    angles = np.sort(rng.uniform(0, 2 * np.pi, 7))
    ring = np.column_stack((np.cos(angles), np.sin(angles))) * rng.uniform(1, 3)
    area = shapely.Polygon(ring).area
    rows = []
    for _ in range(copies):  # the same outline from another vertex, either way round
        drawn = np.roll(ring, rng.integers(len(ring)), axis=0)[:: rng.choice([-1, 1])]
        rows.append("\n".join(f"{x:.17g},{y:.17g}" for x, y in drawn))
    rows.append("10,10\n11,10\n10,11")
    path = tmp_path_factory.mktemp("dups") / "d.csv"
    path.write_text("\n\n".join(rng.permutation(rows)))
    reading = read(str(path))
    assert reading.body.mass_properties().area == pytest.approx(area + 0.5, rel=1e-13)
    assert any(f"dropped {copies - 1} duplicate" in n for n in reading.notices)


def test_dxf_entities_out_of_plane_or_unread_are_named(tmp_path):
    def build(doc, msp):
        msp.add_polyline3d([(5, 0, 0), (6, 0, 1), (6, 1, 0)], close=True)  # z varies: no outline
        msp.add_lwpolyline([(0, 0), (2, 0), (2, 1), (0, 1)], close=True)
        msp.add_text("label")

    reading = read(dxf_file(tmp_path, build))
    assert reading.body.mass_properties().area == 2.0  # the tilted triangle not projected
    assert "dxf: ignored 1 entities not drawn in the XY plane" in reading.notices
    assert any("ignored 1 TEXT" in n for n in reading.notices)


@pytest.mark.parametrize("vertices, holes, message", [
    ([[0, 0], [1, 0], [1, 1]], 5, "holes must be a list"),
    ("abc", (), "list of \\[x, y\\] points"),
    ([[0, 0], [1, 0]], (), "fewer than three distinct points"),
    ([[0, 0], [1, 0], [np.nan, 1]], (), "not a finite number"),
    ([[0, 0, 0], [1, 0, 0], [1, 1, 0]], (), "shape \\(3, 3\\)"),
])
def test_plumbob_polygon_bad_arguments_are_geometry_errors(vertices, holes, message):
    from plumbob.bodies.primitives import polygon

    with pytest.raises(GeometryError, match=message):
        polygon(vertices, holes)


@given(st.lists(st.tuples(st.integers(-50, 50), st.integers(-50, 50), st.integers(1, 9),
                          st.booleans(), st.booleans()), min_size=1, max_size=12))
@settings(max_examples=60, deadline=None)
def test_a_region_from_shapely_has_each_polygons_oriented_rings_in_order(boxes):
    """Region.from_shapely orients every polygon and takes every ring's coordinates in one
    vectorised call each: the rings are those of orienting the polygons one by one,
    exterior then interiors, the closing point dropped, in the same order."""
    from plumbob.bodies.region import Region

    polygons = []
    for x, y, size, hole, clockwise in boxes:
        shell = [(x, y), (x + size, y), (x + size, y + size), (x, y + size)]
        shell = shell[::-1] if clockwise else shell
        inner = [[(x + 0.25, y + 0.25), (x + 0.5, y + 0.25), (x + 0.5, y + 0.5)]] if hole else []
        polygons.append(shapely.Polygon(shell, inner))
    geometry = shapely.MultiPolygon(polygons) if len(polygons) > 1 else polygons[0]
    want = []
    for polygon in getattr(shapely.normalize(geometry), "geoms", [shapely.normalize(geometry)]):
        polygon = shapely.geometry.polygon.orient(polygon, 1.0)
        want.append(np.asarray(polygon.exterior.coords)[:-1])
        want += [np.asarray(ring.coords)[:-1] for ring in polygon.interiors]
    got = Region.from_shapely(geometry).rings
    assert len(got) == len(want)
    for ring, vertices in zip(got, want):
        assert np.array_equal(ring.vertices, vertices) and not ring.vertices.flags.writeable
        assert ring.bulges is None and ring.controls is None


def test_many_regions_at_once_are_each_region_made_alone():
    """A file of many polygons makes its regions in one vectorised pass
    (Region.many_from_shapely): each must hold its own polygon's rings, in shapely's
    order (each polygon's exterior counter-clockwise, then its holes clockwise), the
    first point not repeated, to the bit — whatever the polygons around it."""
    import shapely
    from shapely.geometry.polygon import orient

    from plumbob.bodies.region import Region

    square = shapely.box(0, 0, 4, 4)
    cases = [shapely.Polygon([(0, 0), (0, 1), (1, 1), (1, 0)]),  # clockwise as given
             square.difference(shapely.box(1, 1, 2, 2)).difference(shapely.box(2.5, 2.5, 3, 3)),
             shapely.MultiPolygon([shapely.box(10, 0, 11, 1), square]),
             shapely.Point(0, 0).buffer(1.0, 16),
             shapely.MultiPolygon([shapely.box(0, 0, 1, 1).difference(shapely.box(0.2, 0.2, 0.4, 0.4)),
                                   shapely.box(3, 3, 5, 4)])]
    together = Region.many_from_shapely(cases)
    assert len(together) == len(cases)
    for region, geometry in zip(together, cases):
        expected = [np.asarray(ring.coords)[:-1]
                    for polygon in getattr(shapely.normalize(geometry), "geoms",
                                           [shapely.normalize(geometry)])
                    for oriented in [orient(polygon, 1.0)]
                    for ring in [oriented.exterior, *oriented.interiors]]
        assert len(region.rings) == len(expected)
        for ring, coords in zip(region.rings, expected):
            assert np.array_equal(ring.vertices, coords)
        alone = Region.from_shapely(geometry)
        assert all(np.array_equal(a.vertices, b.vertices) for a, b in zip(region.rings, alone.rings))
