"""What a batch run computes for every file: one frozen, picklable record.

The same :class:`Options` travels to every worker process or Dask worker, so every
file is read and measured with the same units, density, down direction and tilt.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..arguments import in_range, non_negative, number, optional, positive, unit_vector
from ..errors import PlumbobError
from ..units import SEED_GRAVITY

__all__ = ["Options", "INERTIAL_FORMATS"]

#: simulator inertial blocks that can be added as columns (plumbob.export.inertial.FORMATS,
#: written out here so that building the CLI parser imports no numpy)
INERTIAL_FORMATS = ("urdf", "sdf", "mjcf")


@dataclass(frozen=True)
class Options:
    """Options applied to every file of a batch (those of the single-file commands).

    units: length unit of the files' coordinates (``--units``); None: each file's own,
        else metres.
    material, density: the density of parts that give none (``--material``/``--density``).
    repair: close small holes and fix winding in meshes (``--repair``).
    check: add the stability verdict as it stands (``plumbob check``) to each row.
    down, tilt, toward, require_tilt, g: as ``plumbob check`` (``--down``, ``--tilt``,
        ``--toward``, ``--require-tilt``, ``--g``); ``g`` also sets the poses' barriers.
    poses: add the resting-pose summary (``plumbob poses``) to each row.
    pose_table: also return every pose of every file (the long-format pose table).
    inertial: simulator inertial blocks to add as columns (``urdf``, ``sdf``, ``mjcf``).
    timeout: seconds allowed per file; None: no limit.
    load_options: the parsed ``--force``/``--hang``/``--push``/``--press`` values (points
        in each file's length unit; :func:`plumbob.loads.loads_from_options`): the check
        under loads, with its factor of safety.
    standard: a standard's name (``--standard``): a column per test.
    """

    units: str | None = None
    material: str | None = None
    density: float | None = None
    repair: bool = False
    check: bool = False
    down: tuple[float, ...] | None = None
    tilt: float | None = None
    toward: float | None = None
    require_tilt: float | None = None
    g: float = SEED_GRAVITY
    poses: bool = False
    pose_table: bool = False
    inertial: tuple[str, ...] = ()
    timeout: float | None = None
    load_options: tuple = ()
    standard: str | None = None

    def __post_init__(self) -> None:
        unknown = [f for f in self.inertial if f not in INERTIAL_FORMATS]
        if unknown:
            raise PlumbobError(f"unknown inertial format {unknown[0]!r}; use "
                               f"{', '.join(INERTIAL_FORMATS)}")
        if self.material is not None and self.density is not None:
            raise PlumbobError("give --material or --density, not both")
        # Every value checked once here, so a bad one stops the run before any file.
        checks = {"g": positive, "tilt": non_negative, "toward": number, "density": positive,
                  "timeout": positive}
        for name, check in checks.items():
            object.__setattr__(self, name, optional(check, getattr(self, name), name))
        object.__setattr__(self, "require_tilt", optional(
            in_range, self.require_tilt, "require_tilt", 0, 90, unit="°"))
        if self.material is not None and not str(self.material).strip():
            raise PlumbobError("a material name must not be empty")
        if self.toward is not None and self.tilt is None:
            raise PlumbobError("--toward needs --tilt DEG")
        if self.down is not None:
            unit_vector(self.down, "down")  # not zero, finite, 2 or 3 numbers
            object.__setattr__(self, "down", tuple(float(v) for v in self.down))
        object.__setattr__(self, "inertial", tuple(self.inertial))
        object.__setattr__(self, "load_options", tuple(
            (kind, tuple(v) if isinstance(v, (list, tuple)) else v,
             tuple(w) if isinstance(w, (list, tuple)) else w)
            for kind, v, w in self.load_options))
        if self.standard is not None:
            from ..stability.standards import PRESETS

            if self.standard not in PRESETS:
                raise PlumbobError(f"unknown standard {self.standard!r}; plumbob models: "
                                   f"{', '.join(PRESETS)}")
        # A tilt, a down direction, a design check or loads only mean something to the check.
        if any(v is not None for v in (self.down, self.tilt, self.toward, self.require_tilt,
                                       self.standard)) or self.load_options:
            object.__setattr__(self, "check", True)
        if self.pose_table:
            object.__setattr__(self, "poses", True)

    def requirement(self, reading=None):
        """The check's :class:`~plumbob.stability.requirement.Requirement`: the same for
        every file, but for the loads' points, in each file's length unit (``reading``)."""
        from ..loads import loads_from_options
        from ..stability.requirement import Requirement
        from ..units import length_scale

        loads = ()
        if reading is not None:
            loads = tuple(reading.loads) + loads_from_options(
                self.load_options, length_scale(reading.length_unit))
        return Requirement(self.down, self.g, self.tilt, self.toward,
                           require_tilt_deg=self.require_tilt, loads=loads)
