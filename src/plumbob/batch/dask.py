"""The same batch on a Dask distributed cluster (``--scheduler tcp://HOST:PORT``).

Every file is one Dask task running :func:`~plumbob.batch.rows.process_file`, the
function the local pool runs, so the table is the same row for row. Workers are sent
absolute paths (they may have started in another folder; on other machines the files
must be on a shared file system at the same path) and report the path as given.

A Dask task cannot be killed from outside, so ``--timeout`` here abandons a file
whose measurement overruns: the row says ``timeout`` at once and the worker's thread
finishes the file in the background.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Iterator
from typing import Any

from ..blockwise import limit_threads
from .extra import require
from .options import Options
from .rows import FileResult, failure, lost_row, process_file

__all__ = ["run_dask", "dask_task"]

_threads: int | None = None  # the thread count this worker process was limited to


def dask_task(path: str, shown: str, options: Options, threads: int = 1) -> FileResult:
    """One file on a Dask worker, within the time limit (the worker's threads share its
    cores already: BLAS, OpenMP and plumbob's own blocks run on ``threads`` threads)."""
    global _threads
    if _threads != threads:  # once per worker process, not per file
        limit_threads(threads)
        _threads = threads
    if options.timeout is None:
        return process_file(path, options, shown)
    box: list[FileResult] = []
    thread = threading.Thread(target=lambda: box.append(process_file(path, options, shown)),
                              daemon=True)
    thread.start()
    thread.join(options.timeout)
    if box:
        return box[0]
    return lost_row(path, shown, options, "timeout",
                    f"took longer than the time limit of {options.timeout:g} s")


def run_dask(tasks: list[tuple[int, str, str]], options: Options,
             scheduler: Any, threads: int = 1) -> Iterator[tuple[int, FileResult]]:
    """(index, result) for every task as the cluster finishes it, each on ``threads``
    BLAS/OpenMP/plumbob threads.

    scheduler: the scheduler's address (``tcp://HOST:PORT``) or a ``distributed.Client``.
    """
    distributed = require("distributed", "--scheduler (Dask)")
    own = not isinstance(scheduler, distributed.Client)
    client = distributed.Client(scheduler, timeout="30s") if own else scheduler
    try:
        futures = [client.submit(dask_task, os.path.abspath(path), shown, options, threads,
                                 pure=False)
                   for _, path, shown in tasks]
        index_of = {future.key: task[0] for future, task in zip(futures, tasks)}
        shown_of = {future.key: task[2] for future, task in zip(futures, tasks)}
        for future in distributed.as_completed(futures):
            try:
                result = future.result()
            except Exception as error:  # a lost worker, an unimportable plumbob: one row
                key = future.key
                result = FileResult({"path": shown_of[key], "units": options.units,
                                     **failure(error, "crashed")})
            index = index_of[future.key]
            future.release()
            yield index, result
    finally:
        if own:
            client.close()
