"""A process pool that survives its work: a time limit per file, and a worker that dies
(a crash in a C library, memory exhausted) costs one row, never the run.

``concurrent.futures`` cannot stop one running task, so each worker is a process of
its own with a pipe: the parent sends a path, waits on every pipe and every process
at once, and when a file overruns ``--timeout`` kills that worker and starts another.
Only paths go out and small rows come back: meshes are read where they are measured,
never copied between processes. Workers come from a fork server that has already
imported numpy and plumbob, so a restart costs milliseconds.
"""

from __future__ import annotations

import multiprocessing
import signal
import time
from collections import deque
from collections.abc import Iterator

from ..blockwise import set_workers
from .options import Options
from .rows import FileResult, lost_row, process_file

__all__ = ["Task", "run_pool"]

#: (position in the input list, path to read, path to report)
Task = tuple[int, str, str]


def _serve(conn, options: Options) -> None:
    """A worker's life: measure each path it is sent until told to stop."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the parent's to handle
    set_workers(1)  # the pool's processes share the cores already: no threads of its own
    while True:
        try:
            task = conn.recv()
        except (EOFError, OSError):
            return
        if task is None:
            return
        index, path, shown = task
        conn.send((index, process_file(path, options, shown)))


def _context():
    methods = multiprocessing.get_all_start_methods()
    if "forkserver" in methods:
        context = multiprocessing.get_context("forkserver")
        context.set_forkserver_preload(["numpy", "plumbob.batch.rows", "plumbob.stability"])
        return context
    return multiprocessing.get_context("spawn")


class _Worker:
    def __init__(self, context, options: Options) -> None:
        self.conn, child = context.Pipe()
        self.process = context.Process(target=_serve, args=(child, options), daemon=True)
        self.process.start()
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


def _in_process(tasks: list[Task], options: Options) -> Iterator[tuple[int, FileResult]]:
    for index, path, shown in tasks:
        yield index, process_file(path, options, shown)


def run_pool(tasks: list[Task], options: Options, jobs: int) -> Iterator[tuple[int, FileResult]]:
    """(index, result) for every task, as they finish, on ``jobs`` processes.

    With one job and no time limit the files are measured in this process (nothing to
    stop, nothing to gain from a second process).
    """
    if jobs <= 1 and options.timeout is None:
        yield from _in_process(tasks, options)
        return
    from multiprocessing.connection import wait

    context = _context()
    pending = deque(tasks)
    workers = [_Worker(context, options) for _ in range(min(jobs, len(tasks)))]
    try:
        for w in workers:
            if pending:
                w.give(pending.popleft(), options.timeout)
        while any(w.task for w in workers):
            busy = [w for w in workers if w.task]
            left = min(w.deadline for w in busy) - time.monotonic()
            ready = set(wait([w.conn for w in busy] + [w.process.sentinel for w in busy],
                             timeout=None if left == float("inf") else max(left, 0.0)))
            for i, w in enumerate(workers):
                if not w.task:
                    continue
                result = None
                if w.conn in ready or w.process.sentinel in ready:
                    try:
                        _, result = w.conn.recv()
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
                    w = workers[i] = _Worker(context, options)
                w.task = None
                if pending:
                    w.give(pending.popleft(), options.timeout)
                yield index, result
    finally:
        for w in workers:
            w.stop(kill=bool(w.task))
