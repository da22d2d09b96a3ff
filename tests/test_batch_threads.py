"""The worker pools own their threads: one BLAS/OpenMP/plumbob thread per worker
whatever the environment asks for, unless ``--threads-per-job`` says otherwise."""

import json
import os
import subprocess
import sys

import pytest
from _batch_corpus import write_stl
from conftest import ROOT

# Run in a fresh process whose environment asks for 8 threads everywhere: the fork server
# and the workers start from it (a test process's own fork server may predate the setting).
PROBE = """
import json
import threadpoolctl
import numpy  # its OpenBLAS loads here, reading the environment's 8
from plumbob.blockwise import workers
from plumbob.batch.pool import thread_report, worker_threads
from plumbob.stability.drops.run import worker_pool

if __name__ == "__main__":
    with worker_pool(2) as pool:
        drops = pool.submit(thread_report, ("scipy.linalg",), True).result()
    print(json.dumps({
        "parent": {"plumbob": workers(), "libraries": threadpoolctl.threadpool_info()},
        "batch": worker_threads(imports=("scipy.linalg",), manifold_work=True),
        "batch_two": worker_threads(2, imports=("scipy.linalg",)),
        "drops": drops}))
"""


def _cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


@pytest.fixture(scope="module")
def reports(tmp_path_factory):
    script = tmp_path_factory.mktemp("threads") / "probe.py"  # forkserver needs a real main
    script.write_text(PROBE)
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"), PLUMBOB_THREADS="8",
               **{name: "8" for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS",
                                         "MKL_NUM_THREADS")})
    out = subprocess.run([sys.executable, str(script)], env=env, capture_output=True,
                         text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def _threads(report: dict) -> list[int]:
    return [lib["num_threads"] for lib in report["libraries"]]


def test_the_environment_asks_for_many_threads(reports):
    """The control: outside the pools the same environment gives more than one thread
    (OpenBLAS caps its 8 at the machine's cores), so the checks below can fail."""
    parent = reports["parent"]
    assert parent["plumbob"] == 8
    assert parent["libraries"], "numpy's BLAS is seen by threadpoolctl"
    if _cores() > 1:
        assert max(_threads(parent)) > 1


@pytest.mark.parametrize("pool", ["batch", "drops"])
def test_a_live_worker_runs_one_thread_per_library(reports, pool):
    report = reports[pool]
    apis = {lib["internal_api"] for lib in report["libraries"]}
    assert "openblas" in apis
    # numpy's OpenBLAS (loaded before the limit) and scipy's (loaded after) alike
    assert len(report["libraries"]) >= 2
    assert _threads(report) == [1] * len(report["libraries"])
    assert report["plumbob"] == 1


# The control for manifold3d's threads: a plain process (BLAS on one thread, so that
# only manifold's scheduler can add threads) doing the same manifold work.
MANIFOLD_CONTROL = """
import json
from plumbob.batch.pool import thread_report
print(json.dumps(thread_report((), True)))
"""


@pytest.mark.skipif(not os.path.isdir("/proc/self/task"), reason="threads are counted "
                    "through Linux's /proc, which this system lacks")
@pytest.mark.parametrize("pool", ["batch", "drops"])
def test_a_live_worker_runs_manifolds_loops_on_one_thread(reports, pool):
    """manifold3d's oneTBB scheduler has no thread setting of its own; a worker starts
    it on one thread (``blockwise.manifold_on_threads``), so parallel-sized manifold work
    starts no thread in a worker, where a plain process starts a thread per core."""
    before, after = reports[pool]["os_threads"]
    assert after == before
    if _cores() > 1:
        env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"), OPENBLAS_NUM_THREADS="1")
        out = subprocess.run([sys.executable, "-c", MANIFOLD_CONTROL], env=env,
                             capture_output=True, text=True, timeout=60)
        assert out.returncode == 0, out.stderr
        before, after = json.loads(out.stdout)["os_threads"]
        assert after > before


def test_manifold_on_threads_leaves_the_affinity_as_it_was():
    """The scheduler is started under a narrowed CPU mask, which is then restored: the
    process may still run on every CPU it was given."""
    from plumbob.blockwise import manifold_on_threads

    if not hasattr(os, "sched_getaffinity"):
        pytest.skip("CPU affinity is a Linux interface, which this system lacks")
    before = os.sched_getaffinity(0)
    manifold_on_threads(1)
    assert os.sched_getaffinity(0) == before


# As ``plumbob batch`` starts (its entry point insists on BLAS's one thread, whatever the
# environment asks: here 8): a single-threaded process, from which the pool forks its
# workers; then the same with a thread of the program's own alive, the control.
FORKED = """
import json, threading
from plumbob.__main__ import blas_starts_with_one_thread
started = blas_starts_with_one_thread(insist=True)  # a fork server reruns this: False
from plumbob.batch.pool import worker_threads

if __name__ == "__main__":
    assert started
    single = worker_threads(imports=("scipy.linalg",), manifold_work=True)
    stop = threading.Event()
    waiting = threading.Thread(target=stop.wait)
    waiting.start()
    try:
        threaded = worker_threads()
    finally:
        stop.set()
        waiting.join()
    print(json.dumps({"single": single, "threaded": threaded}))
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="the pool forks its "
                    "workers on Linux only (where /proc counts a process's threads)")
def test_the_pool_forks_its_workers_from_a_single_threaded_process(tmp_path):
    """Forked, a worker starts in milliseconds rather than after a fork server's ~0.2 s,
    and owns its threads as a fork server's workers do; a process running another thread
    (a lock it may hold would be copied held) gets them from the fork server instead."""
    script = tmp_path / "forked.py"
    script.write_text(FORKED)
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"),
               **{name: "8" for name in ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")})
    out = subprocess.run([sys.executable, str(script)], env=env, capture_output=True,
                         text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    report = json.loads(out.stdout)
    single, threaded = report["single"], report["threaded"]
    assert single["start_method"] == "fork" and threaded["start_method"] == "forkserver"
    assert len(single["libraries"]) >= 2 and _threads(single) == [1] * len(single["libraries"])
    before, after = single["os_threads"]
    assert after == before
    assert single["plumbob"] == threaded["plumbob"] == 1


def test_threads_per_job_asks_for_more(reports):
    report = reports["batch_two"]
    assert report["plumbob"] == 2
    assert set(_threads(report)) == {min(2, _cores())}


def test_a_worker_that_cannot_start_stops_the_batch_once_with_its_reason(shapes_dir):
    """A worker that fails before its first file (a broken installation: here a thread
    count it cannot take) stops the batch with the worker's own reason, once — it is not
    restarted for every file, each printing a traceback."""
    from plumbob.batch.options import Options
    from plumbob.batch.pool import WorkerStartError, run_pool, worker_threads

    with pytest.raises(WorkerStartError, match="could not start: ValueError"):
        worker_threads(threads="many")
    block = os.path.join(shapes_dir, "block.toml")
    tasks = [(k, block, "block.toml") for k in range(6)]
    with pytest.raises(WorkerStartError, match="could not start"):
        list(run_pool(tasks, Options(), jobs=2, threads="many"))


COMMAND = """
import contextlib, io, json, sys
import threadpoolctl
from plumbob.blockwise import workers
from plumbob.cli import main

with contextlib.redirect_stdout(io.StringIO()):
    status = main(["mass", sys.argv[1]])
print(json.dumps({"status": status, "plumbob": workers(),
                  "libraries": threadpoolctl.threadpool_info()}))
"""


def test_a_command_runs_blas_on_one_thread_and_its_blocks_on_every_core(shapes_dir):
    """A command's products are thin (n × 3 by 3 × k), where BLAS threads only spin: it
    runs BLAS on one thread whatever the environment asks, and its own row-wise blocks
    on the threads it was given (PLUMBOB_THREADS)."""
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"), PLUMBOB_THREADS="3",
               OPENBLAS_NUM_THREADS="8")
    out = subprocess.run([sys.executable, "-c", COMMAND,
                          os.path.join(shapes_dir, "sculpture.toml")],
                         env=env, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    report = json.loads(out.stdout)
    assert report["status"] == 0 and report["plumbob"] == 3
    blas = [lib for lib in report["libraries"] if lib["user_api"] == "blas"]
    assert blas and all(lib["num_threads"] == 1 for lib in blas)


START = """
import json, os, sys
from plumbob.__main__ import blas_starts_with_one_thread
assert "numpy" not in sys.modules, "import plumbob loaded numpy before the command set it up"
started = blas_starts_with_one_thread() if sys.argv[1] == "command" else None
import numpy, threadpoolctl
report = {"tasks": len(os.listdir("/proc/self/task")), "started": started,
          "blas": [lib["num_threads"] for lib in threadpoolctl.threadpool_info()
                   if lib["user_api"] == "blas"]}
with threadpoolctl.threadpool_limits(2):  # what --threads-per-job 2 asks of a worker
    report["raised"] = [lib["num_threads"] for lib in threadpoolctl.threadpool_info()
                        if lib["user_api"] == "blas"]
print(json.dumps(report))
"""


def _start(how: str, **env: str) -> dict:
    from plumbob.__main__ import BLAS_VARIABLES

    base = {k: v for k, v in os.environ.items() if k not in BLAS_VARIABLES}
    out = subprocess.run([sys.executable, "-c", START, how], capture_output=True, text=True,
                         timeout=120, env=dict(base, PYTHONPATH=os.path.join(ROOT, "src"), **env))
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


@pytest.mark.skipif(not os.path.isdir("/proc/self/task") or _cores() < 2,
                    reason="counts the threads in /proc on a machine with 2 or more cores")
def test_a_command_starts_openblas_without_its_threads():
    """The command's process has numpy's OpenBLAS start on one thread, so no thread per
    core is started (and spins) before the command's own limit reaches it; the control,
    a program that imports plumbob, starts OpenBLAS's threads as numpy does. A worker that
    inherits the setting can still be given more threads (``--threads-per-job``)."""
    command, program = _start("command"), _start("program")
    assert command["blas"] == [1] and command["tasks"] == 1 and command["started"] is True
    assert program["blas"][0] > 1 and program["tasks"] > 1
    assert command["raised"] == [2]
    own = _start("command", OPENBLAS_NUM_THREADS="2")  # the user's own count: the command
    assert own["blas"] == [2] and own["started"] is False  # limits it itself (below)


ENTRY = """
import contextlib, io, json, os, sys
from plumbob.__main__ import entry
sys.argv = ["plumbob", *sys.argv[1:]]
with contextlib.redirect_stdout(io.StringIO()):
    status = entry()
import threadpoolctl
print(json.dumps({"status": status, "variable": os.environ["OPENBLAS_NUM_THREADS"],
                  "blas": [lib["num_threads"] for lib in threadpoolctl.threadpool_info()
                           if lib["user_api"] == "blas"]}))
"""


@pytest.mark.parametrize("asked", [None, "8"])
@pytest.mark.parametrize("command", ["mass", "batch"])
def test_the_command_runs_blas_on_one_thread_however_it_started(shapes_dir, tmp_path, asked,
                                                               command):
    """Through the console script's entry point: BLAS on one thread while the command
    runs, whether it started so (nothing asked: the entry point set it) or the
    environment asked for 8 threads (then the command limits it; ``batch`` insists on
    one from the start, whatever is asked, so that its pool may fork its workers)."""
    from plumbob.__main__ import BLAS_VARIABLES

    env = {k: v for k, v in os.environ.items() if k not in BLAS_VARIABLES}
    if asked:
        env["OPENBLAS_NUM_THREADS"] = asked
    arguments = [command, os.path.join(shapes_dir, "sculpture.toml")]
    if command == "batch":
        arguments += ["--out", str(tmp_path / "rows.csv"), "--jobs", "2", "--quiet"]
    out = subprocess.run([sys.executable, "-c", ENTRY, *arguments],
                         env=dict(env, PYTHONPATH=os.path.join(ROOT, "src")),
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    report = json.loads(out.stdout)
    assert report["status"] == 0 and report["blas"] == [1]
    insisted = command == "batch" or not asked
    assert report["variable"] == ("1" if insisted else asked)


MALLOC = """
import ctypes, json, sys
from plumbob.__main__ import malloc_keeps_freed_memory
done = malloc_keeps_freed_memory() if sys.argv[1] == "command" else None
import numpy as np


class Info(ctypes.Structure):  # glibc's struct mallinfo2 (2.33 on)
    _fields_ = [(name, ctypes.c_size_t) for name in (
        "arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks", "fsmblks", "uordblks",
        "fordblks", "keepcost")]


libc = ctypes.CDLL(None)
libc.mallinfo2.restype = Info
held = np.ones(8 << 20)  # 64 MB: mapped on its own by default (beyond 32 MB, always)
while_held = libc.mallinfo2()
del held
after = libc.mallinfo2()
print(json.dumps({"done": done, "mapped_while_held": while_held.hblkhd,
                  "heap_after_free": after.arena}))
"""


def _malloc(how: str) -> dict:
    out = subprocess.run([sys.executable, "-c", MALLOC, how], capture_output=True, text=True,
                         timeout=120, env=dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src")))
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def _has_mallinfo2() -> bool:
    import ctypes

    try:
        return sys.platform.startswith("linux") and hasattr(ctypes.CDLL(None), "mallinfo2")
    except OSError:
        return False


@pytest.mark.skipif(not _has_mallinfo2(), reason="glibc's malloc (mallopt, mallinfo2), on Linux")
def test_a_command_keeps_the_memory_it_freed_for_the_next_array():
    """The command has malloc serve a 64 MB array from its heap and keep it there once
    freed, for the next array to reuse without page faults; in a program that imports
    plumbob (the control) the array is mapped on its own and given back when freed."""
    MB = 1 << 20
    command, program = _malloc("command"), _malloc("program")
    assert command["done"] is True
    assert command["mapped_while_held"] < MB and command["heap_after_free"] >= 64 * MB
    assert program["mapped_while_held"] >= 64 * MB and program["heap_after_free"] < 64 * MB


ONE_JOB = """
import json, os, sys
import plumbob.batch

threads = None if sys.argv[2] == "none" else int(sys.argv[2])
result = plumbob.batch.run([sys.argv[1]], poses=True, jobs=1, threads_per_job=threads)
import manifold3d

manifold3d.Manifold.sphere(1.0, 64).volume()  # parallel-sized: starts the scheduler's threads
print(json.dumps({"status": result.rows[0]["status"],
                  "tasks": len(os.listdir("/proc/self/task"))}))
"""


@pytest.mark.skipif(not os.path.isdir("/proc/self/task") or _cores() < 2,
                    reason="counts the threads in /proc on a machine with 2 or more cores")
def test_one_job_on_one_thread_runs_manifolds_loops_on_one(tmp_path):
    """``--jobs 1 --threads-per-job 1`` measures in the command's own process, and there
    too manifold3d's scheduler starts on one thread (it fixes its count once, for the
    process's life): parallel-sized manifold work after the run starts no thread. The
    control, one job on its cores: the same work starts manifold's threads."""
    import manifold3d
    import numpy as np

    sphere = manifold3d.Manifold.sphere(1.0, 32).to_mesh()
    ball = tmp_path / "ball.stl"
    write_stl(str(ball), np.asarray(sphere.vert_properties)[:, :3][np.asarray(sphere.tri_verts)])

    def tasks(threads: str) -> int:
        env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"), OPENBLAS_NUM_THREADS="1",
                   PLUMBOB_THREADS="1")
        out = subprocess.run([sys.executable, "-c", ONE_JOB, str(ball), threads], env=env,
                             capture_output=True, text=True, timeout=120)
        assert out.returncode == 0, out.stderr
        report = json.loads(out.stdout)
        assert report["status"] == "ok"
        return report["tasks"]

    assert tasks("1") == 1
    assert tasks("none") > 1
