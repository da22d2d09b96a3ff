"""TOML specs: shapes (bodies, ``docs/shapes.md``) and simulations (particles in
motion, ``docs/simulate.md``), read by one reader (:mod:`.loader`) that chooses by
the spec's ``kind``.

* :mod:`.loader` — the files and the kinds: :func:`load_spec`, :func:`load_simulation`;
* :mod:`.values` — numbers, expressions, points, checked tables, ``[parameters]``;
* :mod:`.parts` — ``[[part]]`` tables into bodies;
* :mod:`.particles` — the one ``[[particle]]`` schema;
* :mod:`.simulation` — springs, rods, strings, gravity, friction, solver options.
"""

from .loader import build_spec, load_simulation, load_spec, parse_simulation
from .simulation import SimulationSpec

__all__ = ["load_spec", "build_spec", "load_simulation", "parse_simulation", "SimulationSpec"]
