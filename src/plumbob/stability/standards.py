"""Product-stability standards as bundles of plumbob's checks: one table of presets.

A preset names its standard, edition and clauses, and lists its tests; each test is one
of plumbob's checks — a tilt in every direction (:class:`TiltTest`), forces at the worst
point (:class:`ForceTest`), or the extendable parts opened and loaded
(:class:`OpenedTest`). The bundle passes when, in every group of alternatives
(``groups``), at least one test passes. The numbers are cited in
``docs/standards.md``. This is a design-stage model of a standard's tests, computed from
geometry and densities, not a certification: a test lab tests the product.

To add a standard: one entry in :data:`PRESETS` (and its rows in ``docs/standards.md``),
and a test that a design passes and another fails.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import StabilityError
from ..loads import Extendable, Hang, Press, Push
from ..results import Key, Result
from .requirement import Requirement

__all__ = ["PRESETS", "Preset", "TiltTest", "ForceTest", "OpenedTest", "StandardTest",
           "StandardResult", "run_standard"]

DISCLAIMER = ("a design-stage model of the standard's stability tests, computed from the "
              "geometry and densities given; not a certification (a test lab tests the "
              "product)")


@dataclass(frozen=True)
class TiltTest:
    """It must not overturn on a plane tilted ``tilt_deg`` in any direction."""

    name: str
    clause: str
    tilt_deg: float

    def describe(self) -> str:
        return f"tilted {self.tilt_deg:g}° in every direction"


@dataclass(frozen=True)
class ForceTest:
    """Forces at the worst point no higher than ``max_height`` m: a downward force of
    ``press[0]`` of the weight (at most ``press[1]`` N) and a horizontal force of
    ``push[0]`` of the weight (at most ``push[1]`` N), either may be None."""

    name: str
    clause: str
    push: tuple[float, float] | None = None
    press: tuple[float, float] | None = None
    max_height: float | None = None

    def describe(self) -> str:
        parts = []
        if self.press:
            parts.append(f"down {self.press[0]:.0%} of the weight (≤ {self.press[1]:g} N)")
        if self.push:
            parts.append(f"horizontal {self.push[0]:.0%} of the weight (≤ {self.push[1]:g} N)")
        where = f" at the worst point ≤ {self.max_height:g} m high" if self.max_height else ""
        return " and ".join(parts) + where


@dataclass(frozen=True)
class OpenedTest:
    """Every extendable part opened to its stop and filled at ``fill_density`` kg/m³ of its
    storage volume, the floor tilted forward by a ``block`` m block under the rear feet,
    and ``test_mass`` kg hung at the front of each extendable in turn (one case each)."""

    name: str
    clause: str
    fill_density: float
    block: float
    test_mass: float

    def describe(self) -> str:
        return (f"extendables open and filled at {self.fill_density:g} kg/m³, floor tilted by "
                f"a {self.block * 1000:g} mm block under the rear feet, {self.test_mass:g} kg "
                "at the front of each in turn")


@dataclass(frozen=True)
class Preset:
    """A standard: its name, title, edition, the clause of its stability tests, the tests
    and the groups of alternatives (every group needs one passing test)."""

    name: str
    title: str
    edition: str
    clause: str
    tests: tuple
    groups: tuple[tuple[str, ...], ...]


#: the standards plumbob models, by the name ``--standard`` takes (see docs/standards.md)
PRESETS: dict[str, Preset] = {
    "iec62368-1": Preset(
        "iec62368-1", "IEC 62368-1, audio/video, information and communication technology "
        "equipment — safety", "3rd edition (2018)", "8.6 (stability)",
        (TiltTest("tilt", "8.6: 10° tilt", 10.0),
         ForceTest("force", "8.6: alternative force test", push=(0.13, 250.0),
                   press=(0.50, 100.0), max_height=1.5)),
        (("tilt", "force"),)),
    "iec62368-1-display": Preset(
        "iec62368-1-display", "IEC 62368-1, audio/video, information and communication "
        "technology equipment — safety (displays)", "3rd edition (2018)", "8.6 and 8.6.5",
        (TiltTest("tilt", "8.6: 10° tilt", 10.0),
         ForceTest("force", "8.6: alternative force test", push=(0.13, 250.0),
                   press=(0.50, 100.0), max_height=1.5),
         ForceTest("display", "8.6.5: horizontal force on a display", push=(0.20, 250.0),
                   max_height=1.5)),
        (("tilt", "force"), ("display",))),
    "astm-f2057": Preset(
        "astm-f2057", "ASTM F2057, standard safety specification for clothing storage units",
        "F2057-23", "7 (stability tests)",
        (OpenedTest("opened", "F2057-23: extendables open, filled, 60 lb (27.2 kg) test "
                    "weight, floor tilted by a 0.43 in (10.9 mm) block", 136.2, 0.0109, 27.2),),
        (("opened",),)),
}


@dataclass(frozen=True, repr=False)
class StandardTest(Result):
    """One test of a standard and how the body fares.

    name, clause, description: the test and the clause it models.
    case: which case of the test (an extendable's name), or None.
    passes: whether it passes.
    margin: how far it passes (negative: fails): degrees beyond the required tilt for a
        tilt test, the factor of safety against overturning less 1 for a force test.
    margin_unit: ``"deg"`` or ``"factor"``.
    overturning_safety_factor: resisting / overturning moment (force tests), or None.
    point: (dim,) m, where the deciding force acts (the worst point found), or None.
    direction: (dim,) the horizontal direction it tips toward (the critical one).
    verdict: the verdict under the test (``"stands"``, ``"topples"``, …).
    """

    name: str
    clause: str
    description: str
    passes: bool
    margin: float
    margin_unit: str
    verdict: str
    direction: np.ndarray
    point: np.ndarray | None = None
    overturning_safety_factor: float | None = None
    case: str | None = None

    #: the keys of each of ``standard``'s ``tests``
    KEYS = (
        Key("name", "", "the test", type="str"),
        Key("clause", "", "the clause it models", type="str"),
        Key("description", "", "what it does", type="str"),
        Key("passes", "", "whether it passes", type="bool"),
        Key("margin", "°, factor", "how far it passes (negative: fails)", type="float"),
        Key("margin_unit", "", "`deg` or `factor`", type="str"),
        Key("verdict", "", "the verdict under the test", type="str"),
        Key("direction", "", "the horizontal direction it tips toward", type="xyz"),
        Key("point", "m", "where the deciding force acts (`null` for a tilt test)",
            type="xyz"),
        Key("overturning_safety_factor", "", "resisting / overturning moment (force tests)",
            type="float"),
        Key("case", "", "which case of the test (an extendable's name), or `null`",
            type="str"),
    )


@dataclass(frozen=True, repr=False)
class StandardResult(Result):
    """A standard's tests on one body: each test, and whether the bundle passes.

    standard, title, edition, clause: what is modelled. tests: each test (and case).
    groups: the alternatives (every group needs one passing test). passes: the bundle.
    disclaimer: what this is and is not.
    """

    standard: str
    title: str
    edition: str
    clause: str
    tests: tuple[StandardTest, ...]
    groups: tuple[tuple[str, ...], ...]
    passes: bool
    disclaimer: str = DISCLAIMER
    notes: tuple[str, ...] = field(default=())

    _repr_fields = ("standard", "edition", "passes")

    #: the keys of the ``standard`` object of ``plumbob check --standard NAME --json``
    KEYS = (
        Key("standard", "", "the standard's name, as `--standard` takes it", type="str"),
        Key("title", "", "its title", type="str"),
        Key("edition", "", "the edition modelled", type="str"),
        Key("clause", "", "the clause modelled", type="str"),
        Key("passes", "", "whether the bundle passes", type="bool"),
        Key("groups", "", "the alternatives: every group needs one passing test"),
        Key("tests", "", "each test and case (the keys below)"),
        Key("disclaimer", "", "what this is and is not", type="str"),
        Key("notes", "", "what to know about the answer", "when there are any",
            type="strings"),
    )


def _force_loads(test: ForceTest, weight: float) -> tuple:
    loads = []
    if test.press:
        loads.append(Press(min(test.press[0] * weight, test.press[1]), test.max_height,
                           "downward force"))
    if test.push:
        loads.append(Push(min(test.push[0] * weight, test.push[1]), test.max_height,
                          "horizontal force"))
    return tuple(loads)


def _from_loaded(test, v, case: str | None = None) -> StandardTest:
    lv = v.loaded
    factor = lv.overturning_safety_factor
    margin = (math.inf if factor is None else factor - 1.0)
    push = [m for m in lv.moments if m.kind in ("push", "hang") and m.name != "weight"]
    point = push[-1].at if push else None
    return StandardTest(test.name, test.clause, test.describe(), bool(lv.stands),
                        float(margin) if math.isfinite(margin) else 1e308, "factor", lv.verdict,
                        lv.edge_normal, point, factor, case)


def _parts_by_name(body) -> dict[str, Any]:
    return {getattr(p, "name", None): p for p in body.assembly_parts()}


def _opened(body, extendables: tuple[Extendable, ...]):
    """The body with every extendable moved along its travel, and each one's moved part."""
    from ..bodies.csg import Assembly

    parts = _parts_by_name(body)
    moving: dict[str, np.ndarray] = {}
    for e in extendables:
        for name in e.parts:
            if name not in parts:
                known = ", ".join(n for n in parts if n) or "none"
                raise StabilityError(f"the extendable {e.name!r} names the part {name!r}, which "
                                     f"the body does not have (its parts: {known})")
            moving[name] = e.travel
    opened = tuple(p.translated(moving[n]) if n in moving else p for n, p in parts.items())
    return Assembly(opened), {e.name: parts[e.name].translated(e.travel) for e in extendables}


def _opened_cases(test: OpenedTest, body, req: Requirement, extendables, props) -> list:
    from .support import support_polygon
    from .verdict import check

    if not extendables:
        raise StabilityError("the ASTM F2057 test opens the unit's drawers and doors: mark "
                             "them in the spec with [[extendable]] tables (part, travel, volume)")
    opened, moved = _opened(body, extendables)
    sup = support_polygon(body, req.down, props=props)
    frame = sup.frame
    forward = frame.to_ground(extendables[0].travel)
    if not np.any(forward):
        raise StabilityError("the first extendable's travel is vertical: no way is forward")
    forward = forward / np.linalg.norm(forward)
    depth = float(np.ptp(sup.vertices @ forward))  # front feet to rear feet
    tilt = math.degrees(math.atan2(test.block, depth))
    toward = math.degrees(math.atan2(forward[1], forward[0]))
    fills = []
    fronts = {}
    for e in extendables:
        pts = moved[e.name].hull_points()
        fills.append(Hang(test.fill_density * e.volume, (pts.min(0) + pts.max(0)) / 2,
                          f"fill of {e.name}"))
        along = pts @ frame.from_ground(forward)
        front = pts[along >= along.max() - 1e-9 * max(1.0, abs(along.max()))]
        top = front[:, :] @ frame.up
        front = front[top >= top.max() - 1e-9 * max(1.0, abs(top.max()))]
        fronts[e.name] = front.mean(axis=0)
    cases = []
    for e in extendables:
        loads = (*fills, Hang(test.test_mass, fronts[e.name], f"test weight on {e.name}"))
        case_req = req.replace(tilt_deg=tilt, toward_deg=toward, loads=loads)
        cases.append(_from_loaded(test, check(opened, requirement=case_req), e.name))
    return cases


def run_standard(body, name: str, requirement: Requirement | None = None, *,
                 extendables: tuple = (), props=None) -> StandardResult:
    """Run the preset ``name``'s tests on ``body`` (see :data:`PRESETS`).

    requirement: down, g and friction for every test (its own tilt, margin and loads are
        not used: each test sets its own); extendables: the parts that open (from the
        spec's ``[[extendable]]`` tables), for the tests that open them.
    """
    from .verdict import check

    if name not in PRESETS:
        raise StabilityError(f"unknown standard {name!r}; plumbob models: "
                             f"{', '.join(PRESETS)}")
    preset = PRESETS[name]
    base = Requirement() if requirement is None else requirement
    base = base.replace(tilt_deg=None, toward_deg=None, margin=None, require_tilt_deg=None,
                        loads=())
    props = body.mass_properties() if props is None else props
    weight = props.mass * base.g
    tests: list[StandardTest] = []
    for test in preset.tests:
        if isinstance(test, TiltTest):
            v = check(body, requirement=base.replace(require_tilt_deg=test.tilt_deg),
                      props=props)
            tests.append(StandardTest(test.name, test.clause, test.describe(), bool(v.passes),
                                      float(v.critical_tilt_deg - test.tilt_deg), "deg",
                                      v.verdict, v.critical_direction))
        elif isinstance(test, ForceTest):
            v = check(body, requirement=base.replace(loads=_force_loads(test, weight)),
                      props=props)
            tests.append(_from_loaded(test, v))
        else:
            tests.extend(_opened_cases(test, body, base, tuple(extendables), props))
    ok = {t.name: True for t in tests}
    for t in tests:
        ok[t.name] = ok[t.name] and t.passes
    passes = all(any(ok.get(n, False) for n in group) for group in preset.groups)
    return StandardResult(preset.name, preset.title, preset.edition, preset.clause,
                          tuple(tests), preset.groups, passes)
