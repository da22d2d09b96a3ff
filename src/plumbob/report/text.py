"""``str(result)``: the text report a result's command prints, found for any result."""

from __future__ import annotations

__all__ = ["text_of"]


def text_of(result, units=None) -> str:
    """``str(result)``: the report its command prints — the result's own ``text(units)``
    (a verdict, poses, a lift), the table of ``plumbob mass`` for mass properties
    (:func:`plumbob.report.mass.props_text`), else its repr; ``units`` as
    :func:`units_for` takes them.

    >>> from plumbob.massprops import point_mass
    >>> print(text_of(point_mass(2.0, [0.0, 0.0, 1.0]), "g").splitlines()[3])
    mass                    2000 g
    """
    text = getattr(result, "text", None)
    if callable(text):
        return text(units)
    if type(result).__name__ == "MassProperties":  # its room is above this one: by name
        from .mass import props_text

        return props_text(result, units)
    return repr(result)
