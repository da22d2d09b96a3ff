"""Potential energy: the seed's ``Mgh`` of the centre of mass (section 2.4, equation 23).

The potential energy of a system of particles, or of a rigid body, relative to a
datum is that of a single particle of its whole mass at its centre of mass:
``Σ mᵢ g zᵢ = M g z_G``. From it:

* :func:`potential_energy` — ``Mg(h − datum)``, h the height of the centre of mass;
* :func:`pose_energy_change` — the change between two resting poses, each
  measured as the height of the centre of mass above the plane the body rests on
  (a 1 × 1 × 4 block gains ``3Mgh/2`` going from lying to upright);
* :func:`lift_energy` — the work to raise all the material of a structure from a
  ground datum to where it stands, ``M g z_G`` (the Great Pyramid: about 2.34e12 J);
* :func:`crew_time` — that work in days of labour, for a given work per person per
  day and a crew size (1000 people each lifting 1000 kg through 1 m a day: about
  652 years).

Heights are along ``up``: +z for solids, +y for a lamina in its own plane.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .arguments import answering, count, finite_result, instance, number, positive, unit_vector, vector
from .errors import ArgumentError
from .massprops import MassProperties
from .results import Key, Result, Source
from .tolerances import contact_tolerance
from .units import SEED_GRAVITY

__all__ = [
    "DAYS_PER_YEAR",
    "PotentialEnergy",
    "PoseChange",
    "LiftEnergy",
    "CrewTime",
    "potential_energy",
    "pose_energy_change",
    "lift_energy",
    "crew_time",
    "seed_work_per_day",
]

DAYS_PER_YEAR = 365.25


def seed_work_per_day(g: float = SEED_GRAVITY) -> float:
    """The seed's day of work: lifting 1000 kg through 1 m, ``1000 g`` J.

    >>> seed_work_per_day()
    9810.0
    """
    return 1000.0 * positive(g, "g")


def _props(body_or_props, given: MassProperties | None = None) -> MassProperties:
    """The mass properties of a body (or the ones given), checked to be mass properties."""
    if given is None and isinstance(body_or_props, MassProperties):
        return body_or_props
    if given is not None:
        return instance(given, "props", MassProperties)
    return answering(body_or_props, "body", "mass_properties").mass_properties()


def _up(dim: int, up, down=None) -> np.ndarray:
    """The unit upward direction: −``down`` (gravity's direction, the library's one
    spelling of an orientation, as ``check`` and ``poses`` take it), or ``up`` (the older
    spelling, still read); default +z, +y for a lamina."""
    if up is not None and down is not None:
        raise ArgumentError("give the direction of gravity as down, or up, not both")
    if up is None and down is None:
        return np.array([0.0, 1.0]) if dim == 2 else np.array([0.0, 0.0, 1.0])
    what, given = ("up", up) if down is None else ("down", down)
    v = vector(given, what, (dim, 3))
    if dim == 2 and v.size == 3:
        if v[2] != 0:
            raise ArgumentError(f"{what} must lie in a lamina's plane (z = 0), not {tuple(v)}")
        v = v[:2]
    v = unit_vector(v, what, (dim,))
    return v if down is None else -v


def _energy(mass: float, g: float, height: float, what: str) -> float:
    """``mass · g · height``, J, refused when it overflows (g = 1e308, a datum at 1e308)."""
    return float(finite_result(mass * g * finite_result(height, "the height"), what))


@dataclass(frozen=True, repr=False)
class PotentialEnergy(Result):
    """``energy = mass · g · height``, J; height (m) of the centre of mass above ``datum``."""

    energy: float
    mass: float
    height: float
    datum: float
    g: float

    KEYS = (
        Key("energy", "J", "the potential energy, mass · g · height", type="float"),
        Key("mass", "kg", "the mass", type="float"),
        Key("height", "m", "the centre of mass's height above the datum", type="float"),
        Key("datum", "m", "the height of the zero of potential energy", type="float"),
        Key("g", "m/s²", "gravitational acceleration", type="float"),
    )


def potential_energy(body_or_props, *, datum: float = 0.0, g: float = SEED_GRAVITY,
                     down=None, up=None) -> PotentialEnergy:
    """The potential energy ``Mg(h − datum)`` of a body, J.

    Parameters
    ----------
    body_or_props : Body or MassProperties
        The body, or its mass properties.
    datum : float, default 0
        Height of the zero of potential energy against ``down``, m.
    g : float, default 9.81
        m/s².
    down : array_like, optional
        The direction of gravity, as :func:`~plumbob.stability.check` takes it (default
        −z, −y for a lamina); heights are measured against it. ``up`` (its opposite) is
        the older spelling, still read; give one of them.

    Returns
    -------
    PotentialEnergy
        ``energy`` J, ``mass``, ``height`` above the datum, ``datum``, ``g``.

    Examples
    --------
    >>> from plumbob.massprops import point_mass
    >>> potential_energy(point_mass(2.0, [0.0, 0.0, 3.0]), g=10.0)
    PotentialEnergy(energy=60 J, mass=2 kg, height=3 m, datum=0 m, g=10 m/s²)
    >>> potential_energy(point_mass(2.0, [0.0, 0.0, 3.0]), datum=5.0, g=10.0).energy   # below
    -40.0
    >>> potential_energy(point_mass(2.0, [0.0, 0.0, 3.0]), g=0.0)
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: g must be a positive number, not 0
    """
    props = _props(body_or_props)
    g, datum = positive(g, "g"), number(datum, "datum")
    height = float(props.center_of_mass @ _up(props.dim, up, down)) - datum
    return PotentialEnergy(_energy(props.mass, g, height, "the potential energy"), props.mass,
                           height, datum, g)


@dataclass(frozen=True, repr=False)
class PoseChange(Result):
    """From resting with ``down_from`` to resting with ``down_to`` (body-frame unit vectors).

    height_from, height_to: heights of the centre of mass above the plane, m.
    energy: ``Mg(height_to − height_from)``, J (positive: work must be done).
    """

    down_from: np.ndarray
    down_to: np.ndarray
    height_from: float
    height_to: float
    energy: float
    mass: float
    g: float

    KEYS = (
        Key("down_from", "", "the direction of gravity resting before, body frame (unit vector)",
            type="xyz"),
        Key("down_to", "", "the direction of gravity resting after", type="xyz"),
        Key("height_from", "m", "the centre of mass's height above the plane before",
            type="float"),
        Key("height_to", "m", "its height after", type="float"),
        Key("energy", "J", "Mg(height_to − height_from): positive, work must be done",
            type="float"),
        Key("mass", "kg", "the mass", type="float"),
        Key("g", "m/s²", "gravitational acceleration", type="float"),
    )


def _rest_height(body, props: MassProperties, down) -> tuple[float, np.ndarray]:
    """Height of the centre of mass above the plane the body rests on along ``down``."""
    from .stability.support import body_size, support_points, unit_vector

    d = unit_vector(down, props.dim)
    tol = contact_tolerance(body_size(body))
    pts = support_points(body, d, tol)
    return float(np.max(pts @ d) - props.center_of_mass @ d), d


def pose_energy_change(body, down_from, down_to, *, g: float = SEED_GRAVITY,
                       props: MassProperties | None = None) -> PoseChange:
    """The change in potential energy between two resting poses, J.

    Parameters
    ----------
    body : Body
        Any plumbob body.
    down_from, down_to : array_like, shape (dim,)
        Gravity's direction in the body's frame, resting before and after.
    g : float, default 9.81
        m/s².
    props : MassProperties, optional
        The body's mass properties, when already computed.

    Returns
    -------
    PoseChange
        The heights of the centre of mass above the plane in each pose and
        ``energy = Mg(height_to − height_from)`` (positive: work must be done).

    Examples
    --------
    >>> from plumbob.bodies.primitives import box
    >>> block = box(1, 1, 4, density=1000.0)   # mass 4000 kg, h = 1 m
    >>> change = pose_energy_change(block, [1, 0, 0], [0, 0, -1])   # lying → upright
    >>> change.height_from, change.height_to, change.energy / (4000 * 9.81)
    (0.5, 2.0, 1.5)
    >>> pose_energy_change(block, [0, 0, -1], [0, 0, -1]).energy   # no change
    0.0
    """
    props = _props(body, props)
    g = positive(g, "g")
    h0, d0 = _rest_height(body, props, down_from)
    h1, d1 = _rest_height(body, props, down_to)
    return PoseChange(d0, d1, h0, h1, _energy(props.mass, g, h1 - h0, "the energy change"),
                      props.mass, g)


@dataclass(frozen=True, repr=False)
class LiftEnergy(Result):
    """The work to raise a structure's material from the ground datum to where it stands.

    mass: kg. center_of_mass: (dim,) m. datum: height of the ground against ``down`` (along −down), m.
    com_height: height of the centre of mass above the datum, m.
    lift_energy: ``mass · g · com_height``, J (the key of ``plumbob lift --json``). g: m/s².
    """

    mass: float
    center_of_mass: np.ndarray
    datum: float
    com_height: float
    lift_energy: float
    g: float
    source: Source | None = field(default=None, compare=False)

    _repr_fields = ("mass", "center_of_mass", "datum", "com_height", "lift_energy", "g")

    def text(self, units=None, *, crew=None) -> str:
        """The report ``plumbob lift`` prints (``str(lift)``): lengths and masses in
        ``units`` (a :class:`~plumbob.report.ReportUnits` or ``"mm,g"``; default the
        part's own, else SI), energies in J; with a :class:`CrewTime`, the days of work."""
        from .report import units_for
        from .report.lift import lift_text

        s = self.source or Source()
        return lift_text(self, s.path or "body", units_for(units, s.length_unit), crew=crew,
                         notes=s.notes, size=s.size)

    #: the keys of ``plumbob lift --json`` after the file's (docs/cli.md's table)
    KEYS = (
        Key("mass", "kg", "the mass", type="float"),
        Key("center_of_mass", "m", "the centre of mass, body frame", type="xyz"),
        Key("datum", "m", "the ground's height against `down` (default: the body's lowest "
                          "point)", type="float"),
        Key("com_height", "m", "the centre of mass's height above the datum", type="float"),
        Key("lift_energy", "J", "the work to raise the material from the datum, M g z_G",
            type="float"),
        Key("g", "m/s²", "gravitational acceleration", type="float"),
    )


def lift_energy(body, *, datum: float | None = None, g: float = SEED_GRAVITY, down=None,
                up=None, props: MassProperties | None = None) -> LiftEnergy:
    """The lift (build) energy ``M g z_G`` of a structure, J.

    Parameters
    ----------
    body : Body
        Any plumbob body.
    datum : float, optional
        The ground's height against ``down``, m; default the body's lowest point (the
        ground it is built on).
    g : float, default 9.81
        m/s².
    down : array_like, optional
        The direction of gravity (default −z, −y for a lamina). ``up`` (its opposite) is
        the older spelling, still read; give one of them.
    props : MassProperties, optional
        The body's mass properties, when already computed.

    Returns
    -------
    LiftEnergy
        ``mass``, ``center_of_mass``, ``datum``, ``com_height`` and ``lift_energy``
        (J), the keys of ``plumbob lift --json``.

    Examples
    --------
    >>> from plumbob.bodies.primitives import box
    >>> lift = lift_energy(box(2, 2, 10, density=1.0), g=10.0)   # 40 kg raised 5 m
    >>> lift
    LiftEnergy(mass=40 kg, center_of_mass=[1, 1, 5] m, datum=0 m, com_height=5 m, \
lift_energy=2000 J, g=10 m/s²)

    Below the datum the energy is negative (it is released):

    >>> lift_energy(box(2, 2, 10, density=1.0), datum=20.0, g=10.0).lift_energy
    -6000.0
    """
    from .stability.support import hull_points

    props = _props(body, props)
    g = positive(g, "g")
    u = _up(props.dim, up, down)
    datum = float(np.min(hull_points(body) @ u)) if datum is None else number(datum, "datum")
    height = float(props.center_of_mass @ u) - datum
    return LiftEnergy(props.mass, props.center_of_mass, datum, height,
                      _energy(props.mass, g, height, "the lift energy"), g)


@dataclass(frozen=True, repr=False)
class CrewTime(Result):
    """An amount of work in days of labour.

    work_per_day: J one person does in a day. crew: people.
    person_days: energy / work_per_day. crew_days: person_days / crew.
    crew_years: crew_days / 365.25.
    """

    energy: float
    work_per_day: float
    crew: int
    person_days: float
    crew_days: float
    crew_years: float

    _repr_units = {"energy": "J"}
    #: the crew keys of ``plumbob lift --json`` (the energy is the lift's ``lift_energy``)
    KEYS = (
        Key("work_per_day", "J", "the work one person does in a day", type="float"),
        Key("crew", "", "people working at once", type="int"),
        Key("person_days", "", "the work in days of one person", type="float"),
        Key("crew_days", "", "the days the crew takes", type="float"),
        Key("crew_years", "", "the same in years of 365.25 days", type="float"),
    )


def crew_time(energy: float, work_per_day: float, crew: int = 1) -> CrewTime:
    """How long a crew takes to do an amount of work.

    Parameters
    ----------
    energy : float
        The work, J (≥ 0).
    work_per_day : float
        J one person does in a day (:func:`seed_work_per_day`: 1000 kg through 1 m).
    crew : int, default 1
        People working at once.

    Returns
    -------
    CrewTime
        ``person_days``, ``crew_days`` and ``crew_years`` (of 365.25 days).

    Examples
    --------
    >>> t = crew_time(2.34e12, seed_work_per_day(), 1000)
    >>> round(t.crew_days, -3), round(t.crew_years)
    (239000.0, 653)
    >>> crew_time(0.0, 1000.0).person_days
    0.0
    >>> crew_time(1e6, 1000.0, crew=0)
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: crew must be a whole number of at least 1, not 0
    """
    work = positive(work_per_day, "the work per person per day")
    crew = count(crew, "crew", math.inf, minimum=1)
    energy = number(energy, "the work to do")
    if energy < 0:
        raise ArgumentError(f"the work to do must not be negative, not {energy:g}")
    person_days = float(finite_result(energy / work, "the number of person-days"))
    crew_days = person_days / crew
    return CrewTime(energy, work, crew, person_days, crew_days, crew_days / DAYS_PER_YEAR)
