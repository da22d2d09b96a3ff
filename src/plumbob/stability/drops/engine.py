"""The physics engine side of the drops: a MuJoCo model of the body and the drops themselves.

Everything the engine sees is in *scaled* units — lengths over the body's radius
``r`` (the largest distance from the centre of mass to a hull point), masses over
its mass ``m``, times over ``t0 = sqrt(r / g)`` — so gravity is 1 and the body's size
is 1 whatever its real size. MuJoCo's fixed tolerances (the contact impedance's
width of 1e-3, its minimum masses) are absolute numbers, and a 5 mm part in metres
would otherwise sit on the edge of them; scaled, every body is as well conditioned as
a 1 m one and the same time step suits all.

The body is a mesh geom of its hull's vertices (MuJoCo collides with the convex
hull of a mesh, which is exactly what resting poses need) with plumbob's mass
properties given explicitly (``inertiafromgeom="false"``: MuJoCo's own inertia
would assume a uniform solid). A drop is run until the body is at rest: every
:data:`CHECK_EVERY` steps the height of the centre and the down direction are looked
at, and a body whose pose stayed within :data:`STILL` over the last
:data:`REST_CHECKS` looks is at rest; :data:`MAX_TIME` bounds a drop.

:func:`run_drops` is the worker: module-level and given only plain data, so a
process pool can call it; each drop starts from a reset, so the outcome of a drop
depends only on its own start, never on which process ran it or in what order.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from types import ModuleType

import numpy as np

from ...errors import PlumbobError

__all__ = ["require_mujoco", "EXTRA", "Engine", "model_xml", "run_drops",
           "random_quaternions", "quaternion_downs", "lowest_heights", "damping_ratio"]

EXTRA = "pip install 'plumbob[dynamic]'"

#: scaled time steps: an overdamped drop creeps (its contacts are gentle), a tumbling
#: drop has impacts to resolve
TIMESTEP_OVERDAMPED = 0.02
TIMESTEP_DYNAMIC = 0.005
#: rotational damping of the overdamped setting, in m r² / t0: the body turns at about
#: 1 / (4 t0) under gravity's torque while its inertia relaxes in t0 / 4 — tested to
#: give the same landings as 10 (the motion is inertia-free)
OVERDAMPED_DAMPING = 4.0
#: rolling and torsional friction, scaled lengths: a rolling body comes to rest
ROLLING_FRICTION = 1e-3
CHECK_EVERY = 20  # steps between looks at the velocities
REST_CHECKS = 10  # looks in the window over which a body at rest has not moved
#: scaled: over the window the centre's height and the down direction stay within 1e-3
#: (r, rad). Sliding and spinning about the vertical change no pose and may go on; a
#: soft contact may chatter (a limit cycle of ~1e-5 between two and four contacts).
STILL = 1e-3
MAX_TIME = 200.0  # scaled time after which a drop stops, settled or not
GAP = 1e-3  # scaled height of the lowest point above the ground (or the drop height) at release


def require_mujoco() -> ModuleType:
    """Import MuJoCo or say, in one line, which extra brings it."""
    try:
        return importlib.import_module("mujoco")
    except ImportError:
        raise PlumbobError("dynamic drops (--dynamic) need the 'mujoco' package, part of "
                           f"plumbob's dynamic extra: {EXTRA}") from None


def damping_ratio(restitution: float) -> float:
    """The contact's damping ratio ζ for a coefficient of restitution e, as for a linear
    spring-damper: e = exp(−ζπ / sqrt(1 − ζ²)); e = 0 gives critical damping (ζ = 1).

    >>> damping_ratio(0.0), round(damping_ratio(0.5), 4)
    (1.0, 0.2155)
    """
    if restitution <= 0:
        return 1.0
    log = np.log(restitution)
    return float(-log / np.sqrt(np.pi ** 2 + log * log))


@dataclass(frozen=True)
class Engine:
    """What a worker needs to build the model and run drops: plain data only.

    xml: the MJCF model. damping: (6,) the free joint's damping per degree of freedom
    (three translations, three rotations), scaled. timestep: scaled.
    """

    xml: str
    damping: tuple[float, ...]
    timestep: float


def model_xml(points: np.ndarray, inertia: np.ndarray, *, timestep: float, friction: float,
              restitution: float) -> str:
    """The MJCF model: a ground plane and the body, a free mesh of ``points`` (scaled,
    relative to the centre of mass, which is the body's origin) with mass 1 and
    ``inertia`` (3, 3) (scaled, about the centre, plumbob's sign convention, which is
    MuJoCo's ``fullinertia``)."""
    verts = " ".join(repr(float(v)) for v in points.ravel())
    timeconst = max(2.0 * timestep, 0.02)  # MuJoCo needs at least two steps
    contact = (f'friction="{friction!r} {ROLLING_FRICTION} {ROLLING_FRICTION}" condim="6" '
               f'solref="{timeconst!r} {damping_ratio(restitution)!r}"')
    i = inertia
    full = " ".join(repr(float(v)) for v in (i[0, 0], i[1, 1], i[2, 2], i[0, 1], i[0, 2], i[1, 2]))
    return f"""<mujoco model="plumbob drop">
  <compiler inertiafromgeom="false"/>
  <option timestep="{timestep!r}" gravity="0 0 -1" integrator="implicitfast"/>
  <asset><mesh name="hull" vertex="{verts}" inertia="shell"/></asset>
  <worldbody>
    <geom name="ground" type="plane" size="0 0 1" {contact}/>
    <body name="body">
      <freejoint/>
      <inertial pos="0 0 0" mass="1" fullinertia="{full}"/>
      <geom name="hull" type="mesh" mesh="hull" {contact}/>
    </body>
  </worldbody>
</mujoco>"""


def random_quaternions(count: int, seed: int) -> np.ndarray:
    """(count, 4) unit quaternions (w, x, y, z) uniform on SO(3): a normalised 4-D
    Gaussian is uniform on the 3-sphere, which covers SO(3) twice, evenly."""
    q = np.random.default_rng(seed).normal(size=(count, 4))
    return q / np.linalg.norm(q, axis=1)[:, None]


def _rotations(q: np.ndarray) -> np.ndarray:
    """(n, 3, 3) rotation matrices (body → world) of unit quaternions (n, 4)."""
    w, x, y, z = q.T
    return np.stack((
        np.stack((1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)), -1),
        np.stack((2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)), -1),
        np.stack((2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)), -1),
    ), axis=1)


def quaternion_downs(q: np.ndarray) -> np.ndarray:
    """(n, 3) the world's down direction (0, 0, −1) in the body's frame, for unit
    quaternions (n, 4) (w, x, y, z) that turn the body frame into the world's."""
    return -_rotations(q)[:, 2, :]


def lowest_heights(points: np.ndarray, q: np.ndarray, block: int = 4096) -> np.ndarray:
    """(n,) the height of the lowest of ``points`` (k, 3) below the centre of mass in
    each orientation ``q`` (n, 4) — minus the smallest z of the turned points."""
    out = np.empty(len(q))
    for s in range(0, len(q), block):  # blocks of drops bound the (drops × points) product
        rows = _rotations(q[s:s + block])[:, 2, :]
        out[s:s + block] = -(rows @ points.T).min(axis=1)
    return out


def _pose_of(qpos: np.ndarray) -> np.ndarray:
    """(4,) what a resting pose is: the height of the centre and the down direction in the
    body's frame (sliding and spinning about the vertical change neither)."""
    w, x, y, z = qpos[3:7]
    return np.array((qpos[2], 2 * (w * y - x * z), -2 * (y * z + w * x),
                     2 * (x * x + y * y) - 1))


def run_drops(engine: Engine, quaternions: np.ndarray, heights: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray]:
    """Drop the body from each start — orientation ``quaternions`` (n, 4), centre of mass
    at ``heights`` (n,) (scaled) — until it rests. Returns the final orientations (n, 4)
    and whether each drop came to rest (n,) before :data:`MAX_TIME`."""
    mujoco = require_mujoco()
    model = mujoco.MjModel.from_xml_string(engine.xml)
    model.dof_damping[:] = engine.damping
    data = mujoco.MjData(model)
    blocks = int(np.ceil(MAX_TIME / (engine.timestep * CHECK_EVERY)))
    final = np.empty((len(quaternions), 4))
    settled = np.zeros(len(quaternions), dtype=bool)
    for k in range(len(quaternions)):  # one drop at a time: each is its own simulation
        mujoco.mj_resetData(model, data)
        data.qpos[:3] = (0.0, 0.0, heights[k])
        data.qpos[3:7] = quaternions[k]
        window = np.full((REST_CHECKS, 4), np.inf)
        for look in range(blocks):
            mujoco.mj_step(model, data, nstep=CHECK_EVERY)
            # where the pose has been over a window, not the velocity: a soft contact
            # may chatter from step to step while the body stays put
            window[look % REST_CHECKS] = _pose_of(data.qpos)
            if np.ptp(window, axis=0).max() < STILL:
                settled[k] = True
                break
        q = np.array(data.qpos[3:7])
        final[k] = q / np.linalg.norm(q)
    return final, settled
