"""The text report of ``plumbob balance``: the target, the body before and after, the
ballast (its shape and pocket), and a hollowing's lines.

Formatting only: every number comes from the :mod:`plumbob.balance` results. Lengths
and masses in the report's units (a part drawn in mm reads in mm and g), angles in
degrees; the JSON stays SI.
"""

from __future__ import annotations

from . import ReportUnits, clean, format_number, format_vector, table

__all__ = ["balance_text", "hollow_text", "need_text", "auto_pose_text", "loaded_text"]


class _Units:
    """Numbers with their units as the report shows them: round-off below ``scale`` (m,
    the body's size) as 0, lengths, masses and volumes in ``units``."""

    def __init__(self, scale: float, units: ReportUnits | None):
        self.scale, self.u = scale, units or ReportUnits()

    def num(self, value: float, digits: int = 6) -> str:
        return format_number(float(clean(value, self.scale)), digits)

    def vec(self, values, digits: int = 6) -> str:
        return format_vector(clean(values, self.scale), digits)

    def length(self, value: float, digits: int = 6) -> str:
        return (f"{format_number(self.u.length(float(clean(value, self.scale))), digits)} "
                f"{self.u.length_unit}")

    def point(self, values, digits: int = 6) -> str:
        return f"{format_vector(self.u.length(clean(values, self.scale)), digits)} {self.u.length_unit}"

    def mass(self, value: float, digits: int = 6) -> str:
        return f"{format_number(self.u.mass(float(value)), digits)} {self.u.mass_unit}"

    def volume(self, value: float, digits: int = 4) -> str:
        return f"{format_number(self.u.measure(float(value), 3), digits)} {self.u.unit('measure')}"

    def density(self, value: float) -> str:
        return f"{format_number(self.u.density(float(value), 3))} {self.u.unit('density')}"


def hollow_text(w, scale: float, units: ReportUnits | None = None) -> str:
    """The hollowing's lines: what was emptied and written, and the written file's check;
    lengths and masses in ``units`` (default SI)."""
    f = _Units(scale, units)

    p = w.plan
    if p.cut is None:
        carved = "nothing emptied: it meets the target as it is"
    else:
        carved = (f"the interior beyond the plane n·p = {f.length(p.cut.offset)}, n = "
                  f"{format_vector(p.cut.normal, 4)}, emptied ({p.pieces} piece"
                  f"{'s' if p.pieces != 1 else ''}), {f.mass(p.removed_mass)} removed")
    short = "" if p.target_met else "; carving alone falls short: ballast makes up the rest"
    relaxed = (f.length(p.bound.relaxed, 4) if p.bound.measure != "critical_tilt_deg"
               else f"{f.num(p.bound.relaxed, 4)}°")
    rows = [("hollowed", f"walls {f.length(p.wall)}: {carved}{short}"),
            ("bound", f"{p.bound.sentence()} (the relaxation over {f.length(p.bound.cell_size, 4)} "
                      f"cells: {relaxed}); planned in {p.seconds:.1f} s"),
            ("before", f"mass {f.mass(p.before.mass)}, centre of mass "
                       f"{f.point(p.before.center_of_mass)}"),
            ("after (written)", f"mass {f.mass(w.mass_properties.mass)}, centre of mass "
                                f"{f.point(w.mass_properties.center_of_mass)}, "
                                f"{w.verdict.verdict}, margin {f.length(w.verdict.margin)}, "
                                f"critical tilt {f.num(w.verdict.critical_tilt_deg, 4)}°"),
            ("wrote", w.out + (f" and the void {w.void}" if w.void else ""))]
    return table(rows, title="hollowing")


def balance_text(r, path: str, kind: str, notes: list[str], scale: float,
                 units: ReportUnits | None = None) -> str:
    """The text report of a ballast plan ``r`` (a :class:`~plumbob.balance.result.BalanceResult`)
    on the body read from ``path``: the target, before, the ballast, after, the result;
    round-off below ``scale`` (the body's size) shown as 0; lengths, masses, volumes and
    densities in ``units`` (default SI)."""
    f = _Units(scale, units)
    num, vec = f.num, f.vec

    wanted = []
    if r.margin_target is not None:
        wanted.append(f"margin ≥ {f.length(r.margin_target)}")
    if r.require_tilt_deg is not None:
        way = "in every direction" if r.toward is None else f"toward {vec(r.toward, 4)}"
        wanted.append(f"no toppling at {num(r.require_tilt_deg, 4)}° {way}")

    def state(v) -> str:
        way = ("" if r.toward is None or v.verdict != "stands" else
               f", tips at {num(v.tipping_angle_deg(r.toward), 4)}° that way")
        return (f"{v.verdict}, margin {f.length(v.margin)}, critical tilt "
                f"{num(v.critical_tilt_deg, 4)}°{way}, centre of mass "
                f"{f.point(v.center_of_mass)}")

    rows = [("target", ", ".join(wanted)), ("down", vec(r.down)), ("before", state(r.before))]
    if r.ballast_mass == 0:
        rows.append(("ballast", "none needed: it meets the target as it is"))
    else:
        rows.append(("ballast", f"{f.mass(r.ballast_mass)} centred at {f.point(r.ballast_point)}"))
        if r.ballast_density is not None:
            dims = r.ballast_dimensions
            if r.ballast_shape == "cylinder":
                shape = (f"a cylinder of radius {f.length(dims[0], 4)} and height "
                         f"{f.length(dims[1], 4)}")
            elif r.ballast_shape == "square":
                shape = (f"a square of side {f.length(dims[0], 4)} through the lamina's "
                         f"{f.length(r.ballast_depth, 4)}")
            else:
                shape = f"a cube of side {f.length(dims[0], 4)}"
            rows.append(("ballast shape", f"{r.ballast_material} ({f.density(r.ballast_density)}), "
                                          f"{f.volume(r.ballast_volume)}: {shape}, fits inside"))
            if r.pocket:
                rows.append(("pocket", f"it fills a pocket cut for it: the body gains "
                                       f"{f.mass(r.added_mass)}"))
        rows.append(("after", state(r.after) + f", mass {f.mass(r.after.mass)}"))
    rows.append(("result", "meets the target (checked with the ballast added)" if r.passes
                 else "does NOT meet the target"))
    lines = [table(rows, title=f"plumbob balance {path} ({kind})")]
    lines += [f"note: {note}" for note in notes]
    return "\n".join(lines)


def need_text(need, units: ReportUnits | None = None) -> str:
    """What one resting pose needs (a :class:`~plumbob.balance.auto.PoseNeed`), in words:
    ``"meets it as it is"``, ``"12 g emptied"``, ``"3.5 kg of ballast"``, ``"no carve
    does: …"``; masses in ``units`` (default kg)."""
    def kg(value: float) -> str:
        return (f"{value:.6g} kg" if units is None else
                f"{units.mass(value):.6g} {units.mass_unit}")

    if need.need == "none":
        return "meets it as it is"
    if need.need == "emptied":
        return f"{kg(need.mass)} emptied"
    if need.need == "ballast":
        return f"{kg(need.mass)} of ballast"
    return f"{need.need} does: {need.reason}"


def auto_pose_text(needs, chosen: int, units: ReportUnits | None = None) -> str:
    """The poses ``--target-pose auto`` tried, what each needs, and the one ``chosen``."""
    lines = [(f"pose {n.pose} ({100 * n.probability:.3g} %)",
              f"down {format_vector(n.down, 4)}: {need_text(n, units)}"
              + ("  <- chosen" if n.pose == chosen else ""))
             for n in needs]
    return table(lines, title="--target-pose auto: the most probable poses tried")


def loaded_text(result, path: str, kind: str, notes: list[str], scale: float,
                units: ReportUnits | None = None, standard: str | None = None) -> str:
    """The report of the least ballast under loads or for a ``standard``: the plan
    (:func:`balance_text`), then the check under the loads with the ballast — for a
    :class:`~plumbob.balance.loaded.LoadedBalance`; a standard whose tilt test needs the
    least gives a plain :class:`~plumbob.balance.result.BalanceResult`."""
    from . import loads_report

    loaded = hasattr(result, "after") and hasattr(result, "test")
    text = balance_text(result.ballast if loaded else result, path, kind, notes, scale, units)
    if loaded:
        which = f" ({standard}: its {result.test} test)" if standard else ""
        return (f"{text}\n\nwith the ballast{which}:\n"
                + loads_report(result.after.loaded, units, scale))
    if standard:
        return f"{text}\n\n({standard}: its tilt test needs the least ballast)"
    return text

