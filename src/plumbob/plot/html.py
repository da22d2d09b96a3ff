"""``report_page``: one self-contained HTML page for a design review.

An interactive 3-D view of the body (plotly's offline HTML, its script embedded once,
so the page needs no network when viewed) with the centre of mass, the support polygon
and the ground; the mass-properties table; the stability verdict and its tilt rose; the
pose gallery (a PNG inside the page) with the probabilities. Large meshes are decimated
for the view only, and the page says so; every number comes from the full body.
"""

from __future__ import annotations

import base64
import html

import numpy as np

from .geometry import Drawing, drawing, in_frame, rest_frame
from .rose import _direction_name, rose_samples
from .style import STATUS_COLOURS, fmt, fmt_point, part_colours, status, units_or_si

__all__ = ["report_page", "REPORT_FACES"]

REPORT_FACES = 60_000  # triangles in the interactive view: smooth, and a page of a few MB
GALLERY_DPI = 80  # the pose gallery's PNG, shown at its own size (one image pixel a CSS pixel)
TABLE_FONT_PX = 16  # the browser's default font size, the tables' (no CSS sets another)

_STYLE = """
body { font-family: system-ui, sans-serif; max-width: 1100px; margin: 1.5em auto; color: #222;
       padding: 0 1em; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; margin-top: 1.6em; border-bottom: 1px solid #ccc; }
table { border-collapse: collapse; margin: 0.5em 0; }
td, th { padding: 0.25em 0.8em; border-bottom: 1px solid #e5e5e5; text-align: left;
         font-variant-numeric: tabular-nums; }
.verdict { font-size: 1.2em; font-weight: bold; padding: 0.3em 0.6em; border-radius: 4px;
           display: inline-block; color: white; }
.note { color: #555; font-size: 0.9em; }
.row { display: flex; flex-wrap: wrap; gap: 1em; align-items: flex-start; }
img { max-width: 100%; }
"""


def _e(text) -> str:
    return html.escape(str(text))


def _table(rows: list[tuple[str, str]]) -> str:
    body = "".join(f"<tr><th>{_e(k)}</th><td>{_e(v)}</td></tr>" for k, v in rows)
    return f"<table>{body}</table>"




def _mass_rows(body, props, size: float, u) -> list[tuple[str, str]]:
    rows = [("kind", getattr(body, "kind", "body")),
            ("mass", f"{fmt(u.mass(props.mass), 6)} {u.mass_unit}")]
    if props.measure:
        dim = props.dim
        rows.append(("area" if dim == 2 else "volume",
                     f"{fmt(u.measure(props.measure, dim), 6)} {u.unit('measure', dim)}"))
        rows.append(("mean density",
                     f"{fmt(u.density(props.density, dim), 6)} {u.unit('density', dim)}"))
    rows.append(("centre of mass",
                 f"{fmt_point(u.length(props.center_of_mass), 6, u.length(size))} {u.length_unit}"))
    inertia = np.asarray(u.inertia(props.inertia))
    inertia = np.where(np.abs(inertia) < 1e-12 * max(np.abs(inertia).max(), 1e-300), 0.0, inertia)
    for i, row in enumerate(inertia):
        rows.append(("inertia about G" if i == 0 else "", f"{fmt_point(row, 6)} {u.unit('inertia')}"))
    rows.append(("principal moments",
                 f"{fmt_point(u.inertia(props.principal_moments), 6)} {u.unit('inertia')}"))
    rows.append(("exact", props.exactness))
    return rows


def _parts_html(parts, size: float, u) -> str:
    """The per-part table of an assembly: name, kind, density, mass, centre."""
    head = (f"<tr><th>part</th><th>kind</th><th>mean density</th><th>mass, {u.mass_unit}</th>"
            f"<th>centre of mass, {u.length_unit}</th></tr>")
    rows = []
    for name, kind, props in parts:
        dim = props.dim
        density = (f"{fmt(u.density(props.density, dim), 5)} {u.unit('density', dim)}"
                   if props.measure else "—")
        rows.append(f"<tr><td>{_e(name)}</td><td>{_e(kind)}</td><td>{_e(density)}</td>"
                    f"<td>{fmt(u.mass(props.mass), 6)}</td>"
                    f"<td>{_e(fmt_point(u.length(props.center_of_mass), 6, u.length(size)))}</td>"
                    "</tr>")
    return f'<table class="parts">{head}{"".join(rows)}</table>'


def _view_3d(d: Drawing, rows: np.ndarray, com, verdict, scale: float = 1.0, unit: str = "m"):
    """The 3-D view, lengths times ``scale`` (metres to the report's ``unit``)."""
    import plotly.graph_objects as go

    fig = go.Figure()
    colours, _ = part_colours(d.pieces)
    for piece, colour in zip(d.pieces, colours):
        if piece.triangles is not None and len(piece.triangles):
            # single precision is plenty on screen and halves the page
            t = scale * in_frame(piece.triangles, rows).reshape(-1, 3).astype(np.float32)
            k = np.arange(0, len(t), 3, dtype=np.int32)
            fig.add_trace(go.Mesh3d(x=t[:, 0], y=t[:, 1], z=t[:, 2], i=k, j=k + 1, k=k + 2,
                                    color=colour, opacity=0.6, flatshading=True, name=piece.label,
                                    showlegend=True))
        if piece.points is not None:
            p = scale * in_frame(piece.points, rows)
            fig.add_trace(go.Scatter3d(x=p[:, 0], y=p[:, 1], z=p[:, 2], mode="markers",
                                       marker=dict(size=6, color=colour), name=piece.label))
    c = scale * in_frame(com, rows)
    if verdict is not None:
        support = scale * in_frame(verdict.support.polygon, rows)
        loop = np.vstack((support, support[:1]))
        fig.add_trace(go.Scatter3d(x=loop[:, 0], y=loop[:, 1], z=loop[:, 2], mode="lines+markers",
                                   line=dict(color="black", width=6), marker=dict(size=3),
                                   name="support polygon"))
        foot = scale * in_frame(verdict.support.plane_point, rows)
        fig.add_trace(go.Scatter3d(x=[c[0], foot[0]], y=[c[1], foot[1]], z=[c[2], foot[2]],
                                   mode="lines+markers", name="weight",
                                   line=dict(color="black", width=3, dash="dash"),
                                   marker=dict(size=[0, 7], color=STATUS_COLOURS[status(verdict)],
                                               symbol="square")))
        pts = scale * (d.all_points() @ rows.T)
        lo, hi = pts[:, :2].min(axis=0), pts[:, :2].max(axis=0)
        pad = 0.15 * float(np.max(hi - lo))
        xs = [lo[0] - pad, hi[0] + pad, hi[0] + pad, lo[0] - pad]
        ys = [lo[1] - pad, lo[1] - pad, hi[1] + pad, hi[1] + pad]
        fig.add_trace(go.Mesh3d(x=xs, y=ys, z=[foot[2]] * 4, i=[0, 0], j=[1, 2], k=[2, 3],
                                color="#9e9e9e", opacity=0.35, name="ground", showlegend=True))
    fig.add_trace(go.Scatter3d(x=[c[0]], y=[c[1]], z=[c[2]], mode="markers", name="centre of mass G",
                               marker=dict(size=8, color="white", line=dict(color="black", width=4))))
    names = ("x", "y", "z") if np.allclose(rows, np.eye(3)) else ("e1", "e2", "up")
    fig.update_layout(scene=dict(aspectmode="data", xaxis_title=f"{names[0]}, {unit}",
                                 yaxis_title=f"{names[1]}, {unit}", zaxis_title=f"{names[2]}, {unit}"),
                      height=600, margin=dict(l=0, r=0, t=30, b=0), legend=dict(x=0, y=1))
    return fig


def _view_2d(d: Drawing, rows: np.ndarray, com, verdict, scale: float = 1.0, unit: str = "m"):
    """The 2-D view, lengths times ``scale`` (metres to the report's ``unit``)."""
    import plotly.graph_objects as go

    fig = go.Figure()
    colours, _ = part_colours(d.pieces)
    for piece, colour in zip(d.pieces, colours):
        if piece.rings:
            xs, ys = [], []
            for ring in piece.rings:
                r = scale * in_frame(ring, rows)
                xs += list(r[:, 0]) + [None]
                ys += list(r[:, 1]) + [None]
            fig.add_trace(go.Scatter(x=xs, y=ys, fill="toself", fillcolor=colour, mode="lines",
                                     line=dict(color="#222"), name=piece.label))
    c = scale * in_frame(com, rows)
    if verdict is not None:
        s = scale * in_frame(verdict.support.polygon, rows)
        fig.add_trace(go.Scatter(x=s[:, 0], y=s[:, 1], mode="lines+markers", name="support",
                                 line=dict(color="black", width=6)))
        fig.add_hline(y=float(scale * in_frame(verdict.support.plane_point, rows)[1]), line_color="#555")
    fig.add_trace(go.Scatter(x=[c[0]], y=[c[1]], mode="markers", name="centre of mass G",
                             marker=dict(size=12, color="white", line=dict(color="black", width=3))))
    fig.update_yaxes(scaleanchor="x", scaleratio=1, title=f"y, {unit}")
    fig.update_xaxes(title=f"x, {unit}")
    fig.update_layout(height=550, margin=dict(l=0, r=0, t=30, b=0))
    return fig


def _rose(verdict):
    import plotly.graph_objects as go

    angles, tilts = rose_samples(verdict)
    shown = np.maximum(tilts, 0.0)
    fig = go.Figure()
    colour = STATUS_COLOURS[status(verdict)]
    if len(angles) == 2:
        fig.add_trace(go.Barpolar(r=shown, theta=np.degrees(angles), width=[12, 12],
                                  marker_color=colour, name="critical tilt, °"))
    else:
        fig.add_trace(go.Scatterpolar(r=shown, theta=np.degrees(angles), fill="toself",
                                      line=dict(color="#222"), fillcolor=colour, opacity=0.6,
                                      name="critical tilt, °"))
    g = np.asarray(verdict.support.frame.axes, dtype=float) @ np.asarray(verdict.critical_direction)
    weakest = float(np.degrees(np.arctan2(g[1], g[0]))) if len(g) > 1 else \
        (0.0 if g[0] > 0 else 180.0)
    fig.add_trace(go.Scatterpolar(
        r=[max(verdict.critical_tilt_deg, 0.0)], theta=[weakest], mode="markers+text",
        marker=dict(symbol="triangle-down", size=14, color=STATUS_COLOURS["topples"],
                    line=dict(color="#222", width=1)),
        text=[f"weakest {fmt(verdict.critical_tilt_deg, 3)}°"], textposition="top center",
        name=f"weakest: {fmt(verdict.critical_tilt_deg, 3)}° toward "
             f"{fmt_point(verdict.critical_direction, 3)}"))
    if verdict.required_tilt_deg is not None:
        circle = np.arange(0, 361, 2.0)
        fig.add_trace(go.Scatterpolar(r=np.full(len(circle), verdict.required_tilt_deg),
                                      theta=circle, mode="lines", line=dict(dash="dash", color="#222"),
                                      name=f"required {fmt(verdict.required_tilt_deg, 3)}°"))
    axes = np.asarray(verdict.support.frame.axes, dtype=float)
    names = [_direction_name(axes[0], "+e1"), _direction_name(-axes[0], "−e1")]
    ticks = {0: names[0], 180: names[1]}
    if len(axes) > 1:
        ticks.update({90: _direction_name(axes[1], "+e2"), 270: _direction_name(-axes[1], "−e2")})
    fig.update_layout(height=460, width=480, margin=dict(l=40, r=40, t=50, b=40),
                      title="tilt rose: critical tilt, ° (toward each direction)",
                      font=dict(size=14),
                      polar=dict(angularaxis=dict(tickmode="array", tickvals=list(ticks),
                                                  ticktext=[f"toward {ticks[0]}"] +
                                                  [ticks[k] for k in list(ticks)[1:]])),
                      legend=dict(orientation="h", y=-0.15))
    return fig


def headline(verdict) -> str:
    """The verdict's headline: what a reviewer must see first. A failed requirement
    is the headline (``FAIL: required tilt 10° not met (critical tilt 4.2°)``), never a
    table row under a "stands" badge."""
    if verdict.required_tilt_deg is not None and verdict.passes is False:
        level = {"neutral": "is in neutral balance"}.get(verdict.verdict, verdict.verdict)
        return (f"FAIL: required tilt {fmt(verdict.required_tilt_deg, 3)}° not met "
                f"(critical tilt {fmt(verdict.critical_tilt_deg, 4)}°; on level ground it "
                f"{level})")
    if verdict.required_tilt_deg is not None:
        return f"PASS: {verdict.verdict}, required tilt {fmt(verdict.required_tilt_deg, 3)}° met"
    return str(verdict.verdict)


def _badge(verdict, element_id: str = "") -> str:
    """The verdict's coloured headline: red for a failed requirement whatever the
    verdict on level ground."""
    failed = verdict.required_tilt_deg is not None and verdict.passes is False
    colour = STATUS_COLOURS["topples" if failed else status(verdict)]
    text_colour = "#222" if status(verdict) == "amber" and not failed else "white"
    ident = f' id="{element_id}"' if element_id else ""
    return (f'<p><span class="verdict"{ident} style="background:{colour};color:{text_colour}">'
            f"{_e(headline(verdict))}</span></p>")


def _verdict_html(verdict, u) -> str:
    rows = [("critical tilt", f"{fmt(verdict.critical_tilt_deg, 4)}° toward "
                              f"{fmt_point(verdict.critical_direction, 3)}"),
            ("stability margin", f"{fmt(u.length(verdict.margin), 5)} {u.length_unit}"),
            ("energy to topple", f"{fmt(verdict.energy_to_topple, 5)} J"),
            ("height of G", f"{fmt(u.length(verdict.com_height), 5)} {u.length_unit}"),
            ("support", f"{verdict.support.kind}, {len(verdict.support.vertices)} corner(s)")]
    if verdict.required_tilt_deg is not None:
        rows.append((f"required tilt {fmt(verdict.required_tilt_deg, 3)}°",
                     "PASS" if verdict.passes else "FAIL"))
    return _badge(verdict) + _table(rows)


def _poses_html(poses, body, u) -> str:
    import matplotlib

    from .files import png_bytes
    from .gallery import plot_poses

    # Captions ("small", 0.833 of font.size) no smaller than the table's text on screen.
    points = TABLE_FONT_PX * 72 / GALLERY_DPI / 0.833
    with matplotlib.rc_context({"font.size": points}):
        figure = plot_poses(poses, body, units=u)
        image = base64.b64encode(png_bytes(figure, dpi=GALLERY_DPI)).decode("ascii")
    head = f"<tr><th>#</th><th>probability</th><th>down</th><th>height of G, {u.length_unit}" \
           "</th><th>critical tilt, °</th></tr>"
    body_rows = "".join(
        f"<tr><td>{k}</td><td>{p.probability:.4f}</td><td>{_e(fmt_point(p.down, 3))}</td>"
        f"<td>{fmt(u.length(p.com_height), 5)}</td><td>{fmt(p.critical_tilt_deg, 4)}"
        f"{' (rolls)' if p.neutral else ''}</td></tr>"
        for k, p in enumerate(poses.poses, 1))
    return (f'<img alt="pose gallery" src="data:image/png;base64,{image}">'
            f"<table>{head}{body_rows}</table>")


def _loads_html(loaded, u) -> str:
    """The load case: each load's point, force and moment about the critical edge, the
    moments and the factor of safety, the verdict under the loads."""
    factor = loaded.overturning_safety_factor
    rows = [("verdict under the loads", loaded.verdict),
            ("critical edge", f"{fmt_point(u.length(loaded.edge_start), 4)}–"
                              f"{fmt_point(u.length(loaded.edge_end), 4)} {u.length_unit}"),
            ("resisting / overturning", f"{fmt(loaded.resisting_moment, 5)} / "
                                        f"{fmt(loaded.overturning_moment, 5)} N·m"),
            ("factor of safety", "— (nothing overturns it)" if factor is None else fmt(factor, 4))]
    rows += [(f"{m.name} ({m.kind})", f"{fmt_point(m.force, 4)} N at "
              f"{fmt_point(u.length(m.at), 4)} {u.length_unit}: {fmt(m.moment, 5)} N·m")
             for m in loaded.moments]
    return _table(rows)


def _standard_html(result) -> str:
    """A standard's tests: each one's clause, verdict and margin, and the bundle."""
    rows = [(f"{t.name}{f' [{t.case}]' if t.case else ''} ({t.clause})",
             f"{'PASS' if t.passes else 'FAIL'}: {t.verdict}, margin {fmt(t.margin, 4)} "
             f"({'degrees' if t.margin_unit == 'deg' else 'factor of safety − 1'})")
            for t in result.tests]
    rows.append(("bundle", "PASSES" if result.passes else "FAILS"))
    return (f"<p>{_e(result.title)}, {_e(result.edition)}, clause {_e(result.clause)}.</p>"
            + _table(rows) + f'<p class="note">{_e(result.disclaimer)}.</p>')


def report_page(body, props, verdict=None, poses=None, *, path: str | None = None,
                notes=(), max_faces: int = REPORT_FACES, units=None, parts=(),
                standard=None) -> str:
    """The HTML of one self-contained report page (a string).

    body, props: the body and its mass properties. verdict: its stability verdict, or
    None. poses: its resting poses, or None. path: the file, for the title. notes: lines
    for the notes section (why a section is missing, the reader's notices). units: a
    :class:`plumbob.report.ReportUnits` for the tables (default SI). parts: (name, kind,
    mass properties) of each part of an assembly, for the per-part table. standard: a
    standard's tests (:func:`plumbob.stability.standards.run_standard`), or None.
    """
    u = units_or_si(units)
    parts_of = tuple(parts)
    d = drawing(body, max_faces)
    size = float(np.ptp(d.all_points(), axis=0).max()) or 1.0
    com = np.asarray(props.center_of_mass, dtype=float)
    dim = com.size
    if verdict is not None:
        rows = rest_frame(verdict.down, verdict.support.frame.axes)
    else:
        rows = np.eye(dim)
    view = (_view_3d if dim == 3 else _view_2d)(d, rows, com, verdict, float(u.length(1.0)),
                                                 u.length_unit)
    title = " — ".join(x for x in ("plumbob report", path, getattr(body, "name", None)) if x)
    sections = [f"<h1>{_e(title)}</h1>"]
    if verdict is not None:  # the verdict first: PASS or FAIL is what a reviewer looks for
        sections.append(_badge(verdict, "headline"))
    parts = [*sections, "<h2>Body</h2>",
             view.to_html(full_html=False, include_plotlyjs=True, config={"responsive": True})]
    if d.note:
        parts.append(f'<p class="note">3-D view: {_e(d.note)}.</p>')
    parts += ["<h2>Mass properties</h2>", _table(_mass_rows(body, props, size, u))]
    if parts_of:
        parts += [f"<h2>Parts ({len(parts_of)})</h2>", _parts_html(parts_of, size, u)]
    if verdict is not None:
        parts += ["<h2>Stability on level ground</h2>", '<div class="row"><div>',
                  _verdict_html(verdict, u), "</div><div>",
                  _rose(verdict).to_html(full_html=False, include_plotlyjs=False), "</div></div>"]
        if getattr(verdict, "loaded", None) is not None:
            parts += ["<h2>Under the applied loads</h2>", _loads_html(verdict.loaded, u)]
    if standard is not None:
        parts += [f"<h2>Standard: {_e(standard.standard)}</h2>", _standard_html(standard)]
    if poses is not None:
        parts += [f"<h2>Resting poses ({len(poses)}), most probable first</h2>",
                  _poses_html(poses, body, u)]
    if notes:
        parts += ["<h2>Notes</h2>", "<ul>" + "".join(f"<li>{_e(n)}</li>" for n in notes) + "</ul>"]
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>{_e(title)}</title><style>{_STYLE}</style></head><body>"
            + "\n".join(parts) + "</body></html>\n")
