"""The keys of ``plumbob check --json`` (:meth:`Verdict.as_dict
<plumbob.stability.verdict.Verdict.as_dict>`), declared once: name, unit, when, meaning.

``Verdict.KEYS`` is this tuple; ``docs/cli.md``'s check table is generated from it and
``tests/test_result_keys.py`` holds the verdict's JSON and the batch columns to it.
"""

from __future__ import annotations

from ..results import Key

__all__ = ["VERDICT_KEYS"]

#: the keys of ``Verdict.as_dict()``, in order
VERDICT_KEYS = (
    Key("verdict", "", "`stands`, `topples` or `neutral`"),
    Key("stands", "", "whether it stands"),
    Key("margin", "m", "static stability margin: the signed distance from the foot of "
                       "the centre of mass to the support boundary, negative outside"),
    Key("critical_tilt_deg", "°", "the least tilt of the plane, over every direction, "
                                  "that topples it; negative when it topples already"),
    Key("critical_direction", "", "the horizontal unit vector it topples toward first"),
    Key("energy_to_topple", "J", "the least energy to tip it over an edge"),
    Key("com_height", "m", "the centre of mass's height above the plane"),
    Key("center_of_mass", "m", "the centre of mass, body frame"),
    Key("mass", "kg", "the mass"),
    Key("g", "m/s²", "gravitational acceleration"),
    Key("down", "", "the direction of gravity, body frame (unit vector)"),
    Key("support_kind", "", "`polygon`, `segment` or `point`"),
    Key("support_polygon", "m", "the support's corners in the plane"),
    Key("tolerance", "m", "the contact tolerance used"),
    Key("edges", "m, °, J", "per support edge: `start`, `end`, `normal`, `distance`, "
                            "`tipping_angle_deg`, `energy`"),
    Key("slope", "", "the check on the tilted plane (`SlopeCheck.as_dict()`)",
        "with `--tilt DEG`"),
    Key("friction", "", "the friction coefficient", "with `--friction MU`"),
    Key("slides_first", "", "whether it slides before it topples", "with `--friction MU`"),
    Key("overhang", "m", "how far the centre's foot lies beyond the support",
        "when it topples"),
    Key("over_by_deg", "°", "the tilt by which it is over", "when it topples"),
    Key("required_tilt_deg", "°", "the tilt it must withstand in every direction",
        "with `--require-tilt DEG`"),
    Key("passes", "", "whether it withstands it", "with `--require-tilt DEG`"),
    Key("shortfall_deg", "°", "how far the critical tilt falls short",
        "when the tilt check fails"),
    Key("required_margin", "m", "the margin it must have", "with `--margin M`"),
    Key("margin_passes", "", "whether it has it", "with `--margin M`"),
    Key("settles", "", "where a solid set down on a point, a line or a sliver comes to "
                       "rest (see below)", "when set down so"),
    Key("under_loads", "", "the verdict under applied loads (see below)", "with loads"),
)
