"""The material table: densities of common materials with their sources.

The data lives in ``data/materials.toml`` beside this module: a ``[sources]``
table of citations and one ``[materials.NAME]`` entry per material with its
density (kg/m³), category, a one-line description and a source key. Names are
looked up ignoring case, spaces and hyphens; a few common spellings are aliases.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

from .arguments import check_density
from .errors import MaterialError
from .results import Key, Result

# tomllib, importlib.resources and difflib load when the table is first read. check_density
# (re-exported here) is arguments.py's: every body checks its density, and reading a mesh
# loads neither the table nor this module.

__all__ = ["Material", "materials", "material", "density_of", "sources", "resolve_density",
           "check_density", "closest", "ALIASES", "CATEGORIES"]

CATEGORIES = ("concrete", "masonry", "stone", "glass", "metal", "wood", "wood product",
              "plastic", "filament", "liquid", "other")

ALIASES = {
    "aluminum": "aluminium",
    "aluminum_6061": "aluminium_6061",
    "aluminum_7075": "aluminium_7075",
    "stainless": "stainless_steel",
    "iron": "cast_iron",
    "sea_water": "seawater",
    "fresh_water": "water",
    "pmma": "acrylic",
    "plexiglass": "acrylic",
    "perspex": "acrylic",
    "pc": "polycarbonate",
    "pp": "polypropylene",
    "ps": "polystyrene",
    "pom": "acetal",
    "teflon": "ptfe",
    "pa6": "nylon",
    "pa": "nylon",
    "white_oak": "oak",
    "sugar_maple": "maple",
    "hard_maple": "maple",
    "chipboard": "particleboard",
    "concrete_reinforced": "reinforced_concrete",
    "mortar": "cement_mortar",
}


@dataclass(frozen=True)
class Material(Result):
    """A named material.

    name: the table's key. density: kg/m³. description: one line.
    source: a key of :func:`sources`. category: one of :data:`CATEGORIES`.
    """

    name: str
    density: float
    description: str
    source: str
    category: str = "other"

    #: the keys of each of ``plumbob materials --json``'s ``materials``
    KEYS = (
        Key("name", "", "the table's key, as `--material` takes it", type="str"),
        Key("density", "kg/m³", "its density", type="float"),
        Key("category", "", "one of the table's categories", type="str"),
        Key("description", "", "one line", type="str"),
        Key("source", "", "a key of the references (`sources`)", type="str"),
    )

    @property
    def reference(self) -> str:
        """The full citation of :attr:`source`."""
        return sources().get(self.source, self.source)


def _normalise(name: str) -> str:
    return "_".join(name.strip().lower().replace("-", " ").replace("_", " ").split())


@lru_cache(maxsize=1)
def _table() -> tuple[dict[str, Material], dict[str, str]]:
    import sys
    from importlib import resources

    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover
        import tomli as tomllib

    text = resources.files(__package__).joinpath("data/materials.toml").read_text(encoding="utf-8")
    data = tomllib.loads(text)
    refs = {str(k): str(v) for k, v in data.get("sources", {}).items()}
    table = {
        name: Material(name, float(entry["density"]), entry["description"], entry["source"],
                       entry.get("category", "other"))
        for name, entry in data["materials"].items()
    }
    return table, refs


def materials() -> dict[str, Material]:
    """Every material in the table, by name (in the table's order).

    >>> materials()["water"].density
    998.2
    """
    return dict(_table()[0])


def sources() -> dict[str, str]:
    """Citations of the table's sources, by key.

    >>> "Eurocode" in sources()["EN1991"]
    True
    """
    return dict(_table()[1])


def material(name: str) -> Material:
    """The material called ``name`` (case, spaces and hyphens ignored).

    Parameters
    ----------
    name : str
        A name from ``plumbob materials`` (``"concrete"``, ``"stainless steel"``, …).

    Returns
    -------
    Material
        Its density (kg/m³), description, category and source.

    Raises
    ------
    MaterialError
        An unknown name; the message suggests the closest one.

    Examples
    --------
    >>> material("Concrete").density
    2400.0
    >>> material("stainless steel").name, material("Aluminum").name
    ('stainless_steel', 'aluminium')
    >>> material("granit")
    Traceback (most recent call last):
    ...
    plumbob.errors.MaterialError: unknown material 'granit'; did you mean granite?
    """
    if not isinstance(name, str):
        raise MaterialError(f"a material name must be text, not {name!r}")
    table = _table()[0]
    key = _normalise(name)
    if key in table:
        return table[key]
    if key in ALIASES:
        return table[ALIASES[key]]
    close = closest(name)
    hint = f"; did you mean {', '.join(close)}?" if close else "; 'plumbob materials' lists them"
    raise MaterialError(f"unknown material {name!r}{hint}")


def density_of(name: str) -> float:
    """Density of the named material, kg/m³.

    >>> density_of("steel")
    7850.0
    """
    return material(name).density


def resolve_density(value: float | int | str) -> float:
    """A density in kg/m³ from a number, a number written as text, or a material name.

    >>> resolve_density(1000), resolve_density("2.5e3"), resolve_density("water")
    (1000.0, 2500.0, 998.2)
    """

    if isinstance(value, bool):
        raise MaterialError(f"a density must be a number or a material name, not {value!r}")
    if isinstance(value, (int, float)):
        return check_density(value)  # type: ignore[return-value]
    try:
        number = float(value)
    except (TypeError, ValueError):
        return density_of(value)
    return check_density(number)  # type: ignore[return-value]

def closest(word: str, n: int = 3) -> list[str]:
    """The names in the table (aliases resolved) closest to ``word``, best first: the
    suggestion after a mistyped name or a search that matched nothing.

    >>> closest("granit")
    ['granite']
    """
    import difflib

    table = _table()[0]
    close = difflib.get_close_matches(_normalise(word), list(table) + list(ALIASES), n=n)
    return list(dict.fromkeys(ALIASES.get(c, c) for c in close))
