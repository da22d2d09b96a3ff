"""``plumbob batch --scheduler``: a Dask cluster started here (one scheduler, two
workers on 127.0.0.1) gives the same table as the local pool."""

import os
import socket
import subprocess
import sys
import time

import pytest
from _batch_corpus import make_corpus
from conftest import ROOT

import plumbob.batch
from plumbob.batch.writers import open_writer
from plumbob.cli import main

distributed = pytest.importorskip(
    "distributed", reason="Dask is not installed: pip install 'plumbob[batch]'")


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """`dask scheduler` and two `dask worker` processes, stopped at the end."""
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"))
    cwd = str(tmp_path_factory.mktemp("dask"))  # not the tests' folder: paths must be absolute
    dask = [sys.executable, "-m", "dask"]
    logs = open(os.path.join(cwd, "dask.log"), "w")
    started = [subprocess.Popen([*dask, "scheduler", "--host", "127.0.0.1", "--port", str(port),
                                 "--no-dashboard"], env=env, cwd=cwd, stdout=logs, stderr=logs)]
    try:
        for _ in range(2):
            started.append(subprocess.Popen(
                [*dask, "worker", address, "--nworkers", "1", "--nthreads", "1",
                 "--no-dashboard", "--host", "127.0.0.1"], env=env, cwd=cwd, stdout=logs,
                stderr=logs))
        with distributed.Client(address, timeout="60s") as client:
            client.wait_for_workers(2, timeout=120)
            assert len(client.scheduler_info()["workers"]) == 2
        yield address
    finally:
        for process in reversed(started):
            process.terminate()
        for process in reversed(started):
            try:
                process.wait(timeout=30)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
        logs.close()


def test_dask_cluster_gives_the_identical_table(tmp_path, cluster, monkeypatch):
    folder = str(tmp_path / "corpus")
    make_corpus(folder)
    monkeypatch.chdir(tmp_path)  # relative paths, as a user types them
    local = plumbob.batch.run(["corpus"], check=True, poses=True, pose_table=True,
                              inertial=("urdf",), units="mm", jobs=2, timeout=60)
    out, poses = str(tmp_path / "dask.csv"), str(tmp_path / "dask_poses.csv")
    status = main(["batch", "corpus", "--out", out, "--pose-table", poses, "--check",
                   "--inertial", "urdf", "--units", "mm", "--scheduler", cluster,
                   "--timeout", "60", "--quiet"])
    assert status == 1  # the corpus holds three broken files
    assert open_writer(out, local.fields).read() == local.rows
    assert open_writer(poses, plumbob.batch.runner.pose_fields()).read() == local.pose_rows
    assert sum(r["status"] == "ok" for r in local.rows) == 10
    started = time.monotonic()
    again = plumbob.batch.run(["corpus"], check=True, poses=True, pose_table=True,
                              inertial=("urdf",), units="mm", scheduler=cluster, out=out,
                              pose_out=poses, resume=True)
    assert again.rows == local.rows and again.summary.computed == 0
    assert time.monotonic() - started < 30
