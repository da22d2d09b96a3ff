"""Row-wise array work done block by block, on the machine's cores.

A chain of numpy operations over a hull's 3·10⁵ edges makes temporaries of megabytes
each: every one is fresh memory the process must fault in and stream through the
caches (on this project's virtual machines, memory the host has reclaimed costs about
1 ms per MB to touch again). Done :data:`BLOCK_ROWS` rows at a time the temporaries
stay small and are reused, and only the results are full size. numpy releases the GIL
inside its loops, so the blocks also run in threads: :func:`blockwise` splits them
over :func:`workers` threads.

The answers are the same, bit for bit, whatever the blocks and threads, because the
work is row-wise: a row's results depend on that row's inputs only (no sums across
rows).

``PLUMBOB_THREADS`` (an integer ≥ 1) sets the number of threads; by default it is the
number of cores the process may use. Processes that already run side by side (a batch's
workers, the drops' workers) call :func:`limit_threads` ``(1)``: plumbob's blocks,
every BLAS/OpenMP library in the process (through ``threadpoolctl``) and manifold3d's
parallel loops then run on one thread each, whatever the environment asked for — N
workers each starting a thread per core would fight N × cores threads over the cores.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence

import numpy as np

__all__ = ["BLOCK_ROWS", "MIN_THREADED_ROWS", "THREAD_VARIABLES", "blas_on_one_thread",
           "blockwise", "limit_threads", "manifold_on_threads", "set_workers", "workers"]

#: rows per block: a block's (rows, 3) float64 temporaries (384 KB) fit in a core's cache
BLOCK_ROWS = 16_384

#: below this many rows the work runs in the calling thread alone (a thread's start
#: costs about as much as 10⁴ rows of work)
MIN_THREADED_ROWS = 4 * BLOCK_ROWS

_MAX_WORKERS = 8  # beyond this, row-wise numpy work is bound by memory, not cores
_workers: int | None = None


def _default_workers() -> int:
    text = os.environ.get("PLUMBOB_THREADS", "").strip()
    if text:
        try:
            return max(1, min(int(text), _MAX_WORKERS))
        except ValueError:
            pass  # not a number: the default (an environment variable is no place to fail)
    try:
        cores = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        cores = os.cpu_count() or 1
    return max(1, min(cores, _MAX_WORKERS))


def workers() -> int:
    """How many threads :func:`blockwise` uses (``PLUMBOB_THREADS``, else the cores)."""
    global _workers
    if _workers is None:
        _workers = _default_workers()
    return _workers


def set_workers(count: int | None) -> None:
    """Use ``count`` threads from now on (None: back to the default)."""
    global _workers
    _workers = None if count is None else max(1, min(int(count), _MAX_WORKERS))


#: the environment variables through which BLAS and OpenMP libraries read their thread
#: count when they are loaded
THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS",
                    "BLIS_NUM_THREADS", "VECLIB_MAXIMUM_THREADS", "NUMEXPR_NUM_THREADS")


def blas_on_one_thread() -> None:
    """Run the BLAS libraries in this process on one thread from now on (through
    ``threadpoolctl``), leaving plumbob's own blocks (:func:`workers`) as they are.

    For a command: plumbob's matrix products are thin (n × 3 by 3 × k: points by a
    frame, by normals, by a few directions), where a BLAS library's threads have too
    little to do and spin while they wait for it, costing cores the row-wise work and
    other processes could use. ``plumbob poses`` on a 200k-triangle egg took 1.9 s of
    processor time with OpenBLAS's default threads and 1.4 s on one, and was no slower
    by the clock (2026-11-27, this project's 2-core machine)."""
    import threadpoolctl

    threadpoolctl.threadpool_limits(limits=1, user_api="blas")


def limit_threads(count: int) -> None:
    """Run this process on ``count`` threads from now on: plumbob's blocks, and every BLAS
    and OpenMP library, those loaded already (``threadpoolctl``) and those loaded later
    (their environment variables). For a worker process, whose cores are shared with
    its siblings; the change lasts for the process's life.
    """
    import threadpoolctl

    count = max(1, int(count))
    for name in THREAD_VARIABLES:
        os.environ[name] = str(count)
    set_workers(count)
    threadpoolctl.threadpool_limits(limits=count)
    manifold_on_threads(count)


def manifold_on_threads(count: int) -> bool:
    """Start manifold3d's parallel scheduler on ``count`` threads; True where it was done.

    manifold3d runs its loops on oneTBB, linked into it, and offers no setting for the
    thread count; threadpoolctl does not reach it. oneTBB fixes its count the first
    time it is used, from the CPUs the calling thread may then run on (its affinity
    mask). So the mask is narrowed to ``count`` of those CPUs for one tiny manifold
    operation, which starts the scheduler, and restored at once: the process still runs
    on any of its CPUs, and manifold's loops on ``count`` threads for its life. Without
    this, each of 16 batch workers on a 16-core machine started 15 more threads that
    spun between loops: ``--jobs 4`` kept 6.6 cores busy and ``--jobs 16`` scaled 7.8×
    over one job (2026-11-27, a 16-core device machine; docs/batch.md).

    Nothing is done (False) where the process may use no more than ``count`` CPUs
    anyway, where the affinity cannot be set (not Linux) or where manifold3d is missing.
    A scheduler already started in this process keeps its count: call this first.
    """
    try:
        allowed = os.sched_getaffinity(0)
    except (AttributeError, OSError):
        return False
    if len(allowed) <= count:
        return False
    try:
        import manifold3d
    except ImportError:
        return False
    try:
        os.sched_setaffinity(0, sorted(allowed)[:count])
    except OSError:
        return False
    try:
        manifold3d.Manifold.cube()  # the scheduler's first use: it reads the mask now
    finally:
        os.sched_setaffinity(0, allowed)
    return True


def blockwise(n: int, work: Callable[[slice], Sequence[np.ndarray]],
              block: int | None = None) -> tuple[np.ndarray, ...]:
    """The results of ``work`` over the rows ``0 .. n-1``, computed block by block.

    ``work(rows)`` returns a sequence of arrays with ``rows``' length first, the same
    shapes and dtypes for every block; the answer is each of them over all rows, as one
    call ``work(slice(0, n))`` would give (``work`` must be row-wise). ``block``: rows
    per block (default :data:`BLOCK_ROWS`). Blocks run in :func:`workers` threads when
    ``n`` is at least :data:`MIN_THREADED_ROWS`, under the caller's numpy error
    settings. An exception in any block is raised here.

    >>> x = np.arange(10.0)
    >>> squares, = blockwise(10, lambda rows: (x[rows] ** 2,), block=4)
    >>> squares.tolist()
    [0.0, 1.0, 4.0, 9.0, 16.0, 25.0, 36.0, 49.0, 64.0, 81.0]
    """
    block = BLOCK_ROWS if block is None else max(1, int(block))
    if n <= 0:
        first = work(slice(0, 0))
        return tuple(np.asarray(a) for a in first)
    starts = list(range(0, n, block))
    first = [np.asarray(a) for a in work(slice(0, min(block, n)))]
    if len(starts) == 1:
        return tuple(first)
    out = tuple(np.empty((n, *a.shape[1:]), dtype=a.dtype) for a in first)
    for o, a in zip(out, first):
        o[: len(a)] = a
    del first
    rest = starts[1:]
    threads = min(workers(), len(rest)) if n >= MIN_THREADED_ROWS else 1
    errors: list[BaseException] = []
    settings = np.geterr()

    def run(share: list[int]) -> None:
        try:
            with np.errstate(**settings):  # numpy's error settings are per thread
                for start in share:
                    rows = slice(start, min(start + block, n))
                    for o, a in zip(out, work(rows)):
                        o[rows] = a
        except BaseException as exc:  # noqa: BLE001 - handed to the caller below
            errors.append(exc)

    shares = [rest[k::threads] for k in range(threads)]
    helpers = []
    if threads > 1:  # loaded only here: a command on a small mesh starts no thread (~0.9 ms)
        import threading

        helpers = [threading.Thread(target=run, args=(share,), daemon=True)
                   for share in shares[1:]]
    for thread in helpers:
        thread.start()
    run(shares[0])
    for thread in helpers:
        thread.join()
    if errors:
        raise errors[0]
    return out
