"""What :func:`~plumbob.stability.drops.drop_poses` answers: :class:`DropPose` and :class:`Drops`.

Frozen results in SI units; ``as_dict()`` is the JSON of ``plumbob poses --dynamic
--json`` (keys in ``docs/cli.md``), laid out like the quasi-static
:class:`~plumbob.stability.poses.Poses` so a reader can put the two side by side.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...results import Result

__all__ = ["DropPose", "Drops", "wilson_interval", "CONFIDENCE"]

CONFIDENCE = 0.95
_Z = 1.959963984540054  # the two-sided 95 % normal quantile


def wilson_interval(hits: int, n: int, z: float = _Z) -> tuple[float, float]:
    """Wilson's score interval for a proportion ``hits / n`` (95 % by default): unlike
    p ± z·SE it stays inside [0, 1] and is not empty when no drop landed in a pose.

    >>> [round(v, 4) for v in wilson_interval(0, 100)]
    [0.0, 0.037]
    >>> [round(v, 4) for v in wilson_interval(50, 100)]
    [0.4038, 0.5962]
    """
    if n <= 0:
        return 0.0, 1.0
    p = hits / n
    denom = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / denom
    half = z / denom * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    low = 0.0 if hits == 0 else max(0.0, centre - half)  # exact at the ends, not 1e-19
    high = 1.0 if hits == n else min(1.0, centre + half)
    return low, high


@dataclass(frozen=True, repr=False)
class DropPose(Result):
    """One resting pose and how often the simulated drops landed in it.

    Attributes
    ----------
    down : numpy.ndarray
        (3,) unit vector in the body's frame pointing to the ground (the quasi-static
        pose's ``down``).
    probability : float
        Fraction of the drops that came to rest (and matched a pose) landing here.
    drops : int
        How many drops landed here.
    interval : tuple of float
        Wilson 95 % confidence interval of the probability.
    standard_error : float
        sqrt(p (1 − p) / n), n the drops that came to rest in a pose.
    quasi_static : float
        The quasi-static probability of the same pose, for comparison.
    neutral : bool
        The pose is a rolling family (matched by its axis, not one normal).
    """

    down: np.ndarray
    probability: float
    drops: int
    interval: tuple[float, float]
    standard_error: float
    quasi_static: float
    neutral: bool = False

    def as_dict(self) -> dict:
        """Keys ``down``, ``probability``, ``drops``, ``interval`` ([low, high]),
        ``standard_error``, ``quasi_static``, ``neutral``."""
        return {"down": self.down, "probability": self.probability, "drops": self.drops,
                "interval": list(self.interval), "standard_error": self.standard_error,
                "quasi_static": self.quasi_static, "neutral": self.neutral}

    def __repr__(self) -> str:
        low, high = self.interval
        return (f"DropPose(probability={self.probability:.4g} [{low:.4g}, {high:.4g}], "
                f"drops={self.drops}, quasi_static={self.quasi_static:.4g}, "
                f"down=({', '.join(f'{v:.4g}' for v in self.down)}))")


@dataclass(frozen=True, repr=False)
class Drops(Result):
    """The landings of Monte Carlo drops in MuJoCo, most probable pose first.

    Attributes
    ----------
    poses : tuple of DropPose
        Every quasi-static pose, with the drops that landed in it (possibly none).
    drops : int
        Drops simulated.
    landed : int
        Drops that came to rest in one of the poses (the probabilities' denominator).
    unsettled : int
        Drops still moving at the time limit, or at rest in no pose (balanced on an
        edge, say); left out of the probabilities.
    seed : int
        Seed of the random orientations: the same seed gives the same answer, whatever
        the number of processes.
    drop_height : float
        Height of the lowest point above the ground at release, m.
    restitution, friction : float
        Coefficient of restitution and of sliding friction of the contact.
    overdamped : bool
        The body's rotation was heavily damped and the contact without bounce: the
        drops that lose their energy at once, whose limit is the quasi-static model.
    timestep : float
        The engine's time step, s.
    mass : float
        kg.
    center_of_mass : numpy.ndarray
        (3,) m, body frame.
    engine : str
        The physics engine and its version.
    notes : tuple of str
        What a reader should know.
    """

    poses: tuple[DropPose, ...]
    drops: int
    landed: int
    unsettled: int
    seed: int
    drop_height: float
    restitution: float
    friction: float
    overdamped: bool
    timestep: float
    mass: float
    center_of_mass: np.ndarray
    engine: str
    notes: tuple[str, ...] = field(default=())

    _repr_fields = ("drops", "landed", "unsettled", "seed", "overdamped", "engine")

    def __len__(self) -> int:
        return len(self.poses)

    def __getitem__(self, index: int) -> DropPose:
        return self.poses[index]

    @property
    def probabilities(self) -> np.ndarray:
        """(len,) the poses' landing probabilities, in the order of :attr:`poses`."""
        return np.array([p.probability for p in self.poses])

    def as_dict(self) -> dict:
        """The JSON object of ``plumbob poses --dynamic --json`` without the file's keys:
        ``method`` ("dynamic"), the settings, the counts, ``poses`` (each
        :meth:`DropPose.as_dict`), ``confidence`` (0.95) and ``notes`` when any."""
        out = {"method": "dynamic", "engine": self.engine, "mass": self.mass,
               "center_of_mass": self.center_of_mass, "drops": self.drops,
               "landed": self.landed, "unsettled": self.unsettled, "seed": self.seed,
               "drop_height": self.drop_height, "restitution": self.restitution,
               "friction": self.friction, "overdamped": self.overdamped,
               "timestep": self.timestep, "confidence": CONFIDENCE,
               "poses": [p.as_dict() for p in self.poses]}
        if self.notes:
            out["notes"] = list(self.notes)
        return out
