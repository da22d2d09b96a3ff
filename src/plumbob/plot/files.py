"""Pictures to files: the ``--plot FILE`` argument, and atomic writes by extension.

This module imports no plotting library at load time: the commands import its
argument helper on every run, and matplotlib loads only when a picture is drawn.
A picture is written by :func:`plumbob.files.write_atomic`, so an interrupted or
failed run never leaves a partial file.
"""

from __future__ import annotations

import argparse
import io
import os
from importlib import import_module

from ..errors import PlumbobError
from ..files import write_atomic

__all__ = ["FORMATS", "plot_path", "add_plot_argument", "save_figure", "png_bytes",
           "write_plot"]

FORMATS = {".png": "png", ".svg": "svg", ".pdf": "pdf"}
_DRAW = {"mass": ("body", "plot_body"), "check": ("check", "plot_check"),
         "poses": ("gallery", "plot_poses"), "lift": ("lift", "plot_lift")}


def plot_path(text: str) -> str:
    """An argparse type: a file name ending in .png, .svg or .pdf."""
    if os.path.splitext(text)[1].lower() not in FORMATS:
        raise argparse.ArgumentTypeError(
            f"a picture is written as PNG, SVG or PDF by its extension, not {text!r}")
    return text


def add_plot_argument(parser: argparse.ArgumentParser) -> None:
    """``--plot FILE``."""
    parser.add_argument("--plot", type=plot_path, metavar="FILE",
                        help="also draw the result to FILE (.png, .svg or .pdf)")


def save_figure(fig, path: str, dpi: int = 150) -> None:
    """Save ``fig`` to ``path`` as PNG, SVG or PDF by its extension, atomically."""
    fmt = FORMATS.get(os.path.splitext(path)[1].lower())
    if fmt is None:
        raise PlumbobError(f"a picture is written as PNG, SVG or PDF by its extension, not {path!r}")
    write_atomic(path, writer=lambda handle: fig.savefig(handle, format=fmt, dpi=dpi))


def png_bytes(fig, dpi: int = 100) -> bytes:
    """The figure as PNG bytes (for notebooks and the HTML report); the figure is closed."""
    import matplotlib.pyplot as plt

    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=dpi)
    plt.close(fig)
    return buffer.getvalue()


def write_plot(target: str, command: str, *objects, **options) -> None:
    """Draw the picture of ``command`` (``mass``, ``check``, ``poses`` or ``lift``) from the
    command's results and write it to ``target``: the CLI's one call into this room."""
    import matplotlib

    matplotlib.use("Agg")  # no window, whatever the environment offers
    import matplotlib.pyplot as plt

    module, name = _DRAW[command]
    fig = getattr(import_module(f".{module}", __package__), name)(*objects, **options)
    try:
        save_figure(fig, target)
    finally:
        plt.close(fig)
