"""Batch runs: mass properties, stability and poses of many files, one table.

::

    import plumbob.batch
    result = plumbob.batch.run(["parts/"], check=True, poses=True, out="results.csv")
    result.rows            # one dict per file, keys as ``plumbob mass/check/poses --json``
    result.to_pandas()     # the flat table (needs pandas: pip install 'plumbob[batch]')

:func:`run` finds the files (files, folders searched recursively, globs), measures
them on every core (``jobs``) or on a Dask cluster (``scheduler``), writes each row as
it comes (``out``: .csv, .jsonl or .parquet) and can ``resume`` an interrupted run.
To drive Ray, Dask or your own scheduler, map :func:`process_file` over paths with
one :class:`Options`: it never raises, and its ``row`` is the table's row.

The room is callable as :func:`run`: ``plumbob.batch(["parts/"], check=True)``.
This package imports only the standard library until a batch runs.
"""

from __future__ import annotations

from ..callable_module import make_callable
from .options import Options
from .rows import FileResult, process_file
from .runner import BatchResult, default_jobs, run

make_callable(__name__, run)

__all__ = ["run", "Options", "process_file", "FileResult", "BatchResult", "default_jobs"]
