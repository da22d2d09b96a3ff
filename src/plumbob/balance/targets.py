"""A stability target as linear conditions on the centre of mass.

Why linear: a body of mass ``M`` and centre ``c`` with masses ``m_j`` added at
points ``p_j`` has its centre at ``(M c + Σ m_j p_j) / (M + Σ m_j)``. A condition
``a · x − b ≥ 0`` on that centre is, after multiplying by the (positive) total
mass, ``M (a · c − b) + Σ m_j (a · p_j − b) ≥ 0``: linear in the added masses.
Ballast and carving (the moment of the weight is linear in the material kept)
are then small linear problems.

The rows, one per edge of the support polygon (its contact with the plane is
unchanged by ballast inside the body):

* **margin** ``μ``: the horizontal distance of the centre's projection inside the
  edge, ``d_e(p) = n_e · p − o_e`` (``n_e`` the inward horizontal unit normal), is
  at least ``μ``: the row ``n_e · p − (o_e + μ) ≥ 0``;
* **tilt** ``θ``: tilting the plane by ``θ`` toward the edge does not topple it.
  The body tips over ``e`` at ``atan(d_e / h)`` (``h`` the height of the centre
  above the plane, :mod:`plumbob.stability.verdict`), so the condition is
  ``d_e(p) − tan θ · h(p) ≥ 0`` with ``h(p) = up · p − up · q`` (``q`` a point of
  the plane): linear too.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import StabilityError
from ..stability.support import Support, support_polygon

__all__ = ["Target", "target_for"]


@dataclass(frozen=True)
class Target:
    """Linear conditions on the centre of mass that meet a stability target.

    A body of mass M and centre c with added masses m_j at points p_j meets the
    target iff for every row k: ``M*slack(c)[k] + sum_j m_j*slack(p_j)[k] >= 0``.

    normals: (k, dim) — dim 3 for solids, 2 for a lamina (in its own plane).
    offsets: (k,) m.
    down: (dim,) the unit direction of gravity the target is for.
    margin: the static stability margin asked for, m (None: none asked).
    require_tilt_deg: the tilt asked for, degrees (None: none asked).
    support: the support polygon the rows are built on.
    kinds: (k,) ``"margin"`` or ``"tilt"``, what each row asks.
    """

    normals: np.ndarray
    offsets: np.ndarray
    down: np.ndarray | None = None
    margin: float | None = None
    require_tilt_deg: float | None = None
    support: Support | None = None
    kinds: tuple[str, ...] = ()

    def slack(self, points: np.ndarray) -> np.ndarray:
        """``normals @ p − offsets`` for points (n, dim) → (k, n), m (a single point (dim,)
        gives (k,))."""
        pts = np.asarray(points, dtype=float)
        return (self.normals @ pts.T) - (self.offsets[:, None] if pts.ndim == 2 else self.offsets)

    def met_by(self, center_of_mass: np.ndarray, tolerance: float = 0.0) -> bool:
        """Whether a centre of mass meets every row (within ``tolerance`` m)."""
        return bool(np.all(self.slack(np.asarray(center_of_mass, dtype=float)) >= -tolerance))

    @property
    def dim(self) -> int:
        return self.normals.shape[1]


def target_for(body, *, down=None, margin: float | None = None,
               require_tilt_deg: float | None = None, support: Support | None = None,
               toward=None) -> Target:
    """The :class:`Target` for ``body`` resting with gravity along ``down``.

    Parameters
    ----------
    body : Body
        Any plumbob body (its support polygon and centre of mass are measured).
    down : array_like, optional
        Direction of gravity in the body's frame; default −z (−y for a lamina).
    margin : float, optional
        Static stability margin asked for, m (≥ 0).
    require_tilt_deg : float, optional
        Critical tilt asked for in every direction, degrees, in [0, 90) (degrees at every
        boundary of plumbob, as :class:`~plumbob.stability.requirement.Requirement`).
    support : Support, optional
        The support polygon, when already measured (its ``down`` is used).
    toward : array_like, optional
        With ``require_tilt_deg``: only a plane descending toward this horizontal direction
        (body frame). It tips at ``atan(s/h)``, ``s`` the distance to the support's
        boundary along the direction: ``s = min d_e / cos_e`` over the edges facing it
        (``cos_e`` their outward normal's cosine with it), so the rows are
        ``d_e − cos_e · tan θ · h ≥ 0``.

    Without ``margin`` and ``require_tilt_deg`` the target is to stand: margin 0 (and with a
    tilt ``toward`` one way, margin 0 on the other edges too).

    Examples
    --------
    The seed's block (1 × 1 × 4 m) stands with margin 0.5 m and critical tilt
    atan(0.5 / 2): the tilt rows at that angle have slack 0 at its centre.

    >>> from plumbob.bodies.primitives import box
    >>> t = target_for(box(1, 1, 4), require_tilt_deg=float(np.degrees(np.arctan(0.25))))
    >>> t.slack(np.array([0.5, 0.5, 2.0])).round(12).tolist()
    [0.0, 0.0, 0.0, 0.0]
    """
    if support is None:
        support = support_polygon(body, down)
    frame = support.frame
    if len(support.edge_normals) == 0:
        raise StabilityError(
            "the body rests on a single point: no support edge to keep its centre of mass "
            "inside (give another down direction)")
    inward = -frame.from_ground(support.edge_normals)  # (k, dim), unit, horizontal
    # d_e(p) = inward·(p − foot) + distance_e  =  inward·p − (inward·foot − distance_e)
    base = inward @ support.plane_point - support.edge_distances
    rows, offsets, kinds = [], [], []
    if margin is not None:
        margin = float(margin)
        if not (np.isfinite(margin) and margin >= 0):
            raise StabilityError(f"a stability margin must be ≥ 0, not {margin:g}")
    require_tilt = None
    if require_tilt_deg is not None:
        require_tilt_deg = float(require_tilt_deg)
        if not (np.isfinite(require_tilt_deg) and 0 <= require_tilt_deg < 90):
            raise StabilityError(
                f"a required tilt must be between 0° and 90°, not {require_tilt_deg:g}°")
        require_tilt = np.radians(require_tilt_deg)
    # a tilt toward one way still asks it to stand on level ground (margin 0 elsewhere)
    if margin is not None or require_tilt is None or toward is not None:
        rows.append(inward)
        offsets.append(base + (margin or 0.0))
        kinds += ["margin"] * len(inward)
    if require_tilt is not None:
        t = np.full(len(inward), np.tan(require_tilt))
        keep = np.ones(len(inward), dtype=bool)
        if toward is not None:
            u = frame.to_ground(np.asarray(toward, dtype=float))
            u = u / np.linalg.norm(u)
            cos = support.edge_normals @ u
            keep = cos > 1e-12
            t = t * cos
        up = frame.up
        rows.append(inward[keep] - t[keep, None] * up)
        offsets.append(base[keep] - t[keep] * (up @ support.plane_point))
        kinds += ["tilt"] * int(keep.sum())
    return Target(np.concatenate(rows), np.concatenate(offsets), frame.down.copy(), margin,
                  require_tilt_deg, support, tuple(kinds))
