"""Particle systems in motion: Newton's second law for each particle, integrated with
scipy's ``solve_ivp`` (seed sections 1 and 2).

Forces
------
* **Springs** (Hooke's law): a spring of stiffness k (N/m) and natural length l₀ (m)
  between particles i and j pulls or pushes each with ``k (|rᵢ − rⱼ| − l₀)`` along the line.
* **Light rigid rods** and **inextensible strings** are *constraints*, not stiff springs.
  Formulation: Lagrange multipliers at the acceleration level. For each active link
  with d = rᵢ − rⱼ, w = vᵢ − vⱼ and C = ½(|d|² − L²) we require
  ``C̈ + 2s Ċ + s² C = 0`` (Baumgarte stabilisation at rate ``s``, 1/s, which damps the
  drift of |d| from L), i.e. ``d·(aᵢ − aⱼ) = −|w|² − 2s d·w − s² C``; the multipliers λ
  solve ``(J M⁻¹ Jᵀ) λ = rhs − J M⁻¹ F`` and the link force is ``+λ d`` on i, ``−λ d`` on
  j — equal and opposite, so the links never change the total momentum.
  A rod pushes or pulls. A string only pulls: it is active while taut (|d| ≥ L) and its
  tension non-negative (an active-set loop drops strings that would push), and it goes
  slack otherwise. When a slack string snaps taut the integration stops at that instant
  (a ``solve_ivp`` event), an impulsive tension removes the separating velocity along
  the string (a coalescing impact, e = 0, momentum conserved) and the integration restarts.
* **Uniform gravity** ``gravity`` (m/s², a vector) and **constant applied forces** (N).
* **Sliding friction** on a supporting horizontal surface: when ``surface_gravity`` is set
  the particles slide on a surface whose normal reaction on particle i is
  ``mᵢ · surface_gravity`` (the coordinates are then in-plane coordinates; on an incline
  put the down-slope part of g into ``gravity`` and g cos α into ``surface_gravity``).
  Friction is ``μᵢ N`` opposite the velocity, regularised near rest as
  ``−μᵢ N v / √(|v|² + ε²)`` with ε = ``friction_speed`` (m/s): a particle "at rest" creeps
  at speeds of order ε, and the true (discontinuous) law is recovered for |v| ≫ ε.

Units: kg, m, s, N, m/s, m/s², J, kg·m/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..arguments import count, instance, positive, vector
from ..bodies.particles import ParticleSystem
from ..errors import DynamicsError
from ..limits import MAX_SAMPLES
from ..results import Key, Result
from .feasibility import check_feasible

__all__ = [
    "Spring",
    "Link",
    "MotionModel",
    "SimulationResult",
    "simulate",
]

#: The smallest relative tolerance the integrator can keep in double precision (scipy's
#: solvers raise anything below 100 ulps ≈ 2.2e-14 to that, with a warning).
MIN_RTOL = 1e-13
#: At t = 0 a string counts as taut when |d| ≥ L (1 − _TAUT_RTOL). During a run the
#: threshold is 100 × rtol: a string that the solver holds at |d| ≈ L stays taut.
_TAUT_RTOL = 1e-7
#: Most string jerks (restarts of the integration) in one run.
_MAX_SEGMENTS = 10_000


@dataclass(frozen=True)
class Spring:
    """A light spring between particles ``i`` and ``j`` (indices).

    stiffness: k, N/m (> 0).  natural_length: l₀, m (≥ 0).
    """

    i: int
    j: int
    stiffness: float
    natural_length: float


@dataclass(frozen=True)
class Link:
    """A light rigid rod (``kind = "rod"``) or inextensible string (``kind = "string"``)
    of ``length`` m (> 0) between particles ``i`` and ``j``."""

    i: int
    j: int
    length: float
    kind: str = "rod"


def _as_forces(value, n: int, d: int, label: str) -> np.ndarray:
    arr = np.array(value, dtype=float)
    if arr.ndim == 1 and arr.size == d:
        arr = np.broadcast_to(arr, (n, d))
    if arr.shape != (n, d):
        raise DynamicsError(f"{label} must be one vector of {d} components per particle")
    if not np.all(np.isfinite(arr)):
        raise DynamicsError(f"{label} has a component that is not a finite number")
    return np.array(arr)


@dataclass(frozen=True, eq=False)
class MotionModel:
    """A particle system with the forces acting on it.

    system: the particles (masses kg, positions m, velocities m/s at t = 0).
    springs: light springs between particles.
    links: light rods and strings between particles.
    gravity: (d,) uniform gravitational field, m/s² (None: none).
    forces: (n, d) constant applied force on each particle, N (or one (d,) for all).
    friction: (n,) coefficients of sliding friction with the supporting surface
        (or one number for all); needs ``surface_gravity``.
    surface_gravity: m/s²; when set, the particles slide on a horizontal surface
        whose normal reaction on each is its mass times this (g on a level surface).
    """

    system: ParticleSystem
    springs: tuple[Spring, ...] = ()
    links: tuple[Link, ...] = ()
    gravity: np.ndarray | None = None
    forces: np.ndarray | None = None
    friction: np.ndarray | None = None
    surface_gravity: float | None = None
    names: tuple[str, ...] = field(init=False)

    def __post_init__(self) -> None:
        instance(self.system, "system", ParticleSystem, error=DynamicsError)
        system = self.system
        n, d = len(system.masses), system.dim
        names = system.names or tuple(f"particle {k + 1}" for k in range(n))
        object.__setattr__(self, "names", tuple(str(x) for x in names))
        object.__setattr__(self, "springs", tuple(self.springs))
        object.__setattr__(self, "links", tuple(self.links))
        if self.gravity is not None:
            g = vector(self.gravity, "gravity (m/s²)", (d,), error=DynamicsError)
            object.__setattr__(self, "gravity", g)
        if self.forces is not None:
            object.__setattr__(self, "forces", _as_forces(self.forces, n, d, "the applied forces"))
        if self.surface_gravity is not None:
            gs = float(self.surface_gravity)
            if not (math.isfinite(gs) and gs >= 0):
                raise DynamicsError("the surface's g must be a non-negative number (m/s²)")
            object.__setattr__(self, "surface_gravity", gs)
        if self.friction is not None:
            mu = np.array(np.broadcast_to(np.asarray(self.friction, dtype=float), (n,)))
            if not np.all(np.isfinite(mu)) or np.any(mu < 0):
                raise DynamicsError("a coefficient of friction must be a non-negative number")
            if np.any(mu > 0) and self.surface_gravity is None:
                raise DynamicsError("friction needs a supporting surface: set the surface's g "
                                    "(the particles then slide on a horizontal surface)")
            object.__setattr__(self, "friction", mu)
        for s in self.springs:
            self._check_pair(s.i, s.j, "spring")
            if not (math.isfinite(s.stiffness) and s.stiffness > 0):
                raise DynamicsError(f"the spring {self._pair(s)} needs a positive stiffness "
                                    f"(got {s.stiffness} N/m)")
            if not (math.isfinite(s.natural_length) and s.natural_length >= 0):
                raise DynamicsError(f"the spring {self._pair(s)} needs a non-negative natural "
                                    f"length (got {s.natural_length} m)")
        v = system._velocities
        for link in self.links:
            self._check_pair(link.i, link.j, link.kind)
            if link.kind not in ("rod", "string"):
                raise DynamicsError(f"a link is a 'rod' or a 'string' (got {link.kind!r})")
            if not (math.isfinite(link.length) and link.length > 0):
                raise DynamicsError(f"the {link.kind} {self._pair(link)} needs a positive "
                                    f"length (got {link.length} m)")
            dvec = system.positions[link.i] - system.positions[link.j]
            dist = float(np.linalg.norm(dvec))
            stretch = (dist - link.length) / link.length
            if (link.kind == "rod" and abs(stretch) > 1e-9) or stretch > 1e-9:
                raise DynamicsError(
                    f"the {link.kind} {self._pair(link)} is {link.length:.6g} m long but its "
                    f"ends start {dist:.6g} m apart; move the particles or fix the length")
            if dist > 0:
                rate = float(dvec @ (v[link.i] - v[link.j])) / dist  # m/s
                speed = float(np.linalg.norm(v[link.i]) + np.linalg.norm(v[link.j]))
                taut = link.kind == "rod" or stretch >= -_TAUT_RTOL
                if taut and (link.kind == "rod" or rate > 0) and abs(rate) > 1e-9 * speed:
                    raise DynamicsError(
                        f"the initial velocities {'stretch' if rate > 0 else 'compress'} the "
                        f"{link.kind} {self._pair(link)} at {abs(rate):.6g} m/s; the relative "
                        "velocity of its ends must be perpendicular to it")

    def _pair(self, item: Spring | Link) -> str:
        return f"{self.names[item.i]}–{self.names[item.j]}"

    def _check_pair(self, i: int, j: int, kind: str) -> None:
        n = len(self.system.masses)
        if not (0 <= i < n and 0 <= j < n):
            raise DynamicsError(f"a {kind} joins particle numbers {i} and {j}, but there are "
                                f"only {n} particles")
        if i == j:
            raise DynamicsError(f"a {kind} must join two different particles "
                                f"(both ends on {self.names[i]})")

    @property
    def has_friction(self) -> bool:
        return self.friction is not None and bool(np.any(self.friction > 0))


@dataclass(frozen=True, eq=False, repr=False)
class SimulationResult(Result):
    """The paths of the particles and of their centre of mass.

    times: (t,) s.  names: one per particle.  masses: (n,) kg.
    positions, velocities: (t, n, d) m and m/s.
    center_of_mass, center_of_mass_velocity: (t, d) m and m/s.
    momentum: (t, d) kg·m/s, P = Σ mᵢ vᵢ = M v_G.
    kinetic_energy: (t,) J.
    external_force: (t, d) N, the sum of the external forces (gravity, applied, friction).
    center_of_mass_acceleration: (t, d) m/s², Σ mᵢ aᵢ / M from the equations of motion.
    newton_residual: max over t of |M a_G − F_ext| relative to the largest Σ mᵢ|aᵢ|, |F_ext|:
        the numerical check of F = M a_G (internal forces cancel).
    max_constraint_error: max over t and rods/taut strings of ||d| − L| / L.
    string_jerks: (time s, "A–B") for each instant a slack string snapped taut.
    """

    times: np.ndarray
    names: tuple[str, ...]
    masses: np.ndarray
    positions: np.ndarray
    velocities: np.ndarray
    center_of_mass: np.ndarray
    center_of_mass_velocity: np.ndarray
    momentum: np.ndarray
    kinetic_energy: np.ndarray
    external_force: np.ndarray
    center_of_mass_acceleration: np.ndarray
    newton_residual: float
    max_constraint_error: float
    string_jerks: tuple[tuple[float, str], ...] = ()

    @property
    def total_mass(self) -> float:
        """kg."""
        return float(self.masses.sum())

    def _repr_items(self) -> list[tuple[str, Any]]:
        return [("names", self.names), ("total_mass", self.total_mass),
                ("samples", len(self.times)), ("until", float(self.times[-1])),
                ("newton_residual", self.newton_residual),
                ("max_constraint_error", self.max_constraint_error),
                ("string_jerks", len(self.string_jerks))]

    @property
    def jerks(self) -> list[dict[str, Any]]:
        """Each string jerk as ``{"time": s, "string": "A–B"}``."""
        return [{"time": t, "string": s} for t, s in self.string_jerks]

    #: the keys of ``plumbob simulate --json`` after the spec's (``spec``, ``title``,
    #: ``until``): every field, the total mass after the masses
    KEYS = (
        Key("names", "", "one per particle"),
        Key("masses", "kg", "each particle's"),
        Key("total_mass", "kg", "their sum"),
        Key("times", "s", "the sample times"),
        Key("positions", "m", "(t, n, d): each particle's at each time"),
        Key("velocities", "m/s", "(t, n, d)"),
        Key("center_of_mass", "m", "(t, d)"),
        Key("center_of_mass_velocity", "m/s", "(t, d)"),
        Key("momentum", "kg·m/s", "(t, d): P = Σ mᵢ vᵢ = M v_G"),
        Key("kinetic_energy", "J", "(t,)"),
        Key("external_force", "N", "(t, d): the sum of the external forces"),
        Key("center_of_mass_acceleration", "m/s²", "(t, d): Σ mᵢ aᵢ / M"),
        Key("newton_residual", "", "max over t of |M a_G − F_ext|, relative: the check of "
                                   "F = M a_G"),
        Key("max_constraint_error", "", "max over t of a rod's or taut string's ||d| − L| / L"),
        Key("string_jerks", "s", "each instant a slack string snapped taut: `time`, `string`",
            attr="jerks"),
    )


# ------------------------------------------------------------------ dynamics
class _Dynamics:
    """Vectorised right-hand side of the equations of motion (no I/O, no state)."""

    def __init__(self, model: MotionModel, stabilization: float, friction_speed: float,
                 rtol: float = 1e-10) -> None:
        system = model.system
        self.taut_rtol = max(100.0 * rtol, 1e-12)
        self.model = model
        self.m = system.masses
        self.n, self.d = system.positions.shape
        self.inv_m = 1.0 / self.m
        const = np.zeros((self.n, self.d))
        if model.gravity is not None:
            const += self.m[:, None] * model.gravity
        if model.forces is not None:
            const += model.forces
        self.const = const
        self.mu_n = None
        if model.has_friction:
            self.mu_n = model.friction * self.m * model.surface_gravity
        self.eps2 = friction_speed ** 2
        springs = model.springs
        self.si = np.array([s.i for s in springs], dtype=int)
        self.sj = np.array([s.j for s in springs], dtype=int)
        self.sk = np.array([s.stiffness for s in springs], dtype=float)
        self.sl = np.array([s.natural_length for s in springs], dtype=float)
        links = model.links
        self.li = np.array([x.i for x in links], dtype=int)
        self.lj = np.array([x.j for x in links], dtype=int)
        self.ll = np.array([x.length for x in links], dtype=float)
        self.is_string = np.array([x.kind == "string" for x in links], dtype=bool)
        self.s = float(stabilization)

    def split(self, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        nd = self.n * self.d
        return y[:nd].reshape(self.n, self.d), y[nd:].reshape(self.n, self.d)

    def external(self, v: np.ndarray) -> np.ndarray:
        """(n, d) N: gravity, applied forces and friction."""
        if self.mu_n is None:
            return self.const.copy()
        speed = np.sqrt(np.einsum("ki,ki->k", v, v) + self.eps2)
        return self.const - (self.mu_n / speed)[:, None] * v

    def spring_forces(self, r: np.ndarray) -> np.ndarray:
        out = np.zeros((self.n, self.d))
        if not len(self.si):
            return out
        dvec = r[self.si] - r[self.sj]
        dist = np.sqrt(np.einsum("ki,ki->k", dvec, dvec))
        with_length = self.sl > 0
        if np.any(dist[with_length] == 0):
            raise DynamicsError("a spring collapsed to zero length, so its direction is "
                                "undefined; shorten the run or change the initial state")
        # force on i: −k (|d| − l₀) d/|d|; for l₀ = 0 this is −k d (no division).
        scale = self.sk * np.where(with_length, 1.0 - self.sl / np.where(dist > 0, dist, 1.0), 1.0)
        f = -scale[:, None] * dvec
        np.add.at(out, self.si, f)
        np.add.at(out, self.sj, -f)
        return out

    # -------------------------------------------------------------- links
    def _jacobian(self, r: np.ndarray, idx: np.ndarray) -> np.ndarray:
        """(k, n, d): row k holds d on its particle i and −d on its particle j."""
        dvec = r[self.li[idx]] - r[self.lj[idx]]
        jac = np.zeros((len(idx), self.n, self.d))
        rows = np.arange(len(idx))
        jac[rows, self.li[idx]] += dvec
        jac[rows, self.lj[idx]] -= dvec
        return jac

    def _solve_active(self, r: np.ndarray, candidates: np.ndarray, rhs_of) -> tuple:
        """Solve (J M⁻¹ Jᵀ) λ = b over the candidate links; strings must pull (λ ≤ 0).

        Returns (active indices, λ, J). ``rhs_of(idx, jac)`` gives b for those links.
        """
        active = np.asarray(candidates, dtype=int)
        for _ in range(len(active) + 1):
            if not len(active):
                return active, np.zeros(0), np.zeros((0, self.n, self.d))
            jac = self._jacobian(r, active)
            mat = np.einsum("kid,i,lid->kl", jac, self.inv_m, jac)
            b = rhs_of(active, jac)
            try:
                lam = np.linalg.solve(mat, b)
            except np.linalg.LinAlgError:
                lam = np.linalg.lstsq(mat, b, rcond=None)[0]
            if not np.all(np.isfinite(lam)):
                raise DynamicsError("the rods and strings cannot be resolved (a link of zero "
                                    "length or a degenerate arrangement)")
            pushing = self.is_string[active] & (lam > 0)
            if not np.any(pushing):
                return active, lam, jac
            active = active[~pushing]
        raise DynamicsError("the string tensions could not be resolved")  # pragma: no cover

    def taut(self, r: np.ndarray) -> np.ndarray:
        """Indices of rods and taut strings."""
        if not len(self.li):
            return np.zeros(0, dtype=int)
        dvec = r[self.li] - r[self.lj]
        dist = np.sqrt(np.einsum("ki,ki->k", dvec, dvec))
        ok = ~self.is_string | (dist >= self.ll * (1.0 - self.taut_rtol))
        return np.flatnonzero(ok)

    def accelerations(self, r: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """((n, d) accelerations m/s², (n, d) external forces N)."""
        ext = self.external(v)
        force = ext + self.spring_forces(r)
        if len(self.li):
            a0 = force * self.inv_m[:, None]
            s = self.s

            def rhs_of(idx: np.ndarray, jac: np.ndarray) -> np.ndarray:
                dvec = r[self.li[idx]] - r[self.lj[idx]]
                w = v[self.li[idx]] - v[self.lj[idx]]
                c = 0.5 * (np.einsum("ki,ki->k", dvec, dvec) - self.ll[idx] ** 2)
                cdot = np.einsum("ki,ki->k", dvec, w)
                target = -np.einsum("ki,ki->k", w, w) - 2.0 * s * cdot - s * s * c
                return target - np.einsum("kid,id->k", jac, a0)

            _, lam, jac = self._solve_active(r, self.taut(r), rhs_of)
            if len(lam):
                force = force + np.einsum("k,kid->id", lam, jac)
        return force * self.inv_m[:, None], ext

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        r, v = self.split(y)
        a, _ = self.accelerations(r, v)
        return np.concatenate([v.ravel(), a.ravel()])

    def jerk(self, y: np.ndarray, string: int) -> np.ndarray:
        """Velocities after ``string`` snaps taut: impulses make every taut link's
        ends move with no relative velocity along it (strings only pull)."""
        r, v = self.split(y)
        candidates = np.union1d(self.taut(r), [string])

        def rhs_of(idx: np.ndarray, jac: np.ndarray) -> np.ndarray:
            return -np.einsum("kid,id->k", jac, v)

        _, lam, jac = self._solve_active(r, candidates, rhs_of)
        v_new = v + np.einsum("k,kid->id", lam, jac) * self.inv_m[:, None] if len(lam) else v
        return np.concatenate([r.ravel(), v_new.ravel()])

    def constraint_error(self, r: np.ndarray) -> float:
        idx = self.taut(r)
        if not len(idx):
            return 0.0
        dvec = r[self.li[idx]] - r[self.lj[idx]]
        dist = np.sqrt(np.einsum("ki,ki->k", dvec, dvec))
        return float(np.max(np.abs(dist - self.ll[idx]) / self.ll[idx]))


def _scales(model: MotionModel, until: float) -> tuple[float, float]:
    """Typical length (m) and speed (m/s) for absolute tolerances."""
    system = model.system
    m = system.masses
    acc = 0.0
    if model.gravity is not None:
        acc = max(acc, float(np.linalg.norm(model.gravity)))
    if model.forces is not None:
        acc = max(acc, float(np.max(np.linalg.norm(model.forces, axis=1) / m)))
    if model.has_friction:
        acc = max(acc, float(np.max(model.friction)) * model.surface_gravity)
    speed = max(float(np.max(np.abs(system._velocities))), acc * until)
    lengths = [s.natural_length for s in model.springs] + [x.length for x in model.links]
    length = max([float(np.max(np.abs(system.positions))), speed * until, *lengths])
    if length == 0.0:
        length = 1.0
    if speed == 0.0:
        speed = length / until
    return length, speed


#: the ``solve_ivp`` methods a simulation may use
_METHODS = ("RK45", "RK23", "DOP853", "Radau", "BDF", "LSODA")


def simulate(model: MotionModel, until: float, samples: int = 201, *, rtol: float = 1e-10,
             method: str | None = None, stabilization: float | None = None,
             friction_speed: float | None = None) -> SimulationResult:
    """Integrate the motion from t = 0 to ``until`` (s), reporting ``samples`` equally
    spaced instants.

    rtol: relative tolerance of ``solve_ivp`` (absolute tolerances are scaled to the
        system's typical length and speed).
    method: a ``solve_ivp`` method; default "DOP853", or "LSODA" when there is friction
        (the regularised friction is stiff near rest).
    stabilization: Baumgarte rate s for rods and strings, 1/s (default 20/until).
    friction_speed: ε of the friction regularisation, m/s (default 1e-6 × typical speed).

    Without external forces the momentum is constant to round-off:

    >>> pair = ParticleSystem([1.0, 2.0], [[0, 0], [1, 0]], [[0, 1], [0, 0]])
    >>> run = simulate(MotionModel(pair, springs=(Spring(0, 1, 10.0, 1.0),)), 2.0, samples=3)
    >>> np.allclose(run.momentum, [0, 1], rtol=0, atol=1e-12)
    True
    """
    from scipy.integrate import solve_ivp

    until = positive(until, "the end time (s)", error=DynamicsError)
    samples = count(samples, "samples", MAX_SAMPLES, minimum=2, error=DynamicsError)
    if not (MIN_RTOL <= rtol < 1):
        raise DynamicsError(f"rtol must lie between {MIN_RTOL:g} and 1 (got {rtol!r}): a "
                            "double holds about 16 digits, and the integrator needs some to "
                            "spare (scipy would quietly raise a smaller rtol to 100 ulps)")
    check_feasible(model, until, rtol, _scales)
    length, speed = _scales(model, until)
    if stabilization is None:
        stabilization = 20.0 / until
    if friction_speed is None:
        friction_speed = 1e-6 * speed
    if not (math.isfinite(stabilization) and stabilization >= 0):
        raise DynamicsError("the stabilisation rate must be a non-negative number (1/s)")
    if not (math.isfinite(friction_speed) and friction_speed > 0):
        raise DynamicsError("the friction regularisation speed must be positive (m/s)")
    if method is None:
        method = "LSODA" if model.has_friction else "DOP853"
    if method not in _METHODS:
        raise DynamicsError(f"method must be one of {', '.join(_METHODS)}, not {method!r}")
    dyn = _Dynamics(model, stabilization, friction_speed, rtol)
    system = model.system
    n, d = dyn.n, dyn.d
    atol = np.concatenate([np.full(n * d, rtol * length), np.full(n * d, rtol * speed)])
    times = np.linspace(0.0, until, int(samples))
    y = np.concatenate([system.positions.ravel(), system._velocities.ravel()])
    t0 = 0.0
    out_t: list[np.ndarray] = []
    out_y: list[np.ndarray] = []
    jerks: list[tuple[float, str]] = []
    strings = np.flatnonzero(dyn.is_string)
    for _segment in range(_MAX_SEGMENTS):
        r0, _ = dyn.split(y)
        taut_now = set(dyn.taut(r0).tolist())
        events = [_string_event(dyn, k, k in taut_now) for k in strings]
        t_eval = times[times > t0] if out_t else times
        sol = solve_ivp(dyn.rhs, (t0, until), y, method=method, t_eval=t_eval, rtol=rtol,
                        atol=atol, events=events or None)
        if sol.status == -1:
            raise DynamicsError(f"the integration failed at t = {sol.t[-1]:.6g} s: {sol.message}")
        out_t.append(sol.t)
        out_y.append(sol.y.T)
        if sol.status != 1:
            break
        hits = [(te[0], k, ye[0]) for k, te, ye in zip(strings, sol.t_events, sol.y_events,
                                                        strict=True) if len(te)]
        t0, k, y_event = min(hits, key=lambda h: h[0])
        y = dyn.jerk(y_event, int(k))
        jerks.append((float(t0), model._pair(model.links[int(k)])))
    else:
        raise DynamicsError(f"more than {_MAX_SEGMENTS} string jerks; the strings keep "
                            "snapping taut — check the lengths and the forces")
    t_all = np.concatenate(out_t)
    y_all = np.concatenate(out_y)
    return _result(model, dyn, t_all, y_all, tuple(jerks))


def _string_event(dyn: _Dynamics, k: int, taut: bool):
    """Event: string k reaching its length from below (re-armed below L if taut now)."""
    # A taut string must first slacken by 10 × the taut threshold before a re-tightening
    # is a new jerk (so round-off at |d| ≈ L fires no events); the instant of such a
    # jerk is therefore located to about 1e-7 L / (closing speed).
    target = dyn.ll[k] * (1.0 - 10.0 * dyn.taut_rtol) if taut else dyn.ll[k]
    nd = dyn.n * dyn.d
    i, j = int(dyn.li[k]), int(dyn.lj[k])

    def event(t: float, y: np.ndarray) -> float:
        r = y[:nd].reshape(dyn.n, dyn.d)
        return float(np.linalg.norm(r[i] - r[j])) - target

    event.terminal = True
    event.direction = 1.0
    return event


def _result(model: MotionModel, dyn: _Dynamics, t: np.ndarray, y: np.ndarray,
            jerks: tuple[tuple[float, str], ...]) -> SimulationResult:
    n, d = dyn.n, dyn.d
    m = dyn.m
    positions = y[:, : n * d].reshape(len(t), n, d)
    velocities = y[:, n * d:].reshape(len(t), n, d)
    total = float(m.sum())
    anchor = positions[:, :1, :]
    com = anchor[:, 0, :] + np.einsum("k,tki->ti", m, positions - anchor) / total
    momentum = np.einsum("k,tki->ti", m, velocities)
    ke = 0.5 * np.einsum("k,tki,tki->t", m, velocities, velocities)
    acc = np.empty_like(positions)
    ext = np.empty((len(t), d))
    cerr = 0.0
    for step in range(len(t)):
        a, f = dyn.accelerations(positions[step], velocities[step])
        acc[step] = a
        ext[step] = f.sum(axis=0)
        cerr = max(cerr, dyn.constraint_error(positions[step]))
    mass_acc = np.einsum("k,tki->ti", m, acc)
    scale = max(float(np.max(np.einsum("k,tk->t", m, np.linalg.norm(acc, axis=2)))),
                float(np.max(np.linalg.norm(ext, axis=1))), 1e-300)
    residual = float(np.max(np.linalg.norm(mass_acc - ext, axis=1))) / scale
    return SimulationResult(
        times=t, names=model.names, masses=m, positions=positions, velocities=velocities,
        center_of_mass=com, center_of_mass_velocity=momentum / total, momentum=momentum,
        kinetic_energy=ke, external_force=ext, center_of_mass_acceleration=mass_acc / total,
        newton_residual=residual, max_constraint_error=cerr, string_jerks=jerks)

