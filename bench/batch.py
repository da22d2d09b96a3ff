"""Benchmark: ``plumbob batch`` against a trimesh loop, over a generated corpus.

The corpus: ``--files`` (default 2,000) closed, non-symmetric "potatoes" written as
binary STL, their triangle counts spread from 10 to 200,000 (log-uniform, squared
toward the small end as real part libraries are), and about 4.5 % broken on purpose
(truncated, open, garbage). Each file gets mass properties and resting poses:

* ``plumbob batch CORPUS --poses --jobs 1`` and ``--jobs N`` (N = every core, or each
  of a list: ``--jobs 4,16``), the whole command timed as a process, writing CSV; and
  ``--jobs N`` (the largest) again with
  ``OPENBLAS_NUM_THREADS=OMP_NUM_THREADS=MKL_NUM_THREADS=8`` (``--env-threads``) in its
  environment;
* ``plumbob.batch.run(..., scheduler=...)`` on a Dask ``LocalCluster`` of N
  single-threaded worker processes (cluster start-up not timed);
* a trimesh loop doing the same (``trimesh.load``, ``mass_properties``,
  ``compute_stable_poses`` at the centre of mass) in a process pool of 1 and of N (or
  of the sizes ``--trimesh-jobs`` lists), each worker limited to one BLAS/OpenMP thread
  by ``threadpoolctl`` as plumbob's workers are.

plumbob and trimesh run in turns (plumbob 1, trimesh 1, plumbob N, trimesh N), so that
a shared machine's changing load falls alike on each pair. Printed: wall time, files per
second and CPU time of each run (every process of it: on Linux this process adopts the
pool's orphaned workers, ``PR_SET_CHILD_SUBREAPER``, and waits for them), the load
average before and after, the ratios plumbob / trimesh at 1 and at N processes by wall
and by CPU time, and the scaling from 1 to N jobs. Issue 24 asks for at least 5× a
trimesh process pool of the same size and at least 1.7× from 1 to 2 jobs on a 2-core
machine; the ratios are printed, never asserted (a shared machine's timings are noisy;
by CPU time they are distorted least).

Run: ``python bench/batch.py [--files N] [--largest T] [--folder DIR] [--jobs N[,N...]]
[--trimesh-jobs N[,N...]] [--env-threads K] [--skip-trimesh] [--skip-dask] [--skip-env]``;
``--smoke``: four tiny files, no Dask, every step run once and no target judged (the
test suite runs it, so an import error or a changed API fails the tests).
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np
from _common import PYTHON, SRC, src_environment, write_binary_stl
from _shapes import potato


def triangle_counts(n: int, rng: np.random.Generator) -> np.ndarray:
    """Sizes from 10 to 200k, most parts small (u² skews log-uniform to the small end)."""
    return np.round(10 * 20_000 ** (rng.uniform(0, 1, n) ** 2)).astype(int)


def make_corpus(folder: str, files: int, seed: int = 7, largest: int = 200_000
                ) -> dict[str, int]:
    """Write the corpus; returns counts of good and broken files and triangles."""
    rng = np.random.default_rng(seed)
    os.makedirs(folder, exist_ok=True)
    broken = total = 0
    for k, target in enumerate(np.minimum(triangle_counts(files, rng), largest)):
        rings = max(1, int(round(np.sqrt(target / 4))))
        lon = max(3, int(round(target / (2 * rings))))
        verts, faces = potato(rings + 1, lon, seed=k)
        tris = verts[faces] * rng.uniform(0.02, 0.5)  # 2 cm to 50 cm
        path = os.path.join(folder, f"part_{k:05d}.stl")
        kind = k % 67  # about 4.5 % broken, three ways
        if kind == 11:
            write_binary_stl(path, tris[: len(tris) // 2])
            with open(path, "r+b") as handle:  # header promises more than the file holds
                handle.seek(80)
                handle.write(np.uint32(len(tris)).tobytes())
        elif kind == 22 and len(tris) > 20:
            write_binary_stl(path, tris[:-3])  # an open mesh
        elif kind == 33:
            with open(path, "wb") as handle:
                handle.write(rng.bytes(300))
        else:
            write_binary_stl(path, tris)
            total += len(tris)
            continue
        broken += 1
    return {"files": files, "broken": broken, "triangles": total}


_LIMITS = []  # the trimesh worker's thread limits, kept alive for the process's life


def _one_thread() -> None:
    """A trimesh worker runs BLAS and OpenMP on one thread, as plumbob's workers do
    (``threadpoolctl``, whatever the environment says): the same limits on both sides."""
    import threadpoolctl

    _LIMITS.append(threadpoolctl.threadpool_limits(limits=1))


def _trimesh_one(path: str) -> bool:
    """What a hand-written harness does per file: load, mass properties, stable poses."""
    import trimesh

    try:
        mesh = trimesh.load(path, force="mesh")
        if not mesh.is_watertight:
            return False
        props = mesh.mass_properties
        trimesh.poses.compute_stable_poses(mesh, center_mass=props["center_mass"])
        return True
    except Exception:
        return False


def _children_cpu() -> float:
    """CPU time (user + system, s) of the finished child processes waited for so far."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _adopt_orphans() -> bool:
    """Make this process the reaper of its descendants' orphans (Linux's
    ``PR_SET_CHILD_SUBREAPER``): a pool's workers are children of the command's fork
    server, which the command does not wait for; adopted and waited for here, their CPU
    time reaches :func:`_children_cpu`. False where that is not possible."""
    try:
        import ctypes

        return ctypes.CDLL(None, use_errno=True).prctl(36, 1, 0, 0, 0) == 0
    except (OSError, AttributeError):
        return False


def _reap_orphans(wait: float = 10.0) -> None:
    """Wait for the adopted orphans of a finished run (its fork server, which waits for
    its workers) so that their CPU time is counted."""
    end = time.monotonic() + wait
    while time.monotonic() < end:
        try:
            pid, _ = os.waitpid(-1, os.WNOHANG)
        except ChildProcessError:
            return
        if not pid:
            time.sleep(0.02)


ADOPTS = False  # set in main: whether every process of a pool run is counted
CPU: dict[str, float] = {}  # CPU seconds of each run, where every process of it is counted


def trimesh_loop(paths: list[str], jobs: int) -> float:
    """A trimesh process pool of ``jobs`` workers, each on one BLAS/OpenMP thread."""
    cpu, start = _children_cpu(), time.perf_counter()
    with ProcessPoolExecutor(max_workers=jobs, initializer=_one_thread) as pool:
        list(pool.map(_trimesh_one, paths, chunksize=8))
    seconds = time.perf_counter() - start
    CPU[f"trimesh {jobs}"] = _children_cpu() - cpu
    return seconds


THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


def compile_plumbob() -> None:
    """Compile plumbob's modules once, before anything is timed, beside its sources
    (``__pycache__``, which git ignores): the command and its pool's fork server then
    load compiled bytecode, as an installed package does (trimesh's was compiled when it
    was installed), even where ``PYTHONDONTWRITEBYTECODE`` keeps them from writing it
    (else each process of each run compiles plumbob again: 0.1-0.2 s of CPU)."""
    subprocess.run([PYTHON, "-m", "compileall", "-q", os.path.join(SRC, "plumbob")],
                   check=True, stdout=subprocess.DEVNULL)


def plumbob_cli(folder: str, jobs: int, out: str, threads: str | None = None,
                one_core: bool = False) -> float:
    """Wall time of the whole command; ``threads``: what the environment asks BLAS and
    OpenMP for (the workers must not follow it); ``one_core``: one job on one thread
    (``--threads-per-job 1``), where one job otherwise uses every core for its blocks
    and manifold3d's loops."""
    env = src_environment(**dict.fromkeys(THREAD_VARIABLES, threads) if threads else {})
    cpu, start = _children_cpu(), time.perf_counter()
    done = subprocess.run([PYTHON, "-m", "plumbob", "batch", folder, "--poses", "--out",
                           out, "--jobs", str(jobs), "--quiet",
                           *(["--threads-per-job", "1"] if one_core else [])],
                          env=env, check=False)
    seconds = time.perf_counter() - start
    if done.returncode not in (0, 1):  # 1: the corpus's broken files
        raise SystemExit(f"plumbob batch exited {done.returncode}")
    if ADOPTS:
        _reap_orphans()
    if jobs == 1 or ADOPTS:  # one job runs in the command's own process
        key = f"plumbob {jobs}{f' env {threads}' if threads else ''}"
        CPU[key + (" one core" if one_core else "")] = _children_cpu() - cpu
    return seconds


def plumbob_dask(folder: str, jobs: int) -> tuple[float, list]:
    from distributed import LocalCluster

    import plumbob.batch

    with LocalCluster(n_workers=jobs, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster:
        start = time.perf_counter()
        result = plumbob.batch.run([folder], poses=True, scheduler=cluster.scheduler_address)
        return time.perf_counter() - start, result.rows


def _counts(text: str) -> list[int]:
    """``"4,16"`` -> [4, 16]: process counts, each at least 1."""
    try:
        counts = [int(part) for part in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected counts such as 4 or 4,16, not {text!r}") from None
    if min(counts) < 1:
        raise argparse.ArgumentTypeError(f"process counts are at least 1, not {text!r}")
    return counts


ONE_CORE = "plumbob batch --jobs 1, one thread"


def _pool(n: int) -> str:
    return f"trimesh pool, {n} process{'es' if n > 1 else ''}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--files", type=int, default=2000)
    parser.add_argument("--largest", type=int, default=200_000,
                        help="the largest part's triangles (default 200,000)")
    parser.add_argument("--folder", help="keep the corpus here (default: a temporary folder)")
    parser.add_argument("--jobs", type=_counts, default=None,
                        help="N, or several: 4,16 (default: every core); 1 is always run")
    parser.add_argument("--trimesh-jobs", type=_counts, default=None,
                        help="the trimesh pool's sizes (default: the same as plumbob's)")
    parser.add_argument("--env-threads", default="8",
                        help="what the environment asks BLAS/OpenMP for in the last run")
    parser.add_argument("--skip-trimesh", action="store_true")
    parser.add_argument("--skip-dask", action="store_true")
    parser.add_argument("--skip-env", action="store_true",
                        help="skip the run with the environment asking BLAS for 8 threads")
    parser.add_argument("--one-core", action="store_true",
                        help="also one job on one thread (--threads-per-job 1): the scaling "
                             "per core, where one job alone uses every core in part")
    parser.add_argument("--smoke", action="store_true",
                        help="tiny corpus, each step once, no targets judged")
    args = parser.parse_args(argv)
    if args.smoke:
        args.files, args.skip_dask, args.one_core = 4, True, True
    sys.path.insert(0, SRC)
    from plumbob.batch import default_jobs

    sizes = sorted({1, *(args.jobs or [default_jobs()])})
    jobs = sizes[-1]
    trimesh_sizes = [] if args.skip_trimesh else sorted(set(args.trimesh_jobs or sizes))
    global ADOPTS
    ADOPTS = _adopt_orphans()
    folder = args.folder or tempfile.mkdtemp(prefix="plumbob-batch-")
    try:
        started = time.perf_counter()
        info = make_corpus(os.path.join(folder, "corpus"), args.files,
                           largest=300 if args.smoke else args.largest)
        print(f"corpus: {info['files']} STL files, {info['broken']} broken, "
              f"{info['triangles']:,} triangles in the good ones "
              f"(written in {time.perf_counter() - started:.1f} s)")
        corpus = os.path.join(folder, "corpus")
        if not args.smoke:
            compile_plumbob()
        paths = sorted(os.path.join(corpus, f) for f in os.listdir(corpus))
        rate: dict[str, float] = {}
        cpu_of = {}  # run name -> its key in CPU

        def report(name: str, seconds: float, cpu: str | None = None) -> None:
            rate[name] = len(paths) / seconds
            cpu_of[name] = cpu
            used = f"{CPU[cpu]:9.2f} s CPU" if cpu in CPU else ""
            print(f"{name:<32}{seconds:9.2f} s {rate[name]:10.1f} files/s {used}", flush=True)

        print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
        # plumbob and trimesh in turns, each size after the other, so that a shared
        # machine's changing load falls alike on both of a pair
        for n in sizes:
            name = f"plumbob batch --jobs {n}"
            report(name, plumbob_cli(corpus, n, os.path.join(folder, f"{n}.csv")),
                   f"plumbob {n}")
            if n in trimesh_sizes:
                report(_pool(n), trimesh_loop(paths, n), f"trimesh {n}")
            if n == 1 and args.one_core:
                report(ONE_CORE, plumbob_cli(corpus, 1, os.path.join(folder, "1c.csv"),
                                             one_core=True), "plumbob 1 one core")
        many = f"plumbob batch --jobs {jobs}"
        eight = f"--jobs {jobs}, BLAS env {args.env_threads}"
        if not args.skip_env:
            report(eight, plumbob_cli(corpus, jobs, os.path.join(folder, "e.csv"),
                                      threads=args.env_threads),
                   f"plumbob {jobs} env {args.env_threads}")
        if not args.skip_dask:
            seconds, _ = plumbob_dask(corpus, jobs)
            report(f"plumbob on Dask ({jobs} workers)", seconds)
        print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
        print()
        one = "plumbob batch --jobs 1"
        for n in sizes[1:]:
            ours = f"plumbob batch --jobs {n}"
            print(f"scaling, --jobs 1 -> --jobs {n}: {rate[ours] / rate[one]:.2f}x wall, "
                  f"{rate[ours] / rate[one] / n:.2f} per job (target 1.7x for 2 jobs)" + (
                      f", {CPU['plumbob 1'] / CPU[f'plumbob {n}']:.2f}x CPU (the pool's "
                      "own cost)" if f"plumbob {n}" in CPU else ""))
            if args.one_core:
                print(f"scaling, one job on one thread -> --jobs {n}: "
                      f"{rate[ours] / rate[ONE_CORE]:.2f}x wall, "
                      f"{rate[ours] / rate[ONE_CORE] / n:.2f} per job")
        if args.one_core:
            print(f"one job on every core / on one thread: {rate[one] / rate[ONE_CORE]:.2f}x "
                  "wall")
        if not args.skip_env:
            print(f"--jobs {jobs} with OPENBLAS/OMP/MKL_NUM_THREADS={args.env_threads} / "
                  f"without: {rate[eight] / rate[many]:.2f}x (the workers keep one thread "
                  "each)")
        for n in trimesh_sizes:
            ours, theirs = f"plumbob {n}", f"trimesh {n}"
            line = (f"plumbob / trimesh pool, {n} process{'es' if n > 1 else ''} each: "
                    f"{rate[f'plumbob batch --jobs {n}'] / rate[_pool(n)]:.1f}x wall")
            if ours in CPU and theirs in CPU:
                line += (f", {CPU[theirs] / CPU[ours]:.1f}x CPU (plumbob {CPU[ours]:.1f} s, "
                         f"trimesh {CPU[theirs]:.1f} s: the ratio a shared machine "
                         "distorts least)")
            print(line + (" (target 5x)" if n > 1 else ""))
        if not args.skip_dask:
            print(f"Dask / --jobs {jobs}: "
                  f"{rate[f'plumbob on Dask ({jobs} workers)'] / rate[many]:.2f}x")
    finally:
        if not args.folder:
            shutil.rmtree(folder, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
