"""What :func:`resting_poses` answers: the :class:`Pose` and :class:`Poses` results.

Frozen dataclasses in SI units. ``as_dict()`` gives the JSON object of
``plumbob poses --json`` (keys documented in ``docs/cli.md``; numpy arrays are
left as arrays, :func:`plumbob.results.jsonable` turns them into lists), and the
reprs are one short line each.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...results import Key, Result, Source

__all__ = ["Pose", "Poses"]

_SHOWN = 6  # probabilities shown in the repr of Poses


def _short(value: float, digits: int = 4) -> str:
    """A number in ``digits`` significant figures, round-off below 1e-12 shown as 0."""
    value = float(value)
    return "0" if abs(value) < 1e-12 else f"{value:.{digits}g}"


def _vector(values: np.ndarray) -> str:
    """A vector as ``(x, y, z)`` in :func:`_short` numbers."""
    return "(" + ", ".join(_short(v) for v in np.asarray(values, dtype=float)) + ")"


@dataclass(frozen=True, repr=False)
class Pose(Result):
    """One stable resting pose.

    Attributes
    ----------
    down : numpy.ndarray
        Unit vector (dim,) in the body's frame: the outward normal of the face it rests
        on, pointing to the ground.
    com_height : float
        Height of the centre of mass above the ground, m.
    probability : float
        Quasi-static probability of landing in this pose from a random drop (for a
        family, the sum over its faces).
    critical_tilt_deg : float
        Least tilt of the ground, over every direction, that topples it out of this
        pose, degrees (0 for a rolling pose).
    energy_barrier : float or None
        Energy to leave the pose over the lowest saddle of its basin's boundary, J;
        None when it is the only pose.
    face : numpy.ndarray
        (k, dim) the corners of the face it rests on, m, body frame.
    kind : str
        ``"face"`` (it rests on one physical face), ``"rolling"`` (a family of faces a
        small tilt rolls it between: a cylinder's side, a cone's, a ball; ``down`` and
        ``transform`` are one representative face of it) or ``"rocking"`` (the bottom of
        a bowl: it rocks back to its lowest face, the one given).
    members : int
        How many physical faces the pose stands for.
    axis : numpy.ndarray or None
        (3,) for a rolling pose whose faces turn about one axis (body frame, unit): the
        axis it rolls about; None otherwise (a ball rolls every way).
    transform : numpy.ndarray
        (4, 4) rigid transform, row-major, that rests the body in this pose on the
        ground plane z = 0, up +z, its centre of mass straight above the origin
        (see :func:`~.placement.placement`).
    """

    down: np.ndarray
    com_height: float
    probability: float
    critical_tilt_deg: float
    energy_barrier: float | None
    face: np.ndarray
    kind: str = "face"
    members: int = 1
    axis: np.ndarray | None = None
    transform: np.ndarray = field(default_factory=lambda: np.eye(4))

    @property
    def neutral(self) -> bool:
        """True for a rolling pose (it rolls: neutral, critical tilt 0)."""
        return self.kind == "rolling"

    #: the keys of each of ``plumbob poses --json``'s ``poses`` (docs/cli.md's table)
    KEYS = (
        Key("down", "", "the direction of gravity resting so, body frame (unit vector)",
            type="xyz"),
        Key("com_height", "m", "the centre of mass's height above the ground", type="float"),
        Key("probability", "", "of landing so from a random drop (they sum to 1)",
            type="float"),
        Key("critical_tilt_deg", "°", "the least tilt of the ground that topples it out of "
                                      "the pose", type="float"),
        Key("energy_barrier", "J", "to leave it over the lowest neighbouring saddle (`null` "
                                   "for the only pose)", type="float"),
        Key("kind", "", "`face`, `rolling` (a family of faces it rolls between) or "
                        "`rocking` (a bowl's bottom)", type="str"),
        Key("neutral", "", "whether it rolls (a rolling pose)", type="bool"),
        Key("members", "", "how many physical faces the pose stands for", type="int"),
        Key("axis", "", "the axis a rolling pose rolls about, body frame (`null` otherwise)"),
        Key("face", "m", "the corners of the face it rests on, body frame"),
        Key("transform", "", "4×4, row-major: rests the body on z = 0, centre of mass above "
                             "the origin"),
    )

    def __repr__(self) -> str:
        barrier = "None" if self.energy_barrier is None else f"{_short(self.energy_barrier)} J"
        kind = ""
        if self.kind == "rolling":
            about = "" if self.axis is None else f" about {_vector(self.axis)}"
            kind = f", rolling{about} ({self.members} faces)"
        elif self.kind == "rocking":
            kind = f", rocking ({self.members} faces)"
        return (f"Pose(probability={_short(self.probability)}, down={_vector(self.down)}, "
                f"com_height={_short(self.com_height)} m, "
                f"critical_tilt_deg={_short(self.critical_tilt_deg)}°, "
                f"energy_barrier={barrier}{kind})")


@dataclass(frozen=True, repr=False)
class Poses(Result):
    """All stable resting poses of a body, most probable first.

    Indexing and ``len`` go through :attr:`poses`.

    Attributes
    ----------
    poses : tuple of Pose
        The poses; their probabilities add up to 1.
    mass : float
        kg.
    g : float
        Gravitational acceleration, m/s², for the energy barriers.
    center_of_mass : numpy.ndarray
        (dim,) m, body frame.
    method : str
        ``"exact"`` (basin areas traced exactly) or ``"sampled"`` (the fallback: a
        descent from a Fibonacci lattice of directions).
    hull_faces : int
        Faces of the exact hull (its triangles merged where coplanar to round-off).
    saddles : int
        How many saddles (3D) or maxima (2D) bound the basins.
    area_error : float
        |Σ basin areas − 4π| / 4π (2π for a lamina) before normalising.
    notes : tuple of str
        What a reader should know (merged families, fallbacks).
    """

    poses: tuple[Pose, ...]
    mass: float
    g: float
    center_of_mass: np.ndarray
    method: str
    hull_faces: int
    saddles: int
    area_error: float
    notes: tuple[str, ...] = field(default=())
    source: Source | None = field(default=None, compare=False)

    def text(self, units=None, *, top: int | None = None,
             min_probability: float | None = None, written=()) -> str:
        """The report ``plumbob poses`` prints (``str(poses)``): lengths and masses in
        ``units`` (a :class:`~plumbob.report.ReportUnits` or ``"mm,g"``; default the
        part's own, else SI); at most ``top`` poses, each at least ``min_probability``
        likely; the files ``written``; the body's notes and these poses'."""
        from ...report import units_for
        from ...report.poses import poses_text

        s = self.source or Source()
        shown, rest, rest_p = self.shown(top, min_probability)
        size = s.size or float(np.abs(self.center_of_mass).max(initial=0.0)) or 1.0
        return poses_text(self, shown, s.path or "body", size, units_for(units, s.length_unit),
                          left_out=(rest, rest_p), written=written,
                          notes=(*s.notes, *self.notes))

    def __len__(self) -> int:
        return len(self.poses)

    def __getitem__(self, index: int) -> Pose:
        return self.poses[index]

    def ranked(self, rank: int, what: str = "rank") -> Pose:
        """The ``rank``-th most probable pose (1-based, as ``plumbob poses`` numbers them
        and ``--pose K`` takes them); a :class:`~plumbob.errors.StabilityError` naming
        ``what`` for a rank out of range."""
        from ...errors import StabilityError

        if not 1 <= rank <= len(self.poses):
            raise StabilityError(f"{what} must be between 1 and {len(self.poses)} (the body "
                                 f"has {len(self.poses)} resting poses)")
        return self.poses[rank - 1]

    @property
    def probabilities(self) -> np.ndarray:
        """(len,) the poses' probabilities, most probable first."""
        return np.array([p.probability for p in self.poses])

    def shown(self, top: int | None = None, min_probability: float | None = None
              ) -> tuple[tuple[Pose, ...], int, float]:
        """The poses worth showing: at most ``top`` of them, each at least
        ``min_probability`` likely (the most probable pose is always shown). Returns the
        shown poses, and how many are left out and their total probability.

        >>> from plumbob.bodies.primitives import box
        >>> from plumbob.stability import resting_poses
        >>> shown, rest, p = resting_poses(box(1, 1, 4)).shown(top=4)
        >>> len(shown), rest, round(p, 4)
        (4, 2, 0.0375)
        """
        keep = list(self.poses)
        if min_probability is not None:
            keep = keep[:1] + [q for q in keep[1:] if q.probability >= min_probability]
        if top is not None:
            keep = keep[:max(int(top), 1)]
        kept = {id(q) for q in keep}
        rest = [q for q in self.poses if id(q) not in kept]
        return tuple(keep), len(rest), float(sum(q.probability for q in rest))

    def plot(self, fig=None, *, body=None, **options):
        """Draw the pose gallery (the body in each pose if given); returns the matplotlib
        figure. See :func:`plumbob.plot.plot_poses`."""
        from ...plot.gallery import plot_poses

        return plot_poses(self, body, fig, **options)

    def _repr_png_(self) -> bytes:  # notebooks show the gallery
        from ...plot.files import png_bytes

        return png_bytes(self.plot())

    def _repr_html_(self) -> str:
        """A notebook's table: a row per pose (probability, down, height, critical tilt)
        under the keys of the whole (SI units)."""
        from html import escape

        head = "".join(f"<tr><th>{k}</th><td>{escape(str(v))}</td></tr>"
                       for k, v in (("mass", _short(self.mass)), ("g", _short(self.g)),
                                    ("method", self.method), ("hull_faces", self.hull_faces)))
        rows = "".join(
            f"<tr><td>{k}</td><td>{p.probability:.6f}</td><td>{escape(str(p.down.round(4)))}"
            f"</td><td>{_short(p.com_height)}</td><td>{_short(p.critical_tilt_deg)}</td></tr>"
            for k, p in enumerate(self.poses, 1))
        return (f"<table><caption>Poses (SI units)</caption>{head}</table><table><tr><th>#</th>"
                "<th>probability</th><th>down</th><th>com_height, m</th>"
                f"<th>critical_tilt_deg</th></tr>{rows}</table>")

    #: the keys of ``plumbob poses --json`` after the file's (docs/cli.md's table)
    KEYS = (
        Key("mass", "kg", "the mass", type="float"),
        Key("center_of_mass", "m", "the centre of mass, body frame", type="xyz"),
        Key("g", "m/s²", "gravitational acceleration, for the energy barriers", type="float"),
        Key("method", "", "`exact` (basins traced exactly) or `sampled` (the fallback)",
            type="str"),
        Key("hull_faces", "", "faces of the exact hull, coplanar triangles merged",
            type="int"),
        Key("poses", "", "the poses, most probable first (the keys below)"),
        Key("notes", "", "what a reader should know (merged families, fallbacks)",
            "when there are any", type="strings"),
    )

    def __repr__(self) -> str:
        shown = ", ".join(_short(p.probability) for p in self.poses[:_SHOWN])
        more = ", …" if len(self.poses) > _SHOWN else ""
        return (f"Poses({len(self.poses)} pose(s), probabilities=({shown}{more}), "
                f"method={self.method!r}, mass={_short(self.mass)} kg, "
                f"hull_faces={self.hull_faces})")
