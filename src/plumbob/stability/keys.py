"""The keys of ``plumbob check --json`` (:meth:`Verdict.as_dict
<plumbob.stability.verdict.Verdict.as_dict>`), declared once: name, unit, when, meaning.

``Verdict.KEYS`` is this tuple followed by each later criterion's own key, declared in
the criterion's module beside its answer (``stability/loaded.py``'s ``VERDICT_KEY``):
``docs/cli.md``'s check table is generated from ``Verdict.KEYS`` and
``tests/test_result_keys.py`` holds the verdict's JSON and the batch columns to it.
"""

from __future__ import annotations

from ..results import Key

__all__ = ["VERDICT_KEYS"]

#: the keys of ``Verdict.as_dict()``, in order
VERDICT_KEYS = (
    Key("verdict", "", "`stands`, `topples` or `neutral`", type="str"),
    Key("stands", "", "whether it stands", type="bool"),
    Key("margin", "m", "static stability margin: the signed distance from the foot of "
                       "the centre of mass to the support boundary, negative outside", type="float"),
    Key("critical_tilt_deg", "°", "the least tilt of the plane, over every direction, "
                                  "that topples it; negative when it topples already",
        type="float"),
    Key("critical_direction", "", "the horizontal unit vector it topples toward first",
        type="xyz"),
    Key("energy_to_topple", "J", "the least energy to tip it over an edge", type="float"),
    Key("com_height", "m", "the centre of mass's height above the plane", type="float"),
    Key("center_of_mass", "m", "the centre of mass, body frame", type="xyz"),
    Key("mass", "kg", "the mass", type="float"),
    Key("g", "m/s²", "gravitational acceleration", type="float"),
    Key("down", "", "the direction of gravity, body frame (unit vector)", type="xyz"),
    Key("support_kind", "", "`polygon`, `segment` or `point`", attr="support.kind",
        type="str"),
    Key("support_polygon", "m", "the support's corners in the plane", attr="support.polygon"),
    Key("tolerance", "m", "the contact tolerance used", attr="support.tolerance",
        type="float"),
    Key("edges", "m, °, J", "per support edge: `start`, `end`, `normal`, `distance`, "
                            "`tipping_angle_deg`, `energy`"),
    Key("slope", "", "the check on the tilted plane (`SlopeCheck.as_dict()`)",
        "with `--tilt DEG`"),
    Key("friction", "", "the friction coefficient", "with `--friction MU`", type="float"),
    Key("slides_first", "", "whether it slides before it topples", "with `--friction MU`",
        type="bool"),
    Key("overhang", "m", "how far the centre's foot lies beyond the support",
        "when it topples", type="float"),
    Key("over_by_deg", "°", "the tilt by which it is over", "when it topples", type="float"),
    Key("required_tilt_deg", "°", "the tilt it must withstand in every direction",
        "with `--require-tilt DEG`", type="float"),
    Key("passes", "", "whether it withstands it", "with `--require-tilt DEG`", type="bool"),
    Key("shortfall_deg", "°", "how far the critical tilt falls short",
        "when the tilt check fails", type="float"),
    Key("required_margin", "m", "the margin it must have", "with `--margin M`", type="float"),
    Key("margin_passes", "", "whether it has it", "with `--margin M`", type="bool"),
    Key("settles", "", "where a solid set down on a point, a line or a sliver comes to "
                       "rest (see below)", "when set down so", attr="settling"),
)
