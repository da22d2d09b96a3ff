"""Monte Carlo drops: :func:`drop_poses` — set up, run in parallel, classify, count.

The quasi-static poses (:func:`~plumbob.stability.poses.resting_poses`) name the
places a body can rest; the drops say how often a body that keeps its momentum
actually ends in each. A final orientation is matched to the pose whose ``down`` is
nearest (for a rolling family, whose great circle of down directions is nearest)
within :data:`MATCH_DEG`; a drop at rest nowhere near a pose (balanced on an edge) or
still moving at the time limit is counted as unsettled, not guessed.
"""

from __future__ import annotations

import math

import numpy as np

from ...arguments import answering, count, instance, number
from ...errors import StabilityError
from ...limits import MAX_SAMPLES, check_count
from ...massprops import MassProperties
from ...tolerances import HULL_ROUND_OFF, sampling_tolerance
from ...units import SEED_GRAVITY
from ..poses import Poses, resting_poses
from ..poses.convex import hull_triangles
from ..support import body_size, hull_points
from . import engine as eng
from .result import DropPose, Drops, wilson_interval

__all__ = ["drop_poses", "classify", "check_settings", "MATCH_DEG"]

MATCH_DEG = 2.0  # a body at rest on a face has its down within contact compliance of it
_CHUNKS_PER_JOB = 4  # chunks per process: the slow drops (long rolls) spread evenly


def _pose_axis(pose) -> np.ndarray | None:
    """The axis of a rolling pose: its own ``axis`` when the pose has one, otherwise the
    longest direction of the face it rests on (a cylinder's side strip runs along it);
    None for a pose that rests on one face."""
    if not getattr(pose, "neutral", False) and getattr(pose, "kind", "") != "rolling":
        return None
    axis = getattr(pose, "axis", None)
    if axis is not None:
        return np.asarray(axis, dtype=float)
    face = np.asarray(pose.face, dtype=float)
    _, _, vt = np.linalg.svd(face - face.mean(axis=0), full_matrices=False)
    return vt[0]


def classify(downs: np.ndarray, poses: Poses, match_deg: float = MATCH_DEG) -> np.ndarray:
    """Index of the pose each down direction (n, 3) rests in, −1 when none lies within
    ``match_deg`` degrees: the angle to a face pose's ``down``, or to the great circle
    of down directions of a rolling pose (perpendicular to its axis)."""
    angles = np.empty((len(downs), len(poses)))
    for k, pose in enumerate(poses.poses):  # a handful of poses, each vectorised over drops
        axis = _pose_axis(pose)
        if axis is None:
            angles[:, k] = np.arccos(np.clip(downs @ np.asarray(pose.down, float), -1.0, 1.0))
        else:
            angles[:, k] = np.arcsin(np.clip(np.abs(downs @ axis), 0.0, 1.0))
    best = np.argmin(angles, axis=1)
    near = angles[np.arange(len(downs)), best] <= math.radians(match_deg)
    return np.where(near, best, -1)


def check_settings(drops: int, drop_height: float, restitution: float, friction: float,
                   jobs: int, overdamped: bool) -> int:
    """The number of drops, once every setting is in range; else a LimitError (too many
    drops) or StabilityError naming the setting. Cheap: called before any work."""
    drops = check_count("drops", drops, MAX_SAMPLES, hint="ask for fewer drops")
    drop_height, restitution, friction = (
        number(value, what, error=StabilityError) for value, what in (
            (drop_height, "the drop height"), (restitution, "the restitution"),
            (friction, "the friction coefficient")))
    count(jobs, "jobs", MAX_SAMPLES, minimum=1, error=StabilityError)
    if drops < 1:
        raise StabilityError("dynamic drops need at least one drop")
    if not (math.isfinite(drop_height) and drop_height >= 0):
        raise StabilityError(f"the drop height must be a finite number ≥ 0 m, not {drop_height}")
    if not (0 <= restitution <= 0.95):
        raise StabilityError(f"the restitution must be between 0 and 0.95, not {restitution} "
                             "(a body that keeps bouncing never comes to rest)")
    if not (math.isfinite(friction) and friction > 0):
        raise StabilityError(f"the friction coefficient must be positive, not {friction}")
    if overdamped and (restitution > 0 or drop_height > 0):
        raise StabilityError("the overdamped setting drops from rest on the ground without "
                             "bounce: leave the restitution and drop height at 0")
    return drops


def worker_pool(jobs: int):
    """The process pool the drops run on: ``jobs`` workers of one BLAS/OpenMP/plumbob
    thread each (they share the cores; :func:`~plumbob.blockwise.limit_threads`)."""
    import multiprocessing  # here, not at the top: `plumbob poses` without --dynamic
    from concurrent.futures import ProcessPoolExecutor  # starts faster without them

    from ...blockwise import limit_threads

    # fork where there is one: a spawned worker would re-run a user's script that has no
    # ``if __name__ == "__main__"`` guard; the parent has built no MuJoCo model to share
    methods = multiprocessing.get_all_start_methods()
    context = multiprocessing.get_context("fork" if "fork" in methods else "spawn")
    return ProcessPoolExecutor(max_workers=jobs, mp_context=context, initializer=limit_threads,
                               initargs=(1,))


def _simulate(engine: eng.Engine, quats: np.ndarray, heights: np.ndarray, jobs: int
              ) -> tuple[np.ndarray, np.ndarray]:
    """Run every drop, on ``jobs`` processes; the answer is the same for any ``jobs``."""
    if jobs <= 1 or len(quats) < 2:
        return eng.run_drops(engine, quats, heights)
    parts = np.array_split(np.arange(len(quats)), min(len(quats), jobs * _CHUNKS_PER_JOB))
    with worker_pool(jobs) as pool:
        done = list(pool.map(eng.run_drops, [engine] * len(parts),
                             [quats[p] for p in parts], [heights[p] for p in parts]))
    return (np.concatenate([d[0] for d in done]), np.concatenate([d[1] for d in done]))


def drop_poses(body, *, drops: int = 1000, seed: int = 0, drop_height: float = 0.0,
               restitution: float = 0.0, friction: float = 1.0, overdamped: bool = False,
               jobs: int = 1, g: float = SEED_GRAVITY, poses: Poses | None = None,
               props=None) -> Drops:
    """Drop a solid from random orientations in MuJoCo and count where it comes to rest.

    Orientations are uniform on SO(3) from ``seed``; each drop starts at rest with its
    lowest point ``drop_height`` above the ground and runs until the body is still.
    The final orientations are matched to the quasi-static poses.

    Parameters
    ----------
    body : Body
        A solid (a lamina cannot be dropped in 3-D).
    drops : int, optional
        Number of drops (at most :data:`plumbob.limits.MAX_SAMPLES`).
    seed : int, optional
        Seed of the random orientations.
    drop_height : float, optional
        Height of the lowest point above the ground at release, m.
    restitution : float, optional
        Coefficient of restitution of the contact, 0 to 0.95 (approximate: MuJoCo's
        contact is a soft spring-damper whose damping ratio is chosen to give it).
    friction : float, optional
        Coefficient of sliding friction (rolling and torsional friction are a small fixed
        1e-3 of the body's radius, so rolling bodies stop).
    overdamped : bool, optional
        Heavily damp the body's rotation and drop it from the ground without bounce: the
        drop that loses its energy at once, whose landings are the quasi-static model's.
    jobs : int, optional
        Processes to run the drops on; the answer does not depend on it.
    g : float, optional
        Gravitational acceleration, m/s² (it sets the time scale only).
    poses : Poses, optional
        The quasi-static poses, when already computed.
    props : MassProperties, optional
        The body's mass properties, when already computed.

    Returns
    -------
    Drops
        Each pose's landing probability with its Wilson 95 % interval and count.

    Raises
    ------
    PlumbobError
        MuJoCo is not installed (the ``dynamic`` extra).
    StabilityError
        A lamina, or settings out of range.
    LimitError
        More drops than :data:`plumbob.limits.MAX_SAMPLES`.

    Examples
    --------
    A 1 × 2 × 3 box dropped 200 times in the overdamped setting lands as the
    quasi-static model says, within the drops' noise; on its largest faces about a
    third of the time each:

    >>> from plumbob.bodies.primitives import box
    >>> drops = drop_poses(box(1.0, 2.0, 3.0), drops=200, seed=1, overdamped=True)
    >>> drops.landed, len(drops)
    (200, 6)
    >>> all(abs(p.probability - p.quasi_static) <= 3 * p.standard_error for p in drops)
    True
    >>> round(drops[0].quasi_static, 4)
    0.3225
    """
    body = answering(body, "body", "mass_properties", error=StabilityError)
    drops = check_settings(drops, drop_height, restitution, friction, jobs, overdamped)
    jobs = int(jobs)
    mujoco = eng.require_mujoco()
    props = body.mass_properties() if props is None else instance(props, "props",
                                                                  MassProperties)
    poses = None if poses is None else instance(poses, "poses", Poses)
    if getattr(body, "dim", props.dim) != 3:
        raise StabilityError("dynamic drops need a solid; a lamina rests in its own plane")
    poses = resting_poses(body, g=g, props=props) if poses is None else poses
    com = np.asarray(props.center_of_mass, dtype=float)
    size = body_size(body)
    pts = hull_triangles(hull_points(body, sampling_tolerance(size, None)) - com,
                         HULL_ROUND_OFF * size)[0]
    radius = float(np.linalg.norm(pts, axis=1).max())
    t0 = math.sqrt(radius / g)
    scaled = pts / radius
    inertia = np.asarray(props.inertia, dtype=float) / (props.mass * radius * radius)
    timestep = eng.TIMESTEP_OVERDAMPED if overdamped else eng.TIMESTEP_DYNAMIC
    xml = eng.model_xml(scaled, inertia, timestep=timestep, friction=float(friction),
                        restitution=float(restitution))
    rot = eng.OVERDAMPED_DAMPING if overdamped else 0.0
    engine = eng.Engine(xml, (0.0, 0.0, 0.0, rot, rot, rot), timestep)

    quats = eng.random_quaternions(drops, int(seed))
    heights = eng.lowest_heights(scaled, quats) + drop_height / radius + eng.GAP
    final, settled = _simulate(engine, quats, heights, int(jobs))
    label = np.where(settled, classify(eng.quaternion_downs(final), poses), -1)
    counts = np.bincount(label[label >= 0], minlength=len(poses))
    landed = int(counts.sum())
    out = []
    for pose, hits in zip(poses.poses, counts.tolist()):
        p = hits / landed if landed else 0.0
        se = math.sqrt(p * (1 - p) / landed) if landed else 0.0
        out.append(DropPose(np.asarray(pose.down, float).copy(), p, hits,
                            wilson_interval(hits, landed), se, float(pose.probability),
                            _pose_axis(pose) is not None))
    out.sort(key=lambda q: (-q.probability, -q.quasi_static))
    notes = []
    if landed < drops:
        notes.append(f"{drops - landed} of {drops} drops did not come to rest in a pose "
                     "(still moving at the time limit, or balanced): left out")
    return Drops(tuple(out), drops, landed, drops - landed, int(seed), float(drop_height),
                 float(restitution), float(friction), bool(overdamped), timestep * t0,
                 float(props.mass), com.copy(), f"MuJoCo {mujoco.__version__}", tuple(notes))
