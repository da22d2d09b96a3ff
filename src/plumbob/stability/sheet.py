"""A calculation sheet: the check worked as the seed's solutions work it.

The steps a reviewer or a student follows: the parts (mass, centre, first moment), the
combined centre by the seed's equation (15), ``r_G = Σ m_i r_i / M``, the support and its
edges, the critical edge, each weight and load with its moment about that edge,
resisting against overturning moment, the factor of safety, the verdict. Every number is
plumbob's own (the parts' exact mass properties, the verdict's support and moments);
the sheet only lays them out (:func:`plumbob.report.sheet_markdown`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..results import Result

__all__ = ["Sheet", "SheetPart", "calculation_sheet"]


@dataclass(frozen=True, repr=False)
class SheetPart(Result):
    """One row of the parts table.

    name: the part's name (or ``"part k"``). sign: +1 added, −1 a hole taken away.
    mass: kg (the part's own, positive). center: (dim,) m. first_moment: sign · m r, kg·m.
    moment: N·m, its weight's moment about the critical edge (positive overturns).
    """

    name: str
    sign: float
    mass: float
    center: np.ndarray
    first_moment: np.ndarray
    moment: float


@dataclass(frozen=True, repr=False)
class Sheet(Result):
    """What a calculation sheet shows (see the module's docstring).

    title: the body's name or file. parts: the parts table. mass: M, kg.
    first_moment: Σ m_i r_i, kg·m. center_of_mass: r_G, m. verdict: the check
    (:class:`~plumbob.stability.verdict.Verdict`). edge_start, edge_end, edge_normal: the
    critical edge (body frame). loads: the applied loads' moments (from the verdict under
    loads), empty without loads. resisting_moment, overturning_moment: N·m.
    overturning_safety_factor: resisting / overturning, None when nothing overturns.
    lift_energy: M g h_G, J: the energy to raise its material from the floor.
    """

    title: str
    parts: tuple[SheetPart, ...]
    mass: float
    first_moment: np.ndarray
    center_of_mass: np.ndarray
    verdict: object
    edge_start: np.ndarray
    edge_end: np.ndarray
    edge_normal: np.ndarray
    loads: tuple
    resisting_moment: float
    overturning_moment: float
    overturning_safety_factor: float | None
    lift_energy: float


def _summands(body) -> list[tuple[str, float, object]]:
    """(name, sign, body) of the parts the body's mass properties sum (equation (15))."""
    parts = body.assembly_parts()
    if parts:
        return [(getattr(p, "name", None) or f"part {i + 1}", 1.0, p)
                for i, p in enumerate(parts)]
    pieces, signs = getattr(body, "parts", None), getattr(body, "signs", None)
    if pieces and signs and len(pieces) == len(signs):
        return [(getattr(p, "name", None) or f"part {i + 1}", float(s), p)
                for i, (p, s) in enumerate(zip(pieces, signs))]
    return [(getattr(body, "name", None) or "the body", 1.0, body)]


def _moment(force: np.ndarray, at: np.ndarray, start: np.ndarray, normal: np.ndarray,
            up: np.ndarray) -> float:
    """The moment about the edge (as :mod:`.loaded`): (u·r)(n·F) − (u·F)(n·r)."""
    r = at - start
    return float((up @ r) * (normal @ force) - (up @ force) * (normal @ r))


def calculation_sheet(body, verdict, title: str = "") -> Sheet:
    """The sheet of ``verdict`` (:func:`plumbob.stability.check` of ``body``)."""
    sup = verdict.support
    up, g_vec = sup.frame.up, verdict.g * sup.frame.down
    if verdict.loaded is not None:
        lv = verdict.loaded
        start, end, normal = lv.edge_start, lv.edge_end, lv.edge_normal
        loads = tuple(m for m in lv.moments if m.kind != "weight")
        if lv.tilt_deg is not None:
            theta = np.radians(lv.tilt_deg)
            g_vec = verdict.g * (np.cos(theta) * sup.frame.down + np.sin(theta) * lv.tilt_direction)
    else:
        k = int(np.argmin(sup.edge_distances)) if len(sup.edge_distances) else None
        if k is None:
            start = end = sup.plane_point.copy()
            normal = verdict.critical_direction
        else:
            start, end = sup.to_body(sup.edge_starts[k]), sup.to_body(sup.edge_ends[k])
            normal = sup.frame.from_ground(sup.edge_normals[k])
        loads = ()
    rows = []
    for name, sign, part in _summands(body):
        p = part.mass_properties()
        rows.append(SheetPart(str(name), sign, p.mass, p.center_of_mass,
                              sign * p.mass * p.center_of_mass,
                              _moment(sign * p.mass * g_vec, p.center_of_mass, start, normal,
                                      up)))
    props_mass = verdict.mass
    first = sum((r.first_moment for r in rows), np.zeros_like(rows[0].first_moment))
    # the weight is one force at r_G (the parts' moments are its breakdown): the factor is
    # the check's own
    if verdict.loaded is not None:
        lv = verdict.loaded
        resisting, overturning = lv.resisting_moment, lv.overturning_moment
        factor = lv.overturning_safety_factor
    else:
        weight = _moment(props_mass * g_vec, verdict.center_of_mass, start, normal, up)
        resisting, overturning = max(-weight, 0.0), max(weight, 0.0)
        factor = resisting / overturning if overturning > 0 else None
    return Sheet(title, tuple(rows), props_mass, first, verdict.center_of_mass, verdict,
                 np.asarray(start), np.asarray(end), np.asarray(normal), loads, resisting,
                 overturning, factor, float(props_mass * verdict.g * verdict.com_height))
