"""Particle systems in motion, momentum and collisions (the seed's sections 1, 3 and 4).

* :mod:`.motion` — integrate a particle system with springs, rods, strings, gravity,
  applied forces and friction (``solve_ivp``); paths of the particles and the centre of mass.
* :mod:`.collisions` — Newton's law of restitution for smooth, non-rotating bodies.
* :mod:`.two_particle` — the lift over a pulley, the mace's balance point, the vibrating
  molecule and the other closed forms of section 1.

Simulation specs in TOML are read by :mod:`plumbob.spec` (``load_simulation``), which
builds the :class:`MotionModel` here. scipy is imported only when a simulation runs.
"""

from .collisions import (
    CollisionResult,
    ImpactCheck,
    bounce_heights,
    check_impact,
    collide,
    restitution_from_bounces,
)
from .motion import Link, MotionModel, SimulationResult, Spring, simulate
from .two_particle import (
    MaceBalance,
    PulleyLift,
    RigidPair,
    VibratingMolecule,
    center_of_mass_acceleration,
    mace_balance_point,
    max_pull_before_break,
    partner_position,
    pulley_lift,
    rigid_pair,
    spring_pair_pull,
)

__all__ = [
    "CollisionResult", "ImpactCheck", "bounce_heights", "check_impact", "collide",
    "restitution_from_bounces",
    "Link", "MotionModel", "SimulationResult", "Spring", "simulate",
    "MaceBalance", "PulleyLift", "RigidPair", "VibratingMolecule", "center_of_mass_acceleration",
    "mace_balance_point", "max_pull_before_break", "partner_position", "pulley_lift",
    "rigid_pair", "spring_pair_pull",
]
