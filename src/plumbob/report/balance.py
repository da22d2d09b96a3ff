"""The text report of ``plumbob balance``: the target, the body before and after, the
ballast (its shape and pocket), and a hollowing's lines.

Formatting only: every number comes from the :mod:`plumbob.balance` results.
"""

from __future__ import annotations

from . import clean, format_number, format_vector, table

__all__ = ["balance_text", "hollow_text"]


def hollow_text(w, scale: float) -> str:
    """The hollowing's lines: what was emptied and written, and the written file's check."""
    def num(value: float, digits: int = 6) -> str:
        return format_number(float(clean(value, scale)), digits)

    p = w.plan
    if p.cut is None:
        carved = "nothing emptied: it meets the target as it is"
    else:
        carved = (f"the interior beyond the plane n·p = {num(p.cut.offset)} m, n = "
                  f"{format_vector(p.cut.normal, 4)}, emptied ({p.pieces} piece"
                  f"{'s' if p.pieces != 1 else ''}), {num(p.removed_mass)} kg removed")
    short = "" if p.target_met else "; carving alone falls short: ballast makes up the rest"
    rows = [("hollowed", f"walls {num(p.wall)} m: {carved}{short}"),
            ("bound", f"{p.bound.sentence()} (the relaxation over {num(p.bound.cell_size, 4)} m "
                      f"cells: {num(p.bound.relaxed, 4)}); planned in {p.seconds:.1f} s"),
            ("before", f"mass {num(p.before.mass)} kg, centre of mass "
                       f"{format_vector(clean(p.before.center_of_mass, scale))} m"),
            ("after (written)", f"mass {num(w.mass_properties.mass)} kg, centre of mass "
                                f"{format_vector(clean(w.mass_properties.center_of_mass, scale))} m, "
                                f"{w.verdict.verdict}, margin {num(w.verdict.margin)} m, critical "
                                f"tilt {num(w.verdict.critical_tilt_deg, 4)}°"),
            ("wrote", w.out + (f" and the void {w.void}" if w.void else ""))]
    return table(rows, title="hollowing")


def balance_text(r, path: str, kind: str, notes: list[str], scale: float) -> str:
    """The text report of a ballast plan ``r`` (a :class:`~plumbob.balance.result.BalanceResult`)
    on the body read from ``path``: the target, before, the ballast, after, the result;
    round-off below ``scale`` (the body's size) shown as 0."""
    def num(value: float, digits: int = 6) -> str:
        return format_number(float(clean(value, scale)), digits)

    def vec(values, digits: int = 6) -> str:
        return format_vector(clean(values, scale), digits)

    wanted = []
    if r.margin_target is not None:
        wanted.append(f"margin ≥ {num(r.margin_target)} m")
    if r.require_tilt_deg is not None:
        way = "in every direction" if r.toward is None else f"toward {vec(r.toward, 4)}"
        wanted.append(f"no toppling at {num(r.require_tilt_deg, 4)}° {way}")

    def state(v) -> str:
        way = ("" if r.toward is None or v.verdict != "stands" else
               f", tips at {num(v.tipping_angle_deg(r.toward), 4)}° that way")
        return (f"{v.verdict}, margin {num(v.margin)} m, critical tilt "
                f"{num(v.critical_tilt_deg, 4)}°{way}, centre of mass "
                f"{vec(v.center_of_mass)} m")

    rows = [("target", ", ".join(wanted)), ("down", vec(r.down)), ("before", state(r.before))]
    if r.ballast_mass == 0:
        rows.append(("ballast", "none needed: it meets the target as it is"))
    else:
        rows.append(("ballast", f"{num(r.ballast_mass)} kg centred at {vec(r.ballast_point)} m"))
        if r.ballast_density is not None:
            dims = r.ballast_dimensions
            if r.ballast_shape == "cylinder":
                shape = f"a cylinder of radius {num(dims[0], 4)} m and height {num(dims[1], 4)} m"
            elif r.ballast_shape == "square":
                shape = (f"a square of side {num(dims[0], 4)} m through the lamina's "
                         f"{num(r.ballast_depth, 4)} m")
            else:
                shape = f"a cube of side {num(dims[0], 4)} m"
            rows.append(("ballast shape", f"{r.ballast_material} ({num(r.ballast_density)} "
                                          f"kg/m³), {num(r.ballast_volume, 4)} m³: {shape}, "
                                          "fits inside"))
            if r.pocket:
                rows.append(("pocket", f"it fills a pocket cut for it: the body gains "
                                       f"{num(r.added_mass)} kg"))
        rows.append(("after", state(r.after) + f", mass {num(r.after.mass)} kg"))
    rows.append(("result", "meets the target (checked with the ballast added)" if r.passes
                 else "does NOT meet the target"))
    lines = [table(rows, title=f"plumbob balance {path} ({kind})")]
    lines += [f"note: {note}" for note in notes]
    return "\n".join(lines)
