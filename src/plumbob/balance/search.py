"""The best plane cut of the interior: exact, starting from the relaxation's.

The relaxation over cells (:mod:`plumbob.balance.relax`) says the optimum empties a
half-space of the interior. Here the half-space is found on the interior's exact
mesh: for a cut ``{p : n·p ≥ τ}`` the emptied volume and its centroid come from
:class:`plumbob.balance.cuts.PlaneCuts` (one vectorised pass), so the carved body's
centre — and every target row's slack — is exact for each ``(n, τ)`` tried:

* along ``τ`` for one ``n``: a scan of the interior's span, then Brent's method
  (``minimize_scalar``) about the best level, for the best least slack; Brent's root
  finder (``brentq``) for the level where the slack first reaches what is asked;
* over ``n``: about the relaxation's normal — in the ground plane when every row is
  horizontal (a margin), else over the sphere (Nelder–Mead).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .cuts import PlaneCuts
from .relax import row_gradients

__all__ = ["Carver", "Cut"]

_LEVELS = 24  # levels of the first scan along a normal
_TURN = 0.5  # radians searched either side of the relaxation's normal, in the ground plane


class Cut(NamedTuple):
    """A plane cut: the interior where ``normal · p ≥ offset`` is emptied.

    normal: (3,) unit. offset: m. slack: m, the least row slack of the carved body.
    volume: m³ emptied.
    """

    normal: np.ndarray
    offset: float
    slack: float
    volume: float


class Carver:
    """A body (mass kg, centre (3,) m, density kg/m³) and its interior's mesh, to be cut."""

    def __init__(self, interior: np.ndarray, density: float, mass: float, centre: np.ndarray):
        self.cuts = PlaneCuts(interior)
        self.density, self.mass = float(density), float(mass)
        self.moment = self.mass * np.asarray(centre, dtype=float)
        self._along: tuple[tuple, object] | None = None

    def centre(self, normal: np.ndarray, offset: float) -> tuple[np.ndarray, float]:
        """The carved body's centre of mass (3,) m and the volume emptied, m³."""
        key = tuple(np.asarray(normal, dtype=float).tolist())
        if self._along is None or self._along[0] != key:
            self._along = (key, self.cuts.along(normal))
        volume, first = self._along[1].moments(offset)
        left = self.mass - self.density * volume
        return (self.moment - self.density * first) / left, volume

    def slack(self, target, normal: np.ndarray, offset: float) -> tuple[float, float]:
        """The carved body's least row slack (m) and the volume emptied (m³)."""
        centre, volume = self.centre(normal, offset)
        return float(np.min(target.slack(centre))), volume

    def best_along(self, target, normal: np.ndarray) -> Cut:
        """The level along ``normal`` whose cut leaves the largest least slack."""
        from scipy.optimize import minimize_scalar

        lo, hi = self.cuts.span(normal)
        levels = np.linspace(lo, hi, _LEVELS + 1)
        values = [self.slack(target, normal, t)[0] for t in levels]
        k = int(np.argmax(values))
        a, b = levels[max(k - 1, 0)], levels[min(k + 1, _LEVELS)]
        found = minimize_scalar(lambda t: -self.slack(target, normal, t)[0], bounds=(a, b),
                                method="bounded", options={"xatol": 1e-7 * (hi - lo)})
        offset = float(found.x) if -found.fun >= values[k] else float(levels[k])
        slack, volume = self.slack(target, normal, offset)
        return Cut(normal, offset, slack, volume)

    def least_along(self, target, normal: np.ndarray, safety: float,
                    lightest: bool = False) -> Cut | None:
        """The cut along ``normal`` that leaves every slack ≥ ``safety`` m emptying the
        least (``lightest``: the most); None when no level along it does."""
        from scipy.optimize import brentq

        best = self.best_along(target, normal)
        if best.slack < safety:
            return None
        lo, hi = self.cuts.span(normal)
        end = lo if lightest else hi
        if self.slack(target, normal, end)[0] >= safety:
            offset = end
        else:
            offset = brentq(lambda t: self.slack(target, normal, t)[0] - safety, best.offset,
                            end, xtol=1e-9 * (hi - lo))
            # onto the side that meets it
            step = 1e-9 * (hi - lo)
            while self.slack(target, normal, offset)[0] < safety and step < hi - lo:
                offset += -step if not lightest else step
                step *= 2
        slack, volume = self.slack(target, normal, offset)
        return Cut(normal, float(offset), slack, volume)

    def search(self, target, start: np.ndarray, score) -> Cut | None:
        """The cut whose ``score(normal) -> (value, Cut | None)`` is least, over normals
        about ``start``."""
        from scipy.optimize import minimize, minimize_scalar

        grads = row_gradients(target)
        down = getattr(target, "down", None)
        start = np.asarray(start, dtype=float)
        if not np.any(start):
            start = -grads.mean(axis=0)
        if not np.any(start):  # rows that cancel (a rectangle's): away from the worst one
            start = -grads[int(np.argmin(target.slack(self.moment / self.mass)))]
        if not np.any(start):
            start = np.array([1.0, 0.0, 0.0])
        start = start / np.linalg.norm(start)
        found: dict[tuple, tuple[float, Cut | None]] = {}

        def at(normal: np.ndarray) -> float:
            key = tuple(np.round(normal, 12))
            if key not in found:
                found[key] = score(normal)
            return found[key][0]

        if down is not None and np.allclose(grads @ np.asarray(down, dtype=float), 0.0,
                                            atol=1e-12 * max(np.abs(grads).max(), 1e-300)):
            d = np.asarray(down, dtype=float) / np.linalg.norm(down)
            e1 = start - (start @ d) * d
            e1 = e1 / np.linalg.norm(e1)
            e2 = np.cross(d, e1)

            def turned(angle: float) -> np.ndarray:
                return np.cos(angle) * e1 + np.sin(angle) * e2

            angles = np.linspace(-_TURN, _TURN, 9)
            values = [at(turned(a)) for a in angles]
            k = int(np.argmin(values))
            a, b = angles[max(k - 1, 0)], angles[min(k + 1, len(angles) - 1)]
            minimize_scalar(lambda a: at(turned(a)), bounds=(a, b), method="bounded",
                            options={"xatol": 1e-4})
        else:
            helper = np.eye(3)[int(np.argmin(np.abs(start)))]
            e1 = np.cross(start, helper)
            e1 /= np.linalg.norm(e1)
            e2 = np.cross(start, e1)

            def tipped(v: np.ndarray) -> np.ndarray:
                n = start + v[0] * e1 + v[1] * e2
                return n / np.linalg.norm(n)

            minimize(lambda v: at(tipped(v)), np.zeros(2), method="Nelder-Mead",
                     options={"initial_simplex": [[0, 0], [0.2, 0], [0, 0.2]], "xatol": 1e-3,
                              "fatol": np.inf, "maxfev": 80})
        return min(found.values(), key=lambda item: item[0])[1]

    def best(self, target, start: np.ndarray) -> Cut:
        """The cut leaving the largest least slack, over normals about ``start``."""
        def score(normal):
            cut = self.best_along(target, normal)
            return -cut.slack, cut

        return self.search(target, start, score)

    def least(self, target, start: np.ndarray, safety: float, lightest: bool = False,
              best: Cut | None = None) -> Cut | None:
        """The cut emptying the least (``lightest``: the most) that leaves every slack ≥
        ``safety`` m, over normals about ``start``; None when none found does."""
        total = self.cuts.span(start)[1] - self.cuts.span(start)[0]

        def score(normal):
            cut = self.least_along(target, normal, safety, lightest)
            if cut is None:  # a penalty that still points toward where it can be met
                slack = self.best_along(target, normal).slack
                return 1e6 * (1.0 + (safety - slack) / total), None
            return (-cut.volume if lightest else cut.volume), cut

        cut = self.search(target, start, score)
        if cut is None and best is not None:
            return self.least_along(target, best.normal, safety, lightest)
        return cut
