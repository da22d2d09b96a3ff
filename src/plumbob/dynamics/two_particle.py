"""The two-particle systems of the seed's section 1, in closed form.

* the lift over a pulley (Exercise 1): acceleration, cable tension, pulley reaction;
* the drum major's mace (equation 5): the balance point;
* the vibrating (nitrogen) molecule: centre of mass in uniform motion, the bond
  length in simple harmonic motion;
* Example 2: two equal masses joined by a spring, one pulled by a constant force;
* pairs moving together under one external force (Exercises 8 and 10).

Units: kg, m, s, N, m/s, m/s². Gravity ``g`` defaults to 9.81 m/s².
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..arguments import positive
from ..errors import DynamicsError
from ..results import Result
from ..units import SEED_GRAVITY

__all__ = [
    "PulleyLift",
    "pulley_lift",
    "MaceBalance",
    "mace_balance_point",
    "VibratingMolecule",
    "spring_pair_pull",
    "RigidPair",
    "rigid_pair",
    "max_pull_before_break",
    "center_of_mass_acceleration",
    "partner_position",
]


def _positive(value: float, label: str, unit: str) -> float:
    return positive(value, f"{label} ({unit})", error=DynamicsError)


# ---------------------------------------------------------------------- lift
@dataclass(frozen=True, repr=False)
class PulleyLift(Result):
    """A lift and a counterweight on a light inextensible cable over a light pulley.

    counterweight, lift: masses m₁, m₂, kg.
    g: gravitational acceleration, m/s².
    acceleration: of the lift, downwards positive, m/s²: (m₂ − m₁) g / (m₁ + m₂).
    tension: in the cable, N: 2 m₁ m₂ g / (m₁ + m₂).
    pulley_reaction: the force holding the pulley's axle, N: 4 m₁ m₂ g / (m₁ + m₂)
        (it is less than the total weight (m₁ + m₂) g while the masses accelerate).
    """

    counterweight: float
    lift: float
    g: float
    acceleration: float
    tension: float
    pulley_reaction: float

    def speed_after(self, distance: float) -> float:
        """Speed (m/s) of the lift, released from rest, after it has moved ``distance`` m:
        v² = 2 a d."""
        distance = float(distance)
        if not (math.isfinite(distance) and distance >= 0):
            raise DynamicsError(f"the distance travelled must be non-negative (got {distance} m)")
        return math.sqrt(2.0 * abs(self.acceleration) * distance)

    def time_to(self, distance: float) -> float:
        """Time (s) for the lift, released from rest, to move ``distance`` m: d = ½ a t²."""
        if self.acceleration == 0:
            raise DynamicsError("balanced masses: the lift never moves from rest")
        distance = float(distance)
        if not (math.isfinite(distance) and distance >= 0):
            raise DynamicsError(f"the distance travelled must be non-negative (got {distance} m)")
        return math.sqrt(2.0 * distance / abs(self.acceleration))


def pulley_lift(counterweight: float, lift: float, g: float = SEED_GRAVITY) -> PulleyLift:
    """The seed's lift (Exercise 1): masses in kg, ``g`` in m/s².

    Part (d): lift and counterweight 1000 kg, a 65 kg passenger in the lift.

    >>> lift = pulley_lift(1000, 1065)
    >>> round(lift.acceleration, 2), round(lift.speed_after(100), 1)
    (0.31, 7.9)
    """
    m1 = _positive(counterweight, "the counterweight's mass", "kg")
    m2 = _positive(lift, "the lift's mass", "kg")
    g = _positive(g, "g", "m/s²")
    total = m1 + m2
    tension = 2.0 * m1 * m2 * g / total
    return PulleyLift(m1, m2, g, (m2 - m1) * g / total, tension, 2.0 * tension)


# ---------------------------------------------------------------------- mace
@dataclass(frozen=True, repr=False)
class MaceBalance(Result):
    """The balance point G of two masses on a light rod (seed equation 5).

    head, tail: masses m₁ (at A) and m₂ (at B), kg.  length: |AB|, m.
    from_head, from_tail: distances d₁ = |AG| and d₂ = |GB|, m; d₁/d₂ = m₂/m₁.
    """

    head: float
    tail: float
    length: float
    from_head: float
    from_tail: float


def mace_balance_point(head: float, tail: float, length: float) -> MaceBalance:
    """Where to hold (and catch) a mace: masses kg, length m.

    >>> b = mace_balance_point(3.0, 1.0, 1.2)
    >>> round(b.from_head, 12), round(b.from_tail, 12)
    (0.3, 0.9)
    """
    m1 = _positive(head, "the head's mass", "kg")
    m2 = _positive(tail, "the tail's mass", "kg")
    length = _positive(length, "the rod's length", "m")
    d1 = length * m2 / (m1 + m2)
    return MaceBalance(m1, m2, length, d1, length - d1)


# ------------------------------------------------------------------ molecule
@dataclass(frozen=True)
class VibratingMolecule:
    """Two particles joined by a spring, free of external forces, moving along its line.

    m1, m2: masses, kg.  stiffness: k, N/m.  natural_length: l₀, m.

    The centre of mass moves uniformly; the separation s = x₂ − x₁ oscillates about
    l₀ with angular frequency ω = √(k (m₁ + m₂) / (m₁ m₂)) (√(2k/m) for equal masses).
    """

    m1: float
    m2: float
    stiffness: float
    natural_length: float

    def __post_init__(self) -> None:
        for label, value, unit in (("m1", self.m1, "kg"), ("m2", self.m2, "kg"),
                                   ("stiffness", self.stiffness, "N/m"),
                                   ("natural_length", self.natural_length, "m")):
            object.__setattr__(self, label, _positive(value, label, unit))

    @property
    def angular_frequency(self) -> float:
        """ω, rad/s."""
        return math.sqrt(self.stiffness * (self.m1 + self.m2) / (self.m1 * self.m2))

    @property
    def period(self) -> float:
        """2π/ω, s."""
        return 2.0 * math.pi / self.angular_frequency

    def positions(self, t: float | np.ndarray, x1: float, x2: float, v1: float = 0.0,
                  v2: float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(x₁(t), x₂(t), x_G(t)) in m, from positions x1 < x2 (m) and velocities (m/s) at t = 0.

        >>> mol = VibratingMolecule(1.0, 1.0, 2.0, 1.0)       # ω = 2 rad/s
        >>> [round(float(a), 12) for a in mol.positions(np.pi / 2, 0.0, 1.5)]
        [0.5, 1.0, 0.75]
        """
        t = np.asarray(t, dtype=float)
        total = self.m1 + self.m2
        xg0 = (self.m1 * x1 + self.m2 * x2) / total
        vg = (self.m1 * v1 + self.m2 * v2) / total
        w = self.angular_frequency
        s = self.natural_length + (x2 - x1 - self.natural_length) * np.cos(w * t) + \
            (v2 - v1) / w * np.sin(w * t)
        xg = xg0 + vg * t
        return xg - self.m2 / total * s, xg + self.m1 / total * s, xg


# ------------------------------------------------------------------ example 2
def spring_pair_pull(mass: float, stiffness: float, natural_length: float, pull: float,
                     t: float | np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Seed Example 2 in closed form: x-coordinates (x_A, x_B, x_G) in m at times ``t`` (s).

    Two particles of ``mass`` kg at rest on a smooth horizontal surface, joined by a
    spring of ``stiffness`` N/m and natural length 2l₀ = ``natural_length`` m, centre of
    mass at the origin; a constant force ``pull`` N acts on B along AB from t = 0:
    x_G = P t²/(4m), x_B,A = x_G ± (l₀ + P/(4k) − P/(4k) cos ωt), ω = √(2k/m).

    >>> [float(np.round(x, 12)) for x in spring_pair_pull(1.0, 2.0, 2.0, 8.0, 0.0)]
    [-1.0, 1.0, 0.0]
    """
    m = _positive(mass, "mass", "kg")
    k = _positive(stiffness, "stiffness", "N/m")
    l0 = 0.5 * _positive(natural_length, "natural length", "m")
    p = float(pull)
    t = np.asarray(t, dtype=float)
    w = math.sqrt(2.0 * k / m)
    xg = p * t * t / (4.0 * m)
    d = l0 + p / (4.0 * k) * (1.0 - np.cos(w * t))
    return xg - d, xg + d, xg


# --------------------------------------------------------- pairs moving as one
@dataclass(frozen=True, repr=False)
class RigidPair(Result):
    """Two particles moving together (a taut string or a rod), one pulled by a force.

    pulled, other: masses, kg.  force: the external pull on ``pulled``, N.
    acceleration: the common acceleration F / (m_pulled + m_other), m/s².
    internal_force: magnitude of the force between them, m_other · a, N.
    """

    pulled: float
    other: float
    force: float
    acceleration: float
    internal_force: float


def rigid_pair(pulled: float, other: float, force: float) -> RigidPair:
    """Seed Exercise 10: 20 N on a 1 kg particle dragging a 4 kg one: a = 4 m/s², 16 N.

    >>> p = rigid_pair(1.0, 4.0, 20.0)
    >>> p.acceleration, p.internal_force
    (4.0, 16.0)
    """
    m_p = _positive(pulled, "the pulled particle's mass", "kg")
    m_o = _positive(other, "the other particle's mass", "kg")
    f = float(force)
    if not math.isfinite(f):
        raise DynamicsError(f"the force must be a finite number (got {force!r} N)")
    a = f / (m_p + m_o)
    return RigidPair(m_p, m_o, f, a, abs(m_o * a))


def max_pull_before_break(pulled: float, other: float, breaking_tension: float) -> float:
    """The largest pull (N) on one particle before the string to the other breaks.

    Seed Exercise 8: two 50 kg particles, a 10 N string: 20 N.

    >>> max_pull_before_break(50, 50, 10)
    20.0
    """
    m_p = _positive(pulled, "the pulled particle's mass", "kg")
    m_o = _positive(other, "the other particle's mass", "kg")
    t = _positive(breaking_tension, "the breaking tension", "N")
    return t * (m_p + m_o) / m_o


# ------------------------------------------------------------- centre of mass
def center_of_mass_acceleration(masses: Sequence[float] | np.ndarray,
                                external_forces: Sequence | np.ndarray) -> np.ndarray:
    """a_G = Σ Eᵢ / M (seed equation 19), m/s²: masses (n,) kg, external forces (n, d) N.

    Internal forces do not enter. Seed Exercise 9 (friction 0.4 on a rough wire):

    >>> g = 9.81
    >>> center_of_mass_acceleration([3, 0.5], [[-0.4 * 3 * g], [-0.4 * 0.5 * g]]) / g
    array([-0.4])
    """
    m = np.asarray(masses, dtype=float).reshape(-1)
    if m.size == 0 or not np.all(np.isfinite(m)) or np.any(m <= 0):
        raise DynamicsError("every mass must be positive and finite")
    f = np.asarray(external_forces, dtype=float).reshape(len(m), -1)
    if not np.all(np.isfinite(f)):
        raise DynamicsError("an external force is not a finite number")
    return f.sum(axis=0) / m.sum()


def partner_position(total_mass_center: Sequence[float] | np.ndarray | float,
                     known_mass: float, known_position: Sequence[float] | np.ndarray | float,
                     other_mass: float) -> np.ndarray:
    """Where the second particle of a pair is, given the centre of mass and the first (m).

    r₂ = ((m₁ + m₂) r_G − m₁ r₁) / m₂. Seed Exercise 6: G at x = 3, B at x = 3 ⇒ A at 3.

    >>> partner_position(3.0, 1.0, 3.0, 1.0)
    array([3.])
    """
    m1 = _positive(known_mass, "the known particle's mass", "kg")
    m2 = _positive(other_mass, "the other particle's mass", "kg")
    rg = np.asarray(total_mass_center, dtype=float).reshape(-1)
    r1 = np.asarray(known_position, dtype=float).reshape(-1)
    if rg.shape != r1.shape:
        raise DynamicsError("the centre of mass and the position need the same dimension")
    return ((m1 + m2) * rg - m1 * r1) / m2
