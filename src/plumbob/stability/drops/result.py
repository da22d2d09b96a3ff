"""What :func:`~plumbob.stability.drops.drop_poses` answers: :class:`DropPose` and :class:`Drops`.

Frozen results in SI units; ``as_dict()`` is the JSON of ``plumbob poses --dynamic
--json`` (keys in ``docs/cli.md``), laid out like the quasi-static
:class:`~plumbob.stability.poses.Poses` so a reader can put the two side by side.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...results import Key, Result

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

    #: the keys of each of ``plumbob poses --dynamic --json``'s ``poses``
    KEYS = (
        Key("down", "", "the pose's direction of gravity, body frame (unit vector)",
            type="xyz"),
        Key("probability", "", "of the drops that landed in a pose, the share that landed "
                               "here", type="float"),
        Key("drops", "", "how many drops landed here", type="int"),
        Key("interval", "", "Wilson's 95 % interval of the probability, [low, high]"),
        Key("standard_error", "", "sqrt(p (1 − p) / n)", type="float"),
        Key("quasi_static", "", "the quasi-static probability of the same pose",
            type="float"),
        Key("neutral", "", "whether the pose is a rolling family", type="bool"),
    )

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

    #: the method, always ``"dynamic"`` (the quasi-static :class:`Poses` say ``exact``)
    method = "dynamic"
    #: the confidence of the intervals
    confidence = CONFIDENCE

    #: the keys of ``plumbob poses --dynamic --json`` after the file's
    KEYS = (
        Key("method", "", "`dynamic`", type="str"),
        Key("engine", "", "the physics engine and its version", type="str"),
        Key("mass", "kg", "the mass", type="float"),
        Key("center_of_mass", "m", "the centre of mass, body frame", type="xyz"),
        Key("drops", "", "drops simulated", type="int"),
        Key("landed", "", "drops that came to rest in a pose", type="int"),
        Key("unsettled", "", "drops still moving at the time limit, or at rest in no pose",
            type="int"),
        Key("seed", "", "the seed of the random orientations", type="int"),
        Key("drop_height", "m", "the lowest point's height above the ground at release",
            type="float"),
        Key("restitution", "", "the contact's coefficient of restitution", type="float"),
        Key("friction", "", "the contact's coefficient of friction", type="float"),
        Key("overdamped", "", "whether rotation was heavily damped and the contact without "
                              "bounce", type="bool"),
        Key("timestep", "s", "the engine's time step", type="float"),
        Key("confidence", "", "the confidence of the intervals (0.95)", type="float"),
        Key("poses", "", "every pose, most probable first (the keys below)"),
        Key("notes", "", "what a reader should know", "when there are any", type="strings"),
    )
