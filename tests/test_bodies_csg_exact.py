"""Booleans against answers computed independently: exact rationals for boxes, closed
forms (lens, cap and cylinder-in-sphere volumes and centres) for spheres and cylinders.

What "error" means here (the convention of :mod:`plumbob.bodies.bounds`): the measure's
relative error; the centre's distance from the true one relative to the body's radius
about its centre, beyond the representation of the coordinates themselves (4 ulp of
their size: a centre at 1e6 m cannot be written closer); the inertia's Frobenius
distance relative to its norm. A stated ``relative_error`` must bound all three; an
exact result must be within 1e-12 (the project's standard for exact inputs).
"""

from __future__ import annotations

import itertools
import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from plumbob.bodies.csg import difference, union
from plumbob.bodies.primitives import box, cylinder, disc, rectangle, sphere

EXACT = 1e-12
SEGMENTS = 64  # coarse facets: larger errors for the bounds to cover, and fast
ULP = 4 * np.finfo(float).eps

# ------------------------------------------------------------- exact rational boxes
Box = tuple[tuple[Fraction, Fraction], ...]  # ((x0, x1), (y0, y1), (z0, z1))


def _box_moments(b: Box) -> dict:
    """Volume (area), first and second moments of a box (rectangle), as exact fractions."""
    vol = Fraction(1)
    for lo, hi in b:
        vol *= hi - lo
    mean = [(lo + hi) / 2 for lo, hi in b]
    square = [(lo * lo + lo * hi + hi * hi) / 3 for lo, hi in b]
    m = {"v": vol}
    for i in range(len(b)):
        m[i] = vol * mean[i]
        m[(i, i)] = vol * square[i]
        for j in range(i + 1, len(b)):
            m[(i, j)] = vol * mean[i] * mean[j]
    return m


def _meet(boxes) -> Box | None:
    out = []
    for k in range(len(boxes[0])):
        lo, hi = max(b[k][0] for b in boxes), min(b[k][1] for b in boxes)
        if lo >= hi:
            return None
        out.append((lo, hi))
    return tuple(out)


def _union_moments(boxes: list[Box]) -> dict:
    """Moments of a union of boxes by inclusion and exclusion (intersections are boxes)."""
    total: dict = {}
    for r in range(1, len(boxes) + 1):
        for subset in itertools.combinations(boxes, r):
            common = _meet(subset)
            if common is None:
                continue
            sign = 1 if r % 2 else -1
            for key, value in _box_moments(common).items():
                total[key] = total.get(key, Fraction(0)) + sign * value
    return total


def exact_properties(added: list[Box], removed: list[Box]):
    """(volume, centre, inertia) of ∪added − ∪removed, exactly, then rounded once (in 2D:
    area, centre, the 3 × 3 tensor of a lamina in z = 0)."""
    whole = _union_moments(added)
    cut = [c for a in added for r in removed if (c := _meet((a, r))) is not None]
    lost = _union_moments(cut) if cut else {}
    m = {k: whole[k] - lost.get(k, Fraction(0)) for k in whole}
    vol = m["v"]
    if vol <= 0:
        return 0.0, None, None
    dim = len(added[0])
    centre = [m[i] / vol for i in range(dim)]
    second = [[m[(min(i, j), max(i, j))] - vol * centre[i] * centre[j] if max(i, j) < dim
               else Fraction(0) for j in range(3)] for i in range(3)]
    trace = sum(second[i][i] for i in range(3))
    inertia = [[(trace if i == j else 0) - second[i][j] for j in range(3)] for i in range(3)]
    return (float(vol), np.array([float(c) for c in centre]),
            np.array([[float(v) for v in row] for row in inertia]))


def _plumbob_box(b: Box, offset: np.ndarray):
    size = [float(hi - lo) for lo, hi in b]
    shape = box(*size, density=1.0) if len(b) == 3 else rectangle(*size, density=1.0)
    return shape.translated([float(lo) for lo, _ in b] + offset)


def _errors(props, volume, centre, inertia, radius) -> tuple[float, float, float]:
    vol = abs(props.measure - volume) / volume
    miss = float(np.linalg.norm(props.center_of_mass - centre))
    where = max(0.0, miss - ULP * float(np.max(np.abs(centre)))) / radius
    spin = (float(np.linalg.norm(props.inertia - inertia)) / float(np.linalg.norm(inertia))
            if inertia is not None else 0.0)
    return vol, where, spin


# dyadic corners (k/16 m): every corner, size and shift is exact in float64, at 1e6 too
_coordinate = st.integers(0, 48).map(lambda k: Fraction(k, 16))


@st.composite
def _boxes(draw, dim: int = 3) -> Box:
    out = []
    for _ in range(dim):
        lo = draw(_coordinate)
        out.append((lo, lo + Fraction(draw(st.integers(4, 32)), 16)))
    return tuple(out)


@pytest.mark.parametrize("offset", [0.0, 1e6], ids=["origin", "at_1e6"])
@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(added=st.lists(_boxes(), min_size=1, max_size=3),
       removed=st.lists(_boxes(), min_size=0, max_size=2))
def test_box_booleans_agree_with_exact_rationals(offset, added, removed):
    volume, centre, inertia = exact_properties(added, removed)
    assume(volume > 0.05 * float(_union_moments(added)["v"]))  # not carved to a sliver
    shift = np.array([offset, -offset / 2, offset / 4])
    body = union(*(_plumbob_box(b, shift) for b in added))
    if removed:
        body = difference(body, *(_plumbob_box(b, shift) for b in removed))
    props = body.mass_properties()
    points = body.hull_points()
    radius = float(np.max(np.linalg.norm(points - centre - shift, axis=1)))
    errors = _errors(props, volume, centre + shift, inertia, radius)
    assert props.exact, props.notes
    assert max(errors) <= EXACT, (errors, props.notes)
    assert max(errors) <= max(props.relative_error, EXACT)
    assert "segments per turn" not in " ".join(props.notes)


@pytest.mark.parametrize("offset", [0.0, 1e6], ids=["origin", "at_1e6"])
@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(added=st.lists(_boxes(2), min_size=1, max_size=3),
       removed=st.lists(_boxes(2), min_size=0, max_size=2))
def test_rectangle_booleans_agree_with_exact_rationals(offset, added, removed):
    """The same for laminas: shapely's booleans of polygons, exact but for round-off."""
    area, centre, inertia = exact_properties(added, removed)
    assume(area > 0.05 * float(_union_moments(added)["v"]))
    shift = np.array([offset, -offset / 2])
    body = union(*(_plumbob_box(b, shift) for b in added))
    if removed:
        body = difference(body, *(_plumbob_box(b, shift) for b in removed))
    props = body.mass_properties()
    radius = float(np.max(np.linalg.norm(body.hull_points() - centre - shift, axis=1)))
    errors = _errors(props, area, centre + shift, inertia, radius)
    assert props.exact, props.notes
    assert max(errors) <= EXACT, (errors, props.notes)
    assert max(errors) <= max(props.relative_error, EXACT)


def test_l_bracket_is_exact():
    """Two overlapping boxes minus a square hole through both: every number to 1e-12 of the
    exact rational answer, at the origin and at 1e6 m."""
    f = Fraction
    legs = [((f(0), f(3)), (f(0), f(1, 2)), (f(0), f(2))),
            ((f(0), f(1, 2)), (f(0), f(5, 2)), (f(0), f(2)))]
    hole = [((f(-1), f(4)), (f(0), f(5, 2)), (f(3, 4), f(5, 4)))]  # a slot through both
    volume, centre, inertia = exact_properties(legs, hole)
    for offset in (np.zeros(3), np.array([1e6, 1e6, 0.0])):
        bracket = difference(union(*(_plumbob_box(b, offset) for b in legs)),
                             *(_plumbob_box(b, offset) for b in hole))
        props = bracket.mass_properties()
        errors = _errors(props, volume, centre + offset, inertia, 2.0)
        assert props.exact and max(errors) <= EXACT, errors
        assert max(errors) <= max(props.relative_error, EXACT)


def test_mirror_symmetric_body_has_no_product_of_inertia():
    """A box minus a box through its front face, symmetric about x = 0.3: Ixy and Ixz are
    zero to round-off, the centre on the plane (the shipped cabinet's carcass)."""
    outer = box(0.6, 0.45, 1.2, density=1.0)
    inner = box(0.6 - 2 * 0.018, 0.45, 1.2 - 2 * 0.018).translated([0.018, -0.018, 0.018])
    props = difference(outer, inner).mass_properties()
    scale = float(np.max(np.abs(props.inertia)))
    assert abs(props.inertia[0, 1]) <= 1e-14 * scale and abs(props.inertia[0, 2]) <= 1e-14 * scale
    assert props.center_of_mass[0] == pytest.approx(0.3, abs=1e-15)
    assert props.exact and props.relative_error < 1e-8


# ---------------------------------------------------------- curved: closed forms
def _cap(r: float, h: float) -> tuple[float, float]:
    """Volume of a spherical cap of height h, and its centroid's distance from the centre."""
    return math.pi * h * h * (3 * r - h) / 3, 3 * (2 * r - h) ** 2 / (4 * (3 * r - h))


def _lens(r1: float, r2: float, d: float) -> tuple[float, float]:
    """Volume and x-moment of the lens where a ball r1 at 0 and a ball r2 at (d, 0, 0) meet."""
    x0 = (d * d + r1 * r1 - r2 * r2) / (2 * d)
    v1, c1 = _cap(r1, r1 - x0)
    v2, c2 = _cap(r2, r2 - (d - x0))
    return v1 + v2, v1 * c1 + v2 * (d - c2)


def _ball(r: float) -> float:
    return 4 / 3 * math.pi * r**3


def _check_bound(props, volume, centre, radius):
    errors = _errors(props, volume, centre, None, radius)
    assert not props.exact
    assert max(errors) <= props.relative_error, (errors, props.relative_error)
    assert "segments per turn" in " ".join(props.notes)


@pytest.mark.parametrize("offset", [0.0, 1e6], ids=["origin", "at_1e6"])
@settings(max_examples=8, deadline=None)
@given(r1=st.floats(0.5, 2.0), r2=st.floats(0.5, 2.0), t=st.floats(0.05, 0.95),
       cut=st.booleans())
def test_two_balls_within_their_stated_bound(offset, r1, r2, t, cut):
    d = abs(r1 - r2) + 0.05 + t * (r1 + r2 - abs(r1 - r2) - 0.1)
    shift = np.array([offset, offset / 3, 0.0])
    a, b = sphere(r1, density=1.0).translated(shift), sphere(r2, density=1.0).translated(shift + [d, 0, 0])
    lens, moment = _lens(r1, r2, d)
    if cut:
        assume(_ball(r1) - lens > 0.05 * _ball(r1))
        body, volume, first = difference(a, b, segments=SEGMENTS), _ball(r1) - lens, -moment
        far = [np.array([-r1, 0, 0])]
    else:
        body = union(a, b, segments=SEGMENTS)
        volume, first = _ball(r1) + _ball(r2) - lens, _ball(r2) * d - moment
        far = [np.array([-r1, 0, 0]), np.array([d + r2, 0, 0])]
    centre = np.array([first / volume, 0, 0])
    radius = max(float(np.linalg.norm(p - centre)) for p in far)  # points of the true body
    _check_bound(body.mass_properties(), volume, centre + shift, radius)


@pytest.mark.parametrize("offset", [0.0, 1e6], ids=["origin", "at_1e6"])
@settings(max_examples=6, deadline=None)
@given(a=st.floats(0.2, 0.9), big=st.floats(1.0, 1.5), length=st.floats(1.6, 3.0),
       cut=st.booleans())
def test_ball_on_a_cylinder_within_its_stated_bound(offset, a, big, length, cut):
    """A ball of radius ``big`` centred on a cylinder's top face (radius ``a`` < ``big``):
    they share half the ball's core of radius ``a``, whose volume and moment are closed
    forms: V = 2π/3 (R³ − (R² − a²)^{3/2}), ∫z = −π (R² a²/2 − a⁴/4) below the face."""
    shift = np.array([offset, 0.0, -offset / 2])
    rod = cylinder(a, length, density=1.0).translated(shift)
    ball = sphere(big, density=1.0).translated(shift + [0, 0, length])
    core = 2 * math.pi / 3 * (big**3 - (big * big - a * a) ** 1.5)
    core_z = core * length - math.pi * (big * big * a * a / 2 - a**4 / 4)
    rod_v = math.pi * a * a * length
    if cut:
        body, volume = difference(rod, ball, segments=SEGMENTS), rod_v - core
        first = rod_v * length / 2 - core_z
        far = [np.array([a, 0, 0])]
    else:
        body, volume = union(rod, ball, segments=SEGMENTS), rod_v + _ball(big) - core
        first = rod_v * length / 2 + _ball(big) * length - core_z
        far = [np.array([a, 0, 0]), np.array([0, 0, length + big])]
    centre = np.array([0, 0, first / volume])
    radius = max(float(np.linalg.norm(p - centre)) for p in far)
    _check_bound(body.mass_properties(), volume, centre + shift, radius)


def _segment(r: float, a: float) -> tuple[float, float]:
    """Area of the circular segment of a disc r cut by a chord at distance a from its
    centre (the far side), and its centroid's distance from the centre."""
    alpha = math.acos(a / r)
    area = r * r * (alpha - math.sin(alpha) * math.cos(alpha))
    return area, 2 * r * math.sin(alpha) ** 3 / (3 * (alpha - math.sin(alpha) * math.cos(alpha)))


@pytest.mark.parametrize("offset", [0.0, 1e6], ids=["origin", "at_1e6"])
@settings(max_examples=6, deadline=None)
@given(r1=st.floats(0.5, 2.0), r2=st.floats(0.5, 2.0), t=st.floats(0.05, 0.95),
       cut=st.booleans())
def test_two_discs_within_their_stated_bound(offset, r1, r2, t, cut):
    """Laminas: the lens of two discs is two circular segments (closed forms)."""
    d = abs(r1 - r2) + 0.05 + t * (r1 + r2 - abs(r1 - r2) - 0.1)
    x0 = (d * d + r1 * r1 - r2 * r2) / (2 * d)
    (a1, c1), (a2, c2) = _segment(r1, x0), _segment(r2, d - x0)
    lens, moment = a1 + a2, a1 * c1 + a2 * (d - c2)
    shift = np.array([offset, offset / 3])
    a, b = disc(r1, density=1.0).translated(shift), disc(r2, density=1.0).translated(shift + [d, 0])
    if cut:
        assume(math.pi * r1 * r1 - lens > 0.05 * math.pi * r1 * r1)
        body, area, first = difference(a, b, segments=SEGMENTS), math.pi * r1 * r1 - lens, -moment
        far = [np.array([-r1, 0])]
    else:
        body = union(a, b, segments=SEGMENTS)
        area = math.pi * (r1 * r1 + r2 * r2) - lens
        first = math.pi * r2 * r2 * d - moment
        far = [np.array([-r1, 0]), np.array([d + r2, 0])]
    centre = np.array([first / area, 0])
    radius = max(float(np.linalg.norm(p - centre)) for p in far)
    _check_bound(body.mass_properties(), area, centre + shift, radius)
