"""``plumbob materials``: the material table — name, density, category, description, source."""

from __future__ import annotations

import argparse
import re

HELP = "list the materials that specs and --material accept, with densities and sources"
EPILOG = """\
Densities are typical values in kg/m³ near 20 °C; real pieces vary (the
descriptions give ranges). Use a name in a spec (material = "oak") or on the
command line (plumbob mass part.stl --material petg). Names ignore case,
spaces and hyphens."""


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "materials", help=HELP, description=HELP[0].upper() + HELP[1:] + ".", epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("query", nargs="*", metavar="WORD",
                        help="show only materials whose name, category or description "
                             "contains every WORD")
    parser.add_argument("--category", metavar="NAME",
                        help="show only this category (concrete, stone, metal, wood, plastic, "
                             "filament, liquid, ...)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.set_defaults(func=run)


def _matches(entry, words: list[str], category: str | None, whole: bool) -> bool:
    """Every WORD in the name, category or description: as a whole word, or anywhere."""
    text = f"{entry.name} {entry.category} {entry.description}".lower().replace("_", " ")
    if category is not None and entry.category.lower() != category.lower():
        return False
    words = [w.lower().replace("_", " ").replace("-", " ") for w in words]
    if whole:
        tokens = set(re.findall(r"[\w.]+", text))
        return all(set(w.split()) <= tokens for w in words)
    return all(w in text for w in words)


def run(args: argparse.Namespace) -> int:
    from ..errors import MaterialError
    from ..materials import CATEGORIES, closest, materials, sources
    from ._common import dump_json

    if args.category is not None and args.category.lower() not in CATEGORIES:
        raise MaterialError(f"unknown category {args.category!r}; categories: "
                            + ", ".join(CATEGORIES))
    # Whole words first ("pla" is PLA, not "plain" or "platinum"), else any substring.
    chosen = [m for m in materials().values() if _matches(m, args.query, args.category, True)]
    if not chosen:
        chosen = [m for m in materials().values() if _matches(m, args.query, args.category, False)]
    refs = sources()
    used = sorted({m.source for m in chosen})
    if args.json:
        dump_json({
            "units": {"density": "kg/m^3"},
            "materials": [m.as_dict() for m in chosen],
            "sources": {key: refs.get(key, key) for key in used},
        })
        return 0
    if not chosen:  # a search that finds nothing has not failed: say so, exit status 0
        asked = " ".join(args.query) or args.category or ""
        close = closest(asked) if asked else []
        hint = f"try {', '.join(close)}, or " if close else "try "
        print(f"no material matches {asked!r}; {hint}'plumbob materials' for the "
              "whole table")
        return 0
    rows = [(m.name, f"{m.density:g}", m.category, m.description, m.source) for m in chosen]
    header = ("name", "kg/m³", "category", "description", "source")
    widths = [max(len(r[i]) for r in rows + [header]) for i in range(5)]
    lines = ["  ".join(h.ljust(w) if i != 1 else h.rjust(w) for i, (h, w) in
                       enumerate(zip(header, widths))).rstrip()]
    for row in rows:
        lines.append("  ".join(c.rjust(w) if i == 1 else c.ljust(w)
                               for i, (c, w) in enumerate(zip(row, widths))).rstrip())
    lines.append("")
    lines.append("sources:")
    lines.extend(f"  {key}: {refs.get(key, key)}" for key in used)
    print("\n".join(lines))
    return 0
