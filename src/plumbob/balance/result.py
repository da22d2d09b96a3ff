"""What ``plumbob balance`` reports: the ballast, and the body's stability before and after,
measured by plumbob's own check on the body plus the ballast (never taken from the plan).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..results import Key, Result, Source, keyed, pick
from ..stability.verdict import Verdict, check
from .ballast import ballast_body, plan_ballast
from .targets import Target, target_for

__all__ = ["BalanceResult", "balance"]


#: the keys of ``plumbob balance --json``'s ``target``
TARGET_KEYS = (
    Key("margin", "m", "the static stability margin asked", attr="margin_target"),
    Key("require_tilt_deg", "°", "the critical tilt asked"),
    Key("toward", "", "the one direction the tilt is asked toward (`null`: every one)"),
    Key("down", "", "gravity's direction, body frame (unit vector)"),
)
#: the keys of its ``ballast`` (those with a ``when`` come with a material)
BALLAST_KEYS = (
    Key("mass", "kg", "the ballast's own mass", attr="ballast_mass"),
    Key("center_of_mass", "m", "where its centre goes, body frame", attr="ballast_point"),
    Key("added_mass", "kg", "what the body gains (less the material a pocket removes)"),
    Key("pocket", "", "whether it fills a pocket cut in the body"),
    Key("material", "", "its material", "with a material", attr="ballast_material"),
    Key("density", "kg/m³", "its density", "with a material", attr="ballast_density"),
    Key("volume", "m³", "its volume", "with a material", attr="ballast_volume"),
    Key("shape", "", "`box`, `cylinder` or `square`", "with a material", attr="ballast_shape"),
    Key("dimensions", "m", "(side,) or (radius, height)", "with a material",
        attr="ballast_dimensions"),
    Key("depth", "m", "a lamina's thickness it fills", "a lamina's", attr="ballast_depth"),
)
#: the keys of its ``before`` and ``after``: of each verdict, in this order
STATE_KEYS = pick(Verdict.KEYS, ("verdict", "mass", "center_of_mass", "margin",
                                 "critical_tilt_deg", "critical_direction", "com_height"))


@dataclass(frozen=True, repr=False)
class BalanceResult(Result):
    """The least ballast that meets a stability target, and the stability it gives.

    ballast_mass: kg, the ballast's own mass (0 when the body meets the target as it is).
    added_mass: kg, what the body gains: the ballast's mass less the body's material its
        pocket removes (a ballast of a material placed inside the body fills a pocket cut
        for it; a point mass, or a ballast in a separate region, adds all of its mass).
    pocket: whether the ballast fills a pocket cut in the body.
    ballast_point: (dim,) m, body frame: where the ballast's centre goes.
    ballast_material, ballast_density: the material given (kg/m³), or None for a point mass.
    ballast_volume: m³; ballast_shape: ``"box"``, ``"cylinder"`` or ``"square"`` (a lamina's,
        through its ``ballast_depth`` m); ballast_dimensions: m, (side,) or (radius, height).
    margin_target, require_tilt_deg: the target (m, degrees), None where not asked.
    toward: (dim,) the one direction the tilt is asked toward, or None for every direction.
    down: (dim,) unit vector, gravity in the body's frame.
    before, after: the verdicts of the body alone and of the body with the ballast.
    passes: whether the body with the ballast meets the target by the check's own numbers.
    """

    ballast_mass: float
    ballast_point: np.ndarray
    margin_target: float | None
    require_tilt_deg: float | None
    down: np.ndarray
    before: Verdict
    after: Verdict
    passes: bool
    ballast_material: str | None = None
    ballast_density: float | None = None
    ballast_volume: float | None = None
    ballast_shape: str | None = None
    ballast_dimensions: tuple[float, ...] | None = None
    ballast_depth: float | None = None
    toward: np.ndarray | None = None
    added_mass: float | None = None
    pocket: bool = False
    source: Source | None = field(default=None, compare=False)

    _repr_units = {"ballast_mass": "kg", "ballast_point": "m", "ballast_volume": "m³"}
    _repr_fields = ("ballast_mass", "ballast_point", "ballast_volume", "ballast_shape",
                    "passes")

    def text(self, units=None) -> str:
        """The report ``plumbob balance`` prints (``str(result)``): the target, before, the
        ballast, after; lengths, masses, volumes and densities in ``units`` (a
        :class:`~plumbob.report.ReportUnits` or ``"mm,g"``; default the part's own, from
        its :class:`~plumbob.results.Source`, else SI)."""
        from ..report import units_for
        from ..report.balance import balance_text

        s = self.source or Source()
        kind = s.kind or ("lamina" if len(self.down) == 2 else "solid")
        return balance_text(self, s.path or "body", kind, list(s.notes),
                            s.size or self.before.support.size, units_for(units, s.length_unit))

    @property
    def target_dict(self) -> dict[str, Any]:
        """The ``target`` object of ``plumbob balance --json``."""
        return keyed(self, TARGET_KEYS)

    @property
    def ballast_dict(self) -> dict[str, Any]:
        """The ``ballast`` object of ``plumbob balance --json``."""
        return keyed(self, BALLAST_KEYS)

    @property
    def before_dict(self) -> dict[str, Any]:
        """The ``before`` object: the body alone (:data:`STATE_KEYS` of its verdict)."""
        return keyed(self.before, STATE_KEYS)

    @property
    def after_dict(self) -> dict[str, Any]:
        """The ``after`` object: the body with the ballast, by plumbob's check."""
        return keyed(self.after, STATE_KEYS)

    #: the keys of ``plumbob balance --json`` after the file's (docs/cli.md's table)
    KEYS = (
        Key("target", "m, °", "what was asked: `margin`, `require_tilt_deg`, `toward`, `down`",
            attr="target_dict"),
        Key("ballast", "kg, m, m³", "`mass`, `center_of_mass`, `added_mass`, `pocket`; with a "
                                    "material `material`, `density`, `volume`, `shape`, "
                                    "`dimensions`, and for a lamina `depth`", attr="ballast_dict"),
        Key("before", "", "the body alone: `verdict`, `mass`, `center_of_mass`, `margin`, "
                          "`critical_tilt_deg`, `critical_direction`, `com_height`",
            attr="before_dict"),
        Key("after", "", "the same for the body with the ballast, by plumbob's check",
            attr="after_dict"),
        Key("passes", "", "whether the body with the ballast meets the target", type="bool"),
    )


def meets(v: Verdict, margin: float | None, require_tilt_deg: float | None,
          tolerance: float, toward=None) -> bool:
    """Whether a verdict meets a margin (m) and a tilt (degrees, toward one horizontal
    direction or every one): it stands, with margin and tipping angle at least those
    asked (within round-off)."""
    ok = v.verdict == "stands"
    if margin is not None:
        ok = ok and v.margin >= margin - 1e-9 * tolerance
    if require_tilt_deg is not None:
        angle = v.critical_tilt_deg if toward is None else v.tipping_angle_deg(toward)
        ok = ok and angle >= require_tilt_deg - 1e-9
    return bool(ok)


def _depth(body) -> float | None:
    """A lamina's thickness, m (from the body or its parts), or None."""
    thickness = getattr(body, "thickness", None)
    if thickness is not None:
        return float(thickness)
    for part in getattr(body, "parts", ()) or ((getattr(body, "body", None),) if
                                               hasattr(body, "body") else ()):
        found = _depth(part)
        if found is not None:
            return found
    return None


def balance(body, down=None, *, margin: float | None = None,
            require_tilt_deg: float | None = None, region=None,
            material: str | None = None, density: float | None = None, shape: str = "box",
            g: float | None = None, props=None, target: Target | None = None,
            toward=None) -> BalanceResult:
    """The least ballast that makes ``body`` meet a stability target, and where it goes.

    Parameters
    ----------
    body : Body
        The body, resting with gravity along ``down`` (default −z; −y for a lamina).
    margin : float, optional
        Static stability margin asked for, m.
    require_tilt_deg : float, optional
        Critical tilt asked for in every direction, degrees.
    toward : array_like, optional
        With ``require_tilt_deg``: only toward this horizontal direction (body frame).
    region : Body, optional
        Where the ballast may go (default: inside the body itself).
    material, density : optional
        The ballast's material name (for the report) and density, kg/m³: the ballast is
        then a ``shape`` (``"box"`` or ``"cylinder"``; a square through the thickness
        for a lamina) that fits inside the region.

    Returns
    -------
    BalanceResult
        The ballast and the verdicts before and after, the latter from
        :func:`plumbob.stability.check` on the body plus the ballast.

    Examples
    --------
    The seed's block (1 × 1 × 4 m, 4000 kg) has critical tilt 14.04°; for 20° the least
    point mass sits at the bottom of the block:

    >>> from plumbob.bodies.primitives import box
    >>> r = balance(box(1, 1, 4, density=1000.0), require_tilt_deg=20)
    >>> r.passes, round(r.ballast_mass), round(float(r.ballast_point[2]), 2)
    (True, 1824, 0.0)
    """
    from ..arguments import answering
    from ..units import SEED_GRAVITY

    body = answering(body, "body", "mass_properties")
    g = SEED_GRAVITY if g is None else g
    props = body.mass_properties() if props is None else props
    if toward is not None:
        toward = np.asarray(toward, dtype=float)
    every = None if toward is not None else require_tilt_deg
    before = check(body, down, g=g, props=props, require_tilt_deg=every)
    given = target is not None
    if target is None:
        target = target_for(body, margin=margin, require_tilt_deg=require_tilt_deg,
                            support=before.support, toward=toward)
    depth = _depth(body) if density is not None and target.dim == 2 else None
    if density is not None and target.dim == 2 and depth is None:
        from ..errors import StabilityError

        raise StabilityError("a lamina without a thickness has no volume for a ballast "
                             "material: give the lamina a thickness, or no ballast material")
    pocket = density is not None and region is None
    net = density
    if pocket:  # the ballast fills a pocket: it adds its density less the body's
        net = density - props.mass / (props.measure * (depth or 1.0))
        if net <= 0:
            from ..errors import StabilityError

            raise StabilityError(
                f"the ballast material ({density:g} kg/m³) is not denser than the body "
                f"({density - net:g} kg/m³): a pocket of it would make the body lighter there")
    plan = plan_ballast(body if region is None else region, target, props.mass,
                        before.center_of_mass, density=net, shape=shape, depth=depth)
    already = (target.met_by(before.center_of_mass, before.support.tolerance) if given else
               meets(before, margin, require_tilt_deg, before.support.tolerance, toward))
    if plan.mass > 0 and already:
        # the check's own numbers say it meets the target already: a plan of a few
        # round-off kilograms is no ballast
        from dataclasses import replace

        plan = replace(plan, mass=0.0, volume=None if plan.volume is None else 0.0)
    if plan.mass > 0:
        from ..bodies.csg import Assembly

        # body + pocket filled = body + the ballast's shape at the density difference:
        # the same mass properties, the same support (the shape is inside the body)
        with_ballast = Assembly((body, ballast_body(plan, target)))
        after = check(with_ballast, target.down, g=g, require_tilt_deg=every,
                      tolerance=before.support.tolerance)
    else:
        after = before
    own = plan.mass if plan.volume is None else density * plan.volume
    return BalanceResult(
        own, plan.point, margin, require_tilt_deg, target.down, before, after,
        meets(after, margin, require_tilt_deg, before.support.tolerance, toward), material,
        density if plan.volume is not None else None, plan.volume, plan.shape,
        plan.dimensions or None, plan.depth, toward, plan.mass, pocket and plan.mass > 0)
