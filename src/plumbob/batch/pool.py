"""A process pool that survives its work: a time limit per file, and a worker that dies
(a crash in a C library, memory exhausted) costs one row, never the run.

``concurrent.futures`` cannot stop one running task, so each worker is a process of
its own with a pipe: the parent sends a path, waits on every pipe and every process
at once, and when a file overruns ``--timeout`` kills that worker and starts another.
Only paths go out and small rows come back: meshes are read where they are measured,
never copied between processes. Workers are forked from this process where that is
safe (Linux, and no other thread here that a fork could catch holding a lock: the
command's own process), after it has imported what every worker needs
(:data:`PRELOAD`), so the pool starts in milliseconds; elsewhere they come from a fork
server that has imported the same, at a fork server's start (~0.2 s on this project's
2-core machine), or are spawned.

The workers own their threads: each runs BLAS, OpenMP, manifold3d's loops and plumbob's
own blocks on ``threads`` threads (default 1, ``--threads-per-job``) whatever the
environment says, since ``jobs`` processes already share the cores
(:func:`~plumbob.blockwise.limit_threads`).
One job without a time limit runs in this process, on every core it was given.
"""

from __future__ import annotations

import importlib
import multiprocessing
import os
import signal
import sys
import time
from collections import deque
from collections.abc import Iterator

from ..blockwise import limit_threads, manifold_on_threads, set_workers
from ..blockwise import workers as block_threads
from .options import Options
from .rows import FileResult, lost_row, process_file

__all__ = ["Task", "run_pool", "worker_threads"]

#: (position in the input list, path to read, path to report)
Task = tuple[int, str, str]


def thread_report(imports: tuple[str, ...] = (), manifold_work: bool = False) -> dict:
    """The threads this process runs: plumbob's blocks and each BLAS/OpenMP library's
    (``threadpoolctl.threadpool_info()``), once ``imports`` (module names) are imported;
    with ``manifold_work``, also how many threads the operating system counts in this
    process before and after a manifold3d operation big enough to run its loops in
    parallel (a sphere of 2,048 triangles), which starts its scheduler's threads
    (``os_threads``: [before, after]; None where Linux's /proc is missing)."""
    import importlib

    import threadpoolctl

    for name in imports:
        importlib.import_module(name)
    report = {"plumbob": block_threads(), "libraries": threadpoolctl.threadpool_info()}
    if manifold_work:
        import manifold3d

        tasks = "/proc/self/task"
        before = len(os.listdir(tasks)) if os.path.isdir(tasks) else None
        manifold3d.Manifold.sphere(1.0, 64).volume()
        report["os_threads"] = None if before is None else [before, len(os.listdir(tasks))]
    return report


def _serve(conn, options: Options, threads: int) -> None:
    """A worker's life: measure each path it is sent until told to stop (the message
    ``("threads", imports)`` asks for its :func:`thread_report`)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the parent's to handle
    try:
        limit_threads(threads)  # the pool's processes share the cores already
    except Exception as error:  # noqa: BLE001 - a worker that cannot start says why, once
        conn.send(("failed", f"{type(error).__name__}: {error}"))
        return
    while True:
        try:
            task = conn.recv()
        except (EOFError, OSError):
            return
        if task is None:
            return
        if task[0] == "threads":
            conn.send(thread_report(*task[1:]))
            continue
        index, path, shown = task
        conn.send((index, process_file(path, options, shown)))


#: what every worker imports before its first file (threadpoolctl and manifold3d to
#: limit its threads, the readers and the measures), loaded once where workers fork from
PRELOAD = ("numpy", "threadpoolctl", "manifold3d", "plumbob.loading", "plumbob.batch.rows",
           "plumbob.stability")


def _one_thread() -> bool:
    """Does this process run a single thread, native ones counted (Linux's /proc)?"""
    try:
        return len(os.listdir("/proc/self/task")) == 1
    except OSError:
        return False


def _context():
    """Where the next worker comes from: forked from this process when it runs one
    thread only (once :data:`PRELOAD` is loaded: BLAS may start threads as it loads), so
    that no lock can be caught held by another thread (oneTBB's, OpenBLAS's, a
    program's); else a fork server (a clean process that forks the workers); else spawned.
    Asked again for each worker: a restart may find threads a first start did not."""
    methods = multiprocessing.get_all_start_methods()
    if sys.platform.startswith("linux") and "fork" in methods and _one_thread():
        for name in PRELOAD:
            importlib.import_module(name)
        if _one_thread():
            return multiprocessing.get_context("fork")
    if "forkserver" in methods:
        context = multiprocessing.get_context("forkserver")
        context.set_forkserver_preload(list(PRELOAD))
        return context
    return multiprocessing.get_context("spawn")


class WorkerStartError(RuntimeError):
    """A pool worker could not start (a broken installation, not a bad file): the batch
    stops at once with the worker's reason, rather than restart a worker per file."""


def _answer(message):
    """A worker's message, or :class:`WorkerStartError` when it reports it cannot start."""
    if isinstance(message, tuple) and len(message) == 2 and message[0] == "failed":
        raise WorkerStartError(f"a batch worker process could not start: {message[1]}")
    return message


class _Worker:
    def __init__(self, options: Options, threads: int = 1) -> None:
        context = _context()
        self.conn, child = context.Pipe()
        self.process = context.Process(target=_serve, args=(child, options, threads),
                                       daemon=True)
        self.process.start()
        self.start_method = context.get_start_method()
        child.close()
        self.task: Task | None = None
        self.deadline = float("inf")

    def give(self, task: Task, timeout: float | None) -> None:
        self.task = task
        self.deadline = time.monotonic() + timeout if timeout else float("inf")
        self.conn.send(task)

    def stop(self, kill: bool = False) -> None:
        if not kill:
            try:
                self.conn.send(None)
            except OSError:
                kill = True
            self.process.join(1.0)
        if self.process.is_alive():
            self.process.kill()
            self.process.join()
        self.conn.close()


def worker_threads(threads: int = 1, imports: tuple[str, ...] = (),
                   manifold_work: bool = False) -> dict:
    """The :func:`thread_report` of a live pool worker started with ``threads``, once it
    has imported ``imports``: what BLAS, OpenMP, manifold3d and plumbob run on in a
    batch's workers."""
    worker = _Worker(Options(), threads)
    try:
        worker.conn.send(("threads", tuple(imports), manifold_work))
        return dict(_answer(worker.conn.recv()), start_method=worker.start_method)
    finally:
        worker.stop()


def _in_process(tasks: list[Task], options: Options,
                threads: int | None) -> Iterator[tuple[int, FileResult]]:
    """The files measured in this process: on the cores it was given (``threads`` None),
    or on ``threads`` threads: BLAS's and plumbob's blocks while the files are measured,
    and manifold3d's scheduler for the process's life where it has not started yet
    (oneTBB fixes its count once; :func:`~plumbob.blockwise.manifold_on_threads`).
    Without that last, one job on one thread on 16 cores paid twice a pool worker's CPU
    for each file (49.5 s against 24.1 s for 2,000 small parts, 2026-11-27): manifold's
    15 other threads spinning between its loops."""
    if threads is None:  # the cores this process was given, as the environment says
        for index, path, shown in tasks:
            yield index, process_file(path, options, shown)
        return
    import threadpoolctl

    manifold_on_threads(threads)
    before = block_threads()
    try:
        with threadpoolctl.threadpool_limits(limits=threads):
            set_workers(threads)
            for index, path, shown in tasks:
                yield index, process_file(path, options, shown)
    finally:
        set_workers(before)


def run_pool(tasks: list[Task], options: Options, jobs: int,
             threads: int | None = None) -> Iterator[tuple[int, FileResult]]:
    """(index, result) for every task, as they finish, on ``jobs`` processes of
    ``threads`` threads each (None: one each; in this process, its own cores).

    With one job and no time limit the files are measured in this process (nothing to
    stop, nothing to gain from a second process). Otherwise the workers start here, at
    the call, before the caller starts any thread of its own, so that they can fork
    from it (:func:`_context`); iterate the result to its end, or close it, to stop them.
    """
    if jobs <= 1 and options.timeout is None:
        return _in_process(tasks, options, threads)
    threads = threads or 1
    if jobs > 1:
        tasks = largest_first(tasks)
    workers: list[_Worker] = []
    try:
        for _ in range(min(jobs, len(tasks))):
            workers.append(_Worker(options, threads))
    except BaseException:
        for w in workers:
            w.stop(kill=True)
        raise
    return _results(workers, deque(tasks), options, threads)


def largest_first(tasks: list[Task]) -> list[Task]:
    """The tasks, their largest files first (input order among equals; a file that
    cannot be read, last: its row is an error at once).

    Rows come back as they finish and the table is put in input order at the end, so
    the order of the work is free: largest first, the last files to finish are small
    ones, and no worker is left measuring a 200k-triangle part alone while the others
    wait (the longest-processing-time-first rule, within 4/3 of the best schedule)."""
    def size(task: Task) -> int:
        try:
            return os.stat(task[1]).st_size
        except OSError:
            return -1

    return sorted(tasks, key=size, reverse=True)


def _results(workers: list[_Worker], pending: deque[Task], options: Options,
             threads: int) -> Iterator[tuple[int, FileResult]]:
    """The pool's loop: give each worker a task, collect its row, replace a worker that
    crashed or overran ``options.timeout``."""
    from multiprocessing.connection import wait

    try:
        for w in workers:
            if pending:
                w.give(pending.popleft(), options.timeout)
        while any(w.task for w in workers):
            busy = [w for w in workers if w.task]
            left = min(w.deadline for w in busy) - time.monotonic()
            ready = set(wait([w.conn for w in busy] + [w.process.sentinel for w in busy],
                             timeout=None if left == float("inf") else max(left, 0.0)))
            finished = []  # yielded once every ready worker has its next path: the
            for i, w in enumerate(workers):  # caller's work on a row keeps none waiting
                if not w.task:
                    continue
                result = None
                if w.conn in ready or w.process.sentinel in ready:
                    try:
                        _, result = _answer(w.conn.recv())
                    except (EOFError, OSError):
                        w.process.join(1.0)
                        code = w.process.exitcode
                        result = lost_row(w.task[1], w.task[2], options, "crashed",
                                          f"the worker process died (exit code {code}) while "
                                          "measuring this file")
                elif time.monotonic() >= w.deadline:
                    result = lost_row(w.task[1], w.task[2], options, "timeout",
                                      f"took longer than the time limit of {options.timeout:g} s")
                if result is None:
                    continue
                index = w.task[0]
                if result.row.get("status") in ("crashed", "timeout"):
                    w.stop(kill=True)
                    w = workers[i] = _Worker(options, threads)
                w.task = None
                if pending:
                    w.give(pending.popleft(), options.timeout)
                finished.append((index, result))
            yield from finished
    finally:
        for w in workers:
            w.stop(kill=bool(w.task))
