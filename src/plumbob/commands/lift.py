"""``plumbob lift PATH``: the energy to raise a structure's material into place, and how
long a crew takes to do it.

plumbob's energy code loads when the command runs.
"""

from __future__ import annotations

import argparse

from ..plot.files import add_plot_argument, write_plot
from ._common import (
    add_report_units_argument,
    add_stability_arguments,
    count,
    header,
    number,
    open_body,
    picture_units,
    positive,
    print_json,
    report_units,
    require_finite,
)

__all__ = ["register", "run"]

DESCRIPTION = """\
The lift (build) energy of a structure: the work to raise all its material from the
ground datum to where it stands, M g z_G, z_G the height of its centre of mass above
the datum (the seed's Great Pyramid: about 2.34e12 J). With --crew or --work-per-day,
that work in days of labour; the default day of work is the seed's, lifting 1000 kg
through 1 m (1000 g J)."""



def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "lift", help="energy to lift a structure's material into place, and crew time",
        description=DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_stability_arguments(parser)
    add_report_units_argument(parser)
    parser.add_argument("--datum", type=number, metavar="Z",
                        help="height of the ground, m (default: the body's lowest point)")
    parser.add_argument("--work-per-day", type=positive, metavar="J",
                        help="work one person does in a day, J (default 1000 g: 1000 kg "
                             "through 1 m)")
    parser.add_argument("--crew", type=count, metavar="N", help="people working at once")
    add_plot_argument(parser)
    parser.set_defaults(func=run)


def run(args) -> int:
    from dataclasses import replace

    from ..energy import crew_time, lift_energy, seed_work_per_day

    reading, props, notes = open_body(args)
    u = report_units(args, reading)
    body = reading.body
    lift = lift_energy(body, datum=args.datum, g=args.g, props=props)
    if args.plot:
        write_plot(args.plot, "lift", lift, body, props=props, path=args.path,
                   units=picture_units(args, reading))
    out = {**header(reading, getattr(body, "kind", "solid")), **lift.as_dict()}
    crew = None
    if args.crew is not None or args.work_per_day is not None:
        work = args.work_per_day
        if work is None:
            work = seed_work_per_day(args.g)
            notes.append(f"work per person per day not given: 1000 kg lifted 1 m, "
                         f"{work:g} J, assumed")
        crew = crew_time(lift.lift_energy, work, args.crew or 1)
        out.update(crew.as_dict())
    require_finite(out)
    if args.json:
        print_json(out, reading, notes)
        return 0
    # the result's own report: str(plumbob.lift(path)), with the crew's days and its note
    source = replace(reading.source(props), notes=tuple(notes))
    print(lift.described(source).text(u, crew=crew))
    return 0
