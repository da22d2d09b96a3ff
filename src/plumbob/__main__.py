"""``python -m plumbob`` and the ``plumbob`` command (its console-script entry point)."""

from __future__ import annotations

import gc
import sys


def entry() -> int:
    """Run the command line, its start-up not slowed by the cyclic garbage collector.

    Loading numpy and plumbob makes some 10⁵ objects that all stay alive, so the
    collections their allocation triggers (~5 ms of a ~0.13 s ``plumbob poses``) find
    nothing to free. The collector is paused while :mod:`plumbob.cli` loads, then what
    is loaded is frozen (never scanned again) and the collector resumes before the
    command runs: long runs (``plumbob batch``) collect their cycles as usual.
    """
    gc.disable()
    try:
        from .cli import main
    finally:
        gc.freeze()
        gc.enable()
    return main()


if __name__ == "__main__":
    sys.exit(entry())
