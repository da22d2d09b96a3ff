"""``python -m plumbob`` and the ``plumbob`` command (its console-script entry point)."""

from __future__ import annotations

import gc
import os
import sys

#: the variables through which the BLAS libraries numpy may be built on read their
#: thread count when they load (OpenMP's, which other libraries share, is left alone)
BLAS_VARIABLES = ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS",
                  "VECLIB_MAXIMUM_THREADS")


def blas_starts_with_one_thread(insist: bool = False) -> bool:
    """Have numpy's BLAS start with one thread, unless the environment names a count
    (``insist``: whatever it names); return whether it will (numpy not loaded yet, no
    other count named), so that the command need not limit it again.

    The command runs BLAS on one thread (:func:`plumbob.blockwise.blas_on_one_thread`:
    its products are thin), but OpenBLAS starts a thread per core when numpy loads, and
    those threads spin before a limit reaches them: ~50 ms of processor time per
    command on 2 cores, more on many, and in every worker of a ``batch`` pool (they
    inherit the variables; ``--threads-per-job`` raises the count through threadpoolctl,
    which OpenBLAS allows). Only the command does this, before numpy loads (``import
    plumbob`` does not load it); a program that imports plumbob keeps its own setting.

    ``plumbob batch`` insists: its workers run BLAS on ``--threads-per-job`` threads
    whatever the environment says, and so does its own process when it measures the
    files itself; and its pool forks the workers from this process only while it runs a
    single thread (:func:`plumbob.batch.pool._context`), which BLAS threads started here
    would spoil.
    """
    if "numpy" in sys.modules:
        return False
    for name in BLAS_VARIABLES:
        if insist:
            os.environ[name] = "1"
        else:
            os.environ.setdefault(name, "1")
    return all(os.environ[name] == "1" for name in BLAS_VARIABLES)


#: glibc's mallopt parameters: M_TRIM_THRESHOLD, M_TOP_PAD, M_MMAP_THRESHOLD
_TRIM, _TOP_PAD, _MMAP = -1, -2, -3


def malloc_keeps_freed_memory() -> bool:
    """Have glibc's malloc serve large blocks from its heap and keep what is freed
    (Linux with glibc; elsewhere nothing); whether it was done.

    A command allocates and frees arrays of megabytes over and over (the hull's and the
    landscape's temporaries); by default each comes fresh from the kernel (mmap above
    128 kB) and goes back when freed, so every one is paid again in page faults:
    0.31 s of system time in a 1.5 s ``plumbob poses`` of a 200k-triangle egg. Kept in
    the heap (blocks up to 256 MB, freed memory given back only past 512 MB, the heap
    grown 64 MB at a time), the next array reuses pages already mapped: 0.10 s of system
    time there, a tenth or more of the run's processor time saved, its peak memory up
    by 0.5–8 MB on the 100k–200k meshes measured. Only the command does this; a
    program that imports plumbob keeps its own allocator's settings.
    """
    if not sys.platform.startswith("linux"):
        return False
    import ctypes

    try:
        mallopt = ctypes.CDLL(None).mallopt  # the process's own C library
    except (AttributeError, OSError):  # not glibc (musl has no mallopt)
        return False
    mallopt.argtypes, mallopt.restype = (ctypes.c_int, ctypes.c_int), ctypes.c_int
    return all(mallopt(parameter, value) == 1 for parameter, value in
               ((_MMAP, 256 << 20), (_TRIM, 512 << 20), (_TOP_PAD, 64 << 20)))


#: containers made (less those freed) between two collections of the youngest generation
#: while a command runs (Python's default: 700)
YOUNG_OBJECTS = 20_000


def entry() -> int:
    """Run the command line, its start-up and its exit not slowed by the cyclic garbage
    collector.

    Loading numpy and plumbob makes some 10⁵ objects that all stay alive, so the
    collections their allocation triggers (~5 ms of a ~0.13 s ``plumbob poses``) find
    nothing to free. The collector is paused while :mod:`plumbob.cli` loads, then what
    is loaded is frozen (never scanned again) and the collector resumes before the
    command runs: long runs (``plumbob batch``) collect their cycles as usual, the
    youngest generation once :data:`YOUNG_OBJECTS` containers have been made rather than
    Python's 700 (``plumbob poses`` of tiny.stl or a 100k-triangle mesh, the modules it
    loads as it runs and its small objects: 17 collections in all, 2.4–3.4 ms of processor
    time, at 700; 8, 1.3–1.6 ms, at 20 000). When the
    command has returned, what is alive (the modules it loaded, some 3·10⁴ objects) is
    frozen too: the interpreter's exit, which frees it all, then does not scan it first
    (the exit of a 100k-triangle ``plumbob poses``: 10.6 -> 8.2 ms of processor time).
    """
    one_thread = blas_starts_with_one_thread(insist=sys.argv[1:2] == ["batch"])
    malloc_keeps_freed_memory()
    gc.disable()
    try:
        from .cli import main
    finally:
        gc.freeze()
        gc.set_threshold(YOUNG_OBJECTS, *gc.get_threshold()[1:])
        gc.enable()
    status = main(blas_on_one_thread=one_thread)
    gc.freeze()
    return status


if __name__ == "__main__":
    sys.exit(entry())
