"""Count limits no longer refuse legitimate files (issue 20, item 6): an archipelago's
polygons, a CSV of many rings, an SVG of many rectangles, a spec of many particles or
parts were refused by a count of parts (10,000). A limit bounds work and memory — bytes,
rings, points, expansion — not how many parts a file has (``plumbob.limits``).

Each case here is just over the old limit (10,000), read by the library and checked
exactly: n unit squares, 3 m apart, have an area of n and a centre at the mean of theirs.
(The issue's own sizes — 30,000 polygons, rings or rectangles, 50,000 particles, 90,000
cubes — are read the same way; they take seconds each, too long for the suite.)
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import plumbob

N = 10_001


def _squares(n: int = N):
    k = np.arange(n)
    return 3.0 * (k % 100), 3.0 * (k // 100)


def _centre(n: int = N):
    x, y = _squares(n)
    return [float(np.mean(x)) + 0.5, float(np.mean(y)) + 0.5]


def _check(body, n: int = N):
    props = body.mass_properties()
    assert len(body.parts) == n
    assert props.area == pytest.approx(n, rel=1e-13)
    assert props.center_of_mass == pytest.approx(_centre(n), rel=1e-12)


def test_a_geojson_archipelago_of_many_polygons(tmp_path):
    x, y = _squares()
    features = [{"type": "Feature", "properties": {"name": f"island {k}"},
                 "geometry": {"type": "Polygon", "coordinates": [[
                     [a, b], [a + 1, b], [a + 1, b + 1], [a, b + 1], [a, b]]]}}
                for k, (a, b) in enumerate(zip(x.tolist(), y.tolist()))]
    path = tmp_path / "islands.geojson"
    path.write_text(json.dumps({"type": "FeatureCollection", "features": features}))
    _check(plumbob.load(str(path)))


def test_a_csv_of_many_rings(tmp_path):
    x, y = _squares()
    rings = [f"{a},{b}\n{a + 1},{b}\n{a + 1},{b + 1}\n{a},{b + 1}\n"
             for a, b in zip(x.tolist(), y.tolist())]
    path = tmp_path / "rings.csv"
    path.write_text("\n".join(rings))
    _check(plumbob.load(str(path), units="m"))


def test_an_svg_of_many_rectangles(tmp_path):
    x, y = _squares()
    rects = "".join(f'<rect x="{a:g}" y="{b:g}" width="1" height="1"/>'
                    for a, b in zip(x.tolist(), y.tolist()))
    path = tmp_path / "rects.svg"
    path.write_text('<svg xmlns="http://www.w3.org/2000/svg" width="300" height="303" '
                    f'viewBox="0 0 300 303">{rects}</svg>')
    body = plumbob.load(str(path), units="m")
    props = body.mass_properties()
    assert len(body.parts) == N
    assert props.area == pytest.approx(N, rel=1e-13)
    # SVG's y axis points down: x as written, y mirrored about the drawing
    assert props.center_of_mass[0] == pytest.approx(_centre()[0], rel=1e-12)


def test_a_spec_of_many_particles(tmp_path):
    n = N
    path = tmp_path / "swarm.toml"
    path.write_text('[shape]\nkind = "particles"\n' + "".join(
        f"[[particle]]\nmass = 1\nposition = [{k % 200}, {k // 200}, 0]\n" for k in range(n)))
    props = plumbob.load(str(path)).mass_properties()
    k = np.arange(n)
    assert props.mass == n
    assert props.center_of_mass == pytest.approx([np.mean(k % 200), np.mean(k // 200), 0],
                                                 rel=1e-13, abs=1e-13)
