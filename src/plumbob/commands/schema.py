"""The JSON the commands print, described once: which result's ``KEYS`` each key table of
``docs/cli.md`` shows.

Every result declares its keys beside itself (:class:`plumbob.results.Key`); this module
only names them for the docs. ``python -m plumbob.commands.schema [docs/cli.md]``
rewrites the tables between ``<!-- keys: NAME -->`` and ``<!-- /keys -->`` from them, and
``tests/test_result_keys.py`` fails while a table differs.
"""

from __future__ import annotations

import re
import sys
from importlib import import_module
from pathlib import Path

__all__ = ["DOCUMENTED", "result_class", "documented_keys", "regenerate"]

#: the results docs/cli.md shows a key table of, by the name in its marker: their module
DOCUMENTED = {
    "MassReport": "plumbob.commands.mass_report",
    "Verdict": "plumbob.stability.verdict",
    "TippingEdge": "plumbob.stability.verdict",
    "SlopeCheck": "plumbob.stability.checks",
    "Settling": "plumbob.stability.poses.settling",
    "LoadVerdict": "plumbob.stability.loaded",
    "LoadMoment": "plumbob.stability.loaded",
    "StandardResult": "plumbob.stability.standards",
    "StandardTest": "plumbob.stability.standards",
    "ParameterSolution": "plumbob.balance.solve",
    "BalanceResult": "plumbob.balance.result",
    "LoadedBalance": "plumbob.balance.loaded",
    "WrittenHollow": "plumbob.balance.hollow",
    "HollowBound": "plumbob.balance.hollow",
    "Poses": "plumbob.stability.poses.result",
    "Pose": "plumbob.stability.poses.result",
    "Drops": "plumbob.stability.drops.result",
    "DropPose": "plumbob.stability.drops.result",
    "LiftEnergy": "plumbob.energy",
    "CrewTime": "plumbob.energy",
    "SimulationResult": "plumbob.dynamics.motion",
    "CollisionResult": "plumbob.dynamics.collisions",
    "Material": "plumbob.materials",
}

#: a table between its markers (none inside: an empty block is filled, never overrun)
_BLOCK = re.compile(r"(<!-- keys: (\w+) -->\n)((?:(?!<!-- ).)*?)\n?(<!-- /keys -->)", re.S)


def result_class(name: str) -> type:
    """The result class docs/cli.md's table ``name`` shows."""
    return getattr(import_module(DOCUMENTED[name]), name)


def documented_keys(name: str) -> str:
    """The Markdown key table of the result ``name`` (:func:`plumbob.results.key_table`)."""
    from ..results import key_table

    return key_table(result_class(name).KEYS)


def regenerate(text: str) -> str:
    """``text`` (docs/cli.md) with every key table made again from its result's ``KEYS``."""
    return _BLOCK.sub(lambda m: m[1] + documented_keys(m[2]) + "\n" + m[4], text)


def main(argv: list[str] | None = None) -> int:
    """Rewrite the key tables of the file named (default docs/cli.md) in place."""
    args = sys.argv[1:] if argv is None else argv
    path = Path(args[0] if args else "docs/cli.md")
    text = path.read_text(encoding="utf-8")
    new = regenerate(text)
    if new != text:
        path.write_text(new, encoding="utf-8")
    print(f"{path}: {'rewritten' if new != text else 'unchanged'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
