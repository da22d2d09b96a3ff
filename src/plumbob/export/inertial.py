"""Inertial blocks for robot simulators: URDF, SDF and MuJoCo's MJCF.

A wrong frame or sign convention in a hand-copied ``<inertial>`` silently corrupts a
simulation, so each block is written from :class:`~plumbob.massprops.MassProperties`
in the convention its format documents:

* **URDF** ``<inertial>``: ``<origin xyz>`` at the centre of mass with ``rpy="0 0 0"``
  (the inertia frame parallel to the link frame), ``<mass value>`` in kg and
  ``<inertia ixx ixy ixz iyy iyz izz>`` in kg·m², the upper triangle of the inertia
  *tensor* about the centre of mass (off-diagonals are −∫xy dm, as in plumbob).
* **SDF** ``<inertial>``: the same numbers as ``<pose>x y z 0 0 0</pose>``,
  ``<mass>`` and ``<inertia><ixx>…</inertia>`` elements.
* **MJCF** ``<inertial pos mass fullinertia>``: ``fullinertia`` is
  ``"ixx iyy izz ixy ixz iyz"`` (diagonal first), the tensor about ``pos``.

All three take SI units (m, kg, kg·m²), so the numbers are plumbob's own, written with
every digit (Python's shortest round-trip form) so a parser reads back the same floats.
A lamina lies in z = 0: its centre gets z = 0.
"""

from __future__ import annotations

import numpy as np

from ..massprops import MassProperties

__all__ = ["FORMATS", "inertial_xml"]

#: the formats :func:`inertial_xml` writes
FORMATS = ("urdf", "sdf", "mjcf")


def _num(value: float) -> str:
    """Every digit of ``value`` and no negative zero: ``repr`` of a float round-trips."""
    return repr(float(value) + 0.0)


def _nums(values) -> str:
    return " ".join(_num(v) for v in values)


def inertial_xml(props: MassProperties, fmt: str) -> str:
    """The inertial block of ``props`` in format ``fmt`` (``urdf``, ``sdf`` or ``mjcf``).

    >>> from plumbob.bodies.primitives import box
    >>> print(inertial_xml(box(1, 1, 1, density=12.0).mass_properties(), "mjcf"))
    <inertial pos="0.5 0.5 0.5" mass="12.0" fullinertia="2.0 2.0 2.0 0.0 0.0 0.0"/>
    """
    com = np.zeros(3)
    com[: len(props.center_of_mass)] = props.center_of_mass
    i = np.asarray(props.inertia, dtype=float)
    upper = (i[0, 0], i[0, 1], i[0, 2], i[1, 1], i[1, 2], i[2, 2])
    names = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
    if fmt == "urdf":
        inertia = " ".join(f'{n}="{_num(v)}"' for n, v in zip(names, upper))
        return (f'<inertial>\n  <origin xyz="{_nums(com)}" rpy="0 0 0"/>\n'
                f'  <mass value="{_num(props.mass)}"/>\n  <inertia {inertia}/>\n</inertial>')
    if fmt == "sdf":
        inertia = "".join(f"\n    <{n}>{_num(v)}</{n}>" for n, v in zip(names, upper))
        return (f"<inertial>\n  <pose>{_nums(com)} 0 0 0</pose>\n  <mass>{_num(props.mass)}</mass>"
                f"\n  <inertia>{inertia}\n  </inertia>\n</inertial>")
    if fmt == "mjcf":
        full = (i[0, 0], i[1, 1], i[2, 2], i[0, 1], i[0, 2], i[1, 2])
        return (f'<inertial pos="{_nums(com)}" mass="{_num(props.mass)}" '
                f'fullinertia="{_nums(full)}"/>')
    raise ValueError(f"unknown inertial format {fmt!r}; use one of {', '.join(FORMATS)}")
