"""Benchmark: a 10,000-file ``plumbob batch --poses`` run, with its memory, an
interruption and the resume, and the same on a Dask local cluster.

The corpus: ``--files`` (default 10,000) small closed potatoes written as binary STL
(10 to 2,000 triangles, most small; about 4.5 % broken on purpose), from
``batch.make_corpus``. Measured:

* ``plumbob batch CORPUS --poses --out t.csv --jobs N --quiet`` as a whole process:
  wall time, files/s, and the peak resident memory (VmHWM) of each worker process,
  read from /proc while the run goes on;
* a real interruption late in a run: the same command on a fresh table sent SIGINT
  (as Ctrl-C) once 95 % of its rows are on disk, then ``--resume`` to the end: its
  wall time, the rows it kept and the files it measured, and whether the table is
  the uninterrupted run's; and ``--resume`` of the finished table (nothing left to
  measure: what a resume costs by itself);
* ``plumbob.batch.run(..., scheduler=...)`` on a ``distributed.LocalCluster`` of N
  single-threaded worker processes (start-up not timed), with each worker's peak
  memory.

Run: ``python bench/batch_scale.py [--files N] [--jobs N] [--folder DIR] [--skip-dask]
[--dask-files N] [--skip-full]``;
``--smoke``: 30 files, no Dask, nothing judged.
"""

from __future__ import annotations

import argparse
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

from _common import PYTHON, SRC, src_environment


def _descendants(root: int) -> dict[int, int]:
    """The process ``root`` and its descendants: pid -> depth below ``root``."""
    children: dict[int, list[int]] = {}
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            with open(f"/proc/{name}/stat") as handle:
                parent = int(handle.read().rsplit(")", 1)[1].split()[1])
        except (OSError, ValueError, IndexError):
            continue
        children.setdefault(parent, []).append(int(name))
    out, todo = {}, [(root, 0)]
    while todo:
        pid, depth = todo.pop()
        out[pid] = depth
        todo.extend((child, depth + 1) for child in children.get(pid, []))
    return out


def _high_water(pid: int) -> float | None:
    """A process's peak resident memory so far, MB (None once it has gone)."""
    try:
        with open(f"/proc/{pid}/status") as handle:
            for line in handle:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024
    except OSError:
        return None
    return None


def _cpu(pid: int) -> float:
    """A process's own CPU time so far, s (0 once it has gone)."""
    try:
        with open(f"/proc/{pid}/stat") as handle:
            fields = handle.read().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError):
        return 0.0


class PeakWatch:
    """Polls the peak memory of a process and its descendants every ``every`` s; the
    pool's workers are the deepest of them: the root's children where the pool forks
    them from the command's process, its grandchildren where a fork server does."""

    def __init__(self, root: int, every: float = 0.5) -> None:
        self.root, self.every, self.peaks, self.depth = root, every, {}, {}
        self.cpu = 0.0  # the root's own CPU time so far, s (user + system)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self) -> None:
        while not self._stop.is_set():
            self.cpu = max(self.cpu, _cpu(self.root))
            for pid, depth in _descendants(self.root).items():
                self.depth[pid] = depth
                peak = _high_water(pid)
                if peak is not None:
                    self.peaks[pid] = max(self.peaks.get(pid, 0.0), peak)
            self._stop.wait(self.every)

    def stop(self) -> tuple[float, list[float], float]:
        """(the root's peak, the workers' peaks), MB, and the root's own CPU time, s."""
        self._stop.set()
        self._thread.join()
        deepest = max((d for pid, d in self.depth.items() if pid in self.peaks), default=0)
        workers = [v for pid, v in self.peaks.items() if 0 < deepest == self.depth.get(pid)]
        return self.peaks.get(self.root, 0.0), workers, self.cpu


def _rows(path: str) -> int:
    try:
        with open(path, "rb") as handle:
            return max(0, sum(1 for _ in handle) - 1)
    except OSError:
        return 0


def batch(corpus: str, out: str, jobs: int, *extra: str, stop_at: int | None = None
          ) -> tuple[float, int, tuple[float, list[float], float]]:
    """Run the command; (wall s, exit status, (its own peak, its workers' peaks) MB and
    its own CPU time, s: the work the parent does per file bounds the rate many workers
    can reach).
    ``stop_at``: send SIGINT once the table holds that many rows."""
    env = src_environment()
    start = time.perf_counter()
    child = subprocess.Popen([PYTHON, "-m", "plumbob", "batch", corpus, "--poses", "--out", out,
                              "--jobs", str(jobs), "--quiet", *extra], env=env)
    watch = PeakWatch(child.pid)
    while child.poll() is None:
        if stop_at is not None and _rows(out) >= stop_at:
            child.send_signal(signal.SIGINT)
            stop_at = None
        time.sleep(0.05)
    seconds = time.perf_counter() - start
    peaks = watch.stop()
    return seconds, child.returncode, peaks


def _table(path: str) -> list[str]:
    """A table's lines, header first and the rows sorted (a resumed table keeps the
    order its rows were written in)."""
    with open(path) as handle:
        lines = handle.read().splitlines()
    return lines[:1] + sorted(lines[1:])


def _memory(peaks: tuple[float, list[float], float]) -> str:
    own, workers, _ = peaks
    if not workers:
        return f"peak memory {own:.0f} MB (measured in the command's own process)"
    return (f"peak memory per worker {min(workers):.0f}-{max(workers):.0f} MB "
            f"({len(workers)} worker processes), the command's own process {own:.0f} MB")


def dask_run(corpus: str, jobs: int, files: int) -> tuple[float, list[float], int]:
    from distributed import Client, LocalCluster

    import plumbob.batch

    def peak() -> float:
        return _high_water(os.getpid()) or 0.0

    with LocalCluster(n_workers=jobs, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        start = time.perf_counter()
        names = sorted(os.listdir(corpus))[:files]
        result = plumbob.batch.run([os.path.join(corpus, name) for name in names], poses=True,
                                   scheduler=client, progress=False)
        seconds = time.perf_counter() - start
        peaks = list(client.run(peak).values())
    return seconds, peaks, len(result.rows)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--files", type=int, default=10_000)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--folder", help="keep the corpus and tables here")
    parser.add_argument("--skip-dask", action="store_true")
    parser.add_argument("--dask-files", type=int, help="the first N files only, on Dask")
    parser.add_argument("--skip-full", action="store_true",
                        help="use the table full.csv already in --folder")
    parser.add_argument("--smoke", action="store_true", help="30 files, no Dask")
    args = parser.parse_args(argv)
    if args.smoke:
        args.files, args.skip_dask = 30, True
    sys.path.insert(0, SRC)
    from batch import make_corpus

    folder = args.folder or tempfile.mkdtemp(prefix="plumbob-scale-")
    corpus = os.path.join(folder, "corpus")
    try:
        if not os.path.isdir(corpus):
            info = make_corpus(corpus, args.files, seed=11, largest=2_000)
            print(f"corpus: {info['files']:,} STL files, {info['broken']} broken, "
                  f"{info['triangles']:,} triangles in the good ones", flush=True)
        n = args.files
        full = os.path.join(folder, "full.csv")
        if not args.skip_full:
            seconds, status, peaks = batch(corpus, full, args.jobs)
            print(f"plumbob batch --jobs {args.jobs}: {seconds:.1f} s, {n / seconds:.1f} files/s, "
                  f"exit {status}, {_rows(full):,} rows; {_memory(peaks)}; the command's own "
                  f"CPU {1e3 * peaks[2] / n:.2f} ms per file", flush=True)

        # A real interruption late in a run: the same command on a fresh table, sent
        # SIGINT (as Ctrl-C) once 95 % of its rows are on disk; then --resume to the end,
        # which must give the uninterrupted run's table, and --resume of the finished
        # table (nothing left to measure: what a resume costs by itself).
        live = os.path.join(folder, "interrupted.csv")
        seconds, status, _ = batch(corpus, live, args.jobs, stop_at=int(0.95 * n))
        kept = _rows(live)
        print(f"the same run sent SIGINT at 95 %: {kept:,} rows on disk after {seconds:.1f} s, "
              f"exit {status}", flush=True)
        seconds, status, peaks = batch(corpus, live, args.jobs, "--resume")
        same = _table(live) == _table(full)
        print(f"--resume: {seconds:.1f} s to keep {kept:,} rows and measure the "
              f"{n - kept:,} files left, exit {status}, {_rows(live):,} rows, "
              f"{'the same table as the uninterrupted run' if same else 'NOT the same table'}"
              f"; the command's own CPU {peaks[2]:.2f} s", flush=True)
        seconds, status, peaks = batch(corpus, live, args.jobs, "--resume")
        print(f"--resume of the finished table (nothing to measure): {seconds:.2f} s, its "
              f"own CPU {peaks[2]:.2f} s", flush=True)
        if not args.skip_dask:
            seconds, peaks, rows = dask_run(corpus, args.jobs, args.dask_files or n)
            print(f"Dask LocalCluster, {args.jobs} workers x 1 thread: {seconds:.1f} s, "
                  f"{rows / seconds:.1f} files/s, {rows:,} rows; peak memory per worker "
                  f"{min(peaks):.0f}-{max(peaks):.0f} MB", flush=True)
    finally:
        if not args.folder:
            shutil.rmtree(folder, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
