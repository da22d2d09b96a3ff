"""``python -m plumbob`` and the ``plumbob`` command (its console-script entry point)."""

from __future__ import annotations

import gc
import os
import sys

#: the variables through which the BLAS libraries numpy may be built on read their
#: thread count when they load (OpenMP's, which other libraries share, is left alone)
BLAS_VARIABLES = ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS",
                  "VECLIB_MAXIMUM_THREADS")


def blas_starts_with_one_thread() -> bool:
    """Have numpy's BLAS start with one thread, unless the environment names a count;
    return whether it will (numpy not loaded yet, no other count named), so that the
    command need not limit it again.

    The command runs BLAS on one thread (:func:`plumbob.blockwise.blas_on_one_thread`:
    its products are thin), but OpenBLAS starts a thread per core when numpy loads, and
    those threads spin before a limit reaches them: ~50 ms of processor time per
    command on 2 cores, more on many, and in every worker of a ``batch`` pool (they
    inherit the variables; ``--threads-per-job`` raises the count through threadpoolctl,
    which OpenBLAS allows). Only the command does this, before numpy loads (``import
    plumbob`` does not load it); a program that imports plumbob keeps its own setting.
    """
    if "numpy" in sys.modules:
        return False
    for name in BLAS_VARIABLES:
        os.environ.setdefault(name, "1")
    return all(os.environ[name] == "1" for name in BLAS_VARIABLES)


def entry() -> int:
    """Run the command line, its start-up not slowed by the cyclic garbage collector.

    Loading numpy and plumbob makes some 10⁵ objects that all stay alive, so the
    collections their allocation triggers (~5 ms of a ~0.13 s ``plumbob poses``) find
    nothing to free. The collector is paused while :mod:`plumbob.cli` loads, then what
    is loaded is frozen (never scanned again) and the collector resumes before the
    command runs: long runs (``plumbob batch``) collect their cycles as usual.
    """
    one_thread = blas_starts_with_one_thread()
    gc.disable()
    try:
        from .cli import main
    finally:
        gc.freeze()
        gc.enable()
    return main(blas_on_one_thread=one_thread)


if __name__ == "__main__":
    sys.exit(entry())
