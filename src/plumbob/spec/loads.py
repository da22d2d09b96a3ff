"""A shape spec's ``[[load]]`` tables: the forces and hung masses it is checked under.

Each table is one load: ``force = [FX, FY, FZ]`` (N) or ``mass = M`` (kg, hung along
gravity) at ``at = [X, Y, Z]`` (in the spec's length unit), or ``push = F`` / ``press = F``
(N: a horizontal force in the worst direction / a downward force, at the worst point
no higher than ``max_height``); optional ``name``. A lamina's loads have 2 numbers.
"""

from __future__ import annotations

from typing import Any

from ..errors import PlumbobError
from ..loads import Extendable, Force, Hang, Press, Push
from .values import SpecContext, shown

__all__ = ["LOAD_KEYS", "EXTENDABLE_KEYS", "read_loads", "read_extendables"]

EXTENDABLE_KEYS = {"part", "with", "travel", "volume"}

LOAD_KEYS = {"force", "mass", "push", "press", "at", "max_height", "name"}
_KINDS = ("force", "mass", "push", "press")


def read_loads(spec: SpecContext, tables: Any, dim: int) -> tuple:
    """The loads of the ``[[load]]`` tables, for a body of ``dim`` dimensions."""
    if not isinstance(tables, list):
        raise spec.error("load", f"expected [[load]] tables, not {shown(tables)}")
    loads = []
    for i, table in enumerate(tables, 1):
        where = f"load[{i}]"
        spec.table(table, LOAD_KEYS, where)
        kinds = [k for k in _KINDS if k in table]
        if len(kinds) != 1:
            given = " and ".join(kinds) if kinds else "none of them"
            raise spec.error(where, "a load is one of force = [..], mass = .., push = .. or "
                             f"press = .., not {given}")
        kind = kinds[0]
        name = spec.text(table["name"], f"{where}.name") if "name" in table else None
        try:
            loads.append(_load(spec, table, kind, where, name, dim))
        except PlumbobError as error:
            if getattr(error, "path", None):
                raise
            raise spec.error(where, str(error)) from None
    return tuple(loads)


def _load(spec: SpecContext, table: dict, kind: str, where: str, name: str | None, dim: int):
    if kind in ("push", "press"):
        if "at" in table:
            raise spec.error(f"{where}.at", f"a {kind} finds its own worst point: give "
                             "max_height, not at")
        height = (spec.number(table["max_height"], f"{where}.max_height", length=True)
                  if "max_height" in table else None)
        force = spec.number(table[kind], f"{where}.{kind}")
        return (Push if kind == "push" else Press)(force, height, name)
    if "max_height" in table:
        raise spec.error(f"{where}.max_height", "max_height goes with push or press")
    if "at" not in table:
        raise spec.error(where, f"a {kind} load needs at = [X, Y{', Z' if dim == 3 else ''}]: "
                         "the point it acts at")
    like = "the body (a lamina: 2 numbers)" if dim == 2 else "the body (a solid: 3 numbers)"
    at = spec.vector(table["at"], f"{where}.at", (dim,), like=like)
    if kind == "mass":
        mass = spec.number(table["mass"], f"{where}.mass")
        if mass < 0:
            raise spec.error(f"{where}.mass", f"a hung mass must be ≥ 0 kg, not {mass:g}")
        return Hang(mass, at, name)
    force = spec.vector(table["force"], f"{where}.force", (dim,), length=False, like=like)
    return Force(force, at, name)


def read_extendables(spec: SpecContext, tables: Any, dim: int) -> tuple:
    """The ``[[extendable]]`` tables: ``part`` (a part's name), ``travel`` (its opening to
    its stop, in the spec's unit), ``volume`` (its storage volume, in the spec's unit
    cubed) and optional ``with`` (the names of parts it carries)."""
    if not isinstance(tables, list):
        raise spec.error("extendable", f"expected [[extendable]] tables, not {shown(tables)}")
    found = []
    for i, table in enumerate(tables, 1):
        where = f"extendable[{i}]"
        spec.table(table, EXTENDABLE_KEYS, where)
        for key in ("part", "travel", "volume"):
            if key not in table:
                raise spec.error(where, f"an extendable needs {key}")
        name = spec.text(table["part"], f"{where}.part")
        carried = table.get("with", [])
        if not isinstance(carried, list):
            raise spec.error(f"{where}.with", f"expected a list of part names, not {shown(carried)}")
        carried = [spec.text(c, f"{where}.with") for c in carried]
        travel = spec.vector(table["travel"], f"{where}.travel", (dim,))
        volume = spec.number(table["volume"], f"{where}.volume") * spec.scale ** 3
        if volume < 0:
            raise spec.error(f"{where}.volume", f"a storage volume must be ≥ 0, not {volume:g}")
        found.append(Extendable(name, (name, *carried), travel, volume))
    return tuple(found)
