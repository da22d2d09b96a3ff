"""The material table: densities of common materials with their sources.

The data lives in ``data/materials.toml`` beside this module; each entry has a
density in kg/m³, a description and a source key explained in the file's
header.
"""

from __future__ import annotations

import difflib
import sys
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

from .errors import MaterialError

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["Material", "materials", "material", "density_of"]


@dataclass(frozen=True)
class Material:
    """A named material. density: kg/m³."""

    name: str
    density: float
    description: str
    source: str


def _normalise(name: str) -> str:
    return name.strip().lower().replace("-", "_").replace(" ", "_")


@lru_cache(maxsize=1)
def materials() -> dict[str, Material]:
    """Every material in the table, by name."""
    text = resources.files(__package__).joinpath("data/materials.toml").read_text(encoding="utf-8")
    table = tomllib.loads(text)["materials"]
    return {name: Material(name, float(entry["density"]), entry["description"], entry["source"])
            for name, entry in table.items()}


def material(name: str) -> Material:
    """The material called ``name`` (case, spaces and hyphens ignored).

    >>> material("Concrete").density
    2400.0
    """
    table = materials()
    key = _normalise(name)
    if key in table:
        return table[key]
    aliases = {"aluminum": "aluminium", "stainless": "stainless_steel", "iron": "cast_iron"}
    if key in aliases:
        return table[aliases[key]]
    close = difflib.get_close_matches(key, table, n=3)
    hint = f"; did you mean {', '.join(close)}?" if close else "; 'plumbob materials' lists them"
    raise MaterialError(f"unknown material {name!r}{hint}")


def density_of(name: str) -> float:
    """Density of the named material, kg/m³."""
    return material(name).density
