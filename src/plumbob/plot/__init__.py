"""Pictures of bodies and results: matplotlib figures, and a self-contained HTML report.

Imported only when a picture is asked for (``--plot``, ``plumbob report``, ``.plot()``):
the names below load their modules, and matplotlib, on first use, so ``plumbob.plot``
itself is cheap to import (the commands import its argument helper).

The drawing functions follow scipy.spatial's plotting helpers: ``ax=None`` makes a new
figure, and the figure is returned.
"""

from __future__ import annotations

from ..lazy import lazy_exports

__all__ = ["plot_body", "plot_check", "tilt_rose", "plot_poses", "plot_lift", "save_figure",
           "report_page", "png_bytes"]

_LAZY = {
    "plot_body": ".body",
    "plot_check": ".check",
    "tilt_rose": ".rose",
    "plot_poses": ".gallery",
    "plot_lift": ".lift",
    "save_figure": ".files",
    "png_bytes": ".files",
    "report_page": ".html",
}

__getattr__, __dir__ = lazy_exports(__name__, _LAZY, __all__)
