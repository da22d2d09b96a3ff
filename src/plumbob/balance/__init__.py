"""Make it stand: what to change so a body meets a stability target.

* :func:`target_for` — a target (margin, tilt) as linear conditions on the centre
  of mass (:class:`Target`);
* :func:`ballast` — the least added mass, and where, that meets it.

Built on :mod:`plumbob.stability`; scipy loads only when a function needs it.
"""

from .targets import Target, target_for

__all__ = ["Target", "target_for"]
