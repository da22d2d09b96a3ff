"""plumbob batch: rows equal the single-file commands' JSON, failures are rows, the run
resumes, and every output form holds the same table."""

import json
import os
import subprocess
import sys
import time

import pytest
from _batch_corpus import make_corpus
from conftest import ROOT

import plumbob.batch
from plumbob.batch.columns import pose_fields, result_fields
from plumbob.batch.writers import open_writer
from plumbob.cli import main
from plumbob.errors import PlumbobError

OPTIONS = ["--units", "mm", "--material", "aluminium"]


@pytest.fixture(scope="module")
def corpus(tmp_path_factory):
    folder = str(tmp_path_factory.mktemp("corpus"))
    return folder, make_corpus(folder)


@pytest.fixture(scope="module")
def full(corpus):
    """The whole corpus with every kind of column, in this process."""
    folder, _ = corpus
    return plumbob.batch.run([folder], check=True, poses=True, pose_table=True,
                             inertial=("urdf", "mjcf"), units="mm", material="aluminium",
                             jobs=1)


def _json(capsys, *args):
    main([*args, *OPTIONS, "--json"])
    return json.loads(capsys.readouterr().out)


def test_rows_equal_the_single_file_commands(capsys, corpus, full):
    folder, expect = corpus
    assert sorted(os.path.relpath(r["path"], folder) for r in full.rows) == sorted(expect)
    ok = 0
    for row in full.rows:
        if row["status"] != "ok":
            continue
        ok += 1
        mass = _json(capsys, "mass", row["path"])
        for key, value in mass.items():
            if key != "part_properties":
                assert row[key] == value, (row["path"], key)
        check = _json(capsys, "check", row["path"])
        for key in ("verdict", "stands", "margin", "critical_tilt_deg", "critical_direction",
                    "energy_to_topple", "com_height", "down", "support_kind"):
            assert row[key] == check[key], (row["path"], key)
        poses = _json(capsys, "poses", row["path"])
        first = poses["poses"][0]
        assert row["poses"] == len(poses["poses"]) and row["poses_method"] == poses["method"]
        for key in ("probability", "down", "com_height", "critical_tilt_deg", "energy_barrier"):
            assert row[f"pose_{key}"] == first[key], (row["path"], key)
        table = [p for p in full.pose_rows if p["path"] == row["path"]]
        assert [p["probability"] for p in table] == [p["probability"] for p in poses["poses"]]
        assert [p["pose"] for p in table] == list(range(1, len(table) + 1))
        for fmt in ("urdf", "mjcf"):
            main(["mass", row["path"], *OPTIONS, "--format", fmt])
            assert row[f"{fmt}_inertial"] == capsys.readouterr().out.rstrip("\n")
    assert ok == sum(v == "ok" for v in expect.values())


def test_broken_files_are_rows_with_a_reason(corpus, full):
    folder, expect = corpus
    for row in full.rows:
        wanted = expect[os.path.relpath(row["path"], folder)]
        if wanted == "ok":
            assert row["status"] == "ok" and row["reason"] is None
        else:
            assert row["status"] == "failed" and row["error"] == wanted
            assert row["path"] in row["reason"] and "\n" not in row["reason"]
            assert row["mass"] is None
    assert full.summary.statuses == {"ok": 10, "failed": 3}


@pytest.mark.parametrize("suffix", [".csv", ".jsonl", ".parquet"])
def test_every_output_form_holds_the_same_table(tmp_path, corpus, full, suffix):
    if suffix == ".parquet":
        pytest.importorskip("pyarrow", reason="Parquet needs the batch extra")
    folder, _ = corpus
    out, poses = str(tmp_path / f"r{suffix}"), str(tmp_path / f"p{suffix}")
    result = plumbob.batch.run([folder], check=True, poses=True, inertial=("urdf", "mjcf"),
                               units="mm", material="aluminium", jobs=2, out=out,
                               pose_out=poses)
    assert result.rows == full.rows and result.pose_rows == full.pose_rows
    fields = result_fields(plumbob.batch.Options(check=True, poses=True,
                                                 inertial=("urdf", "mjcf")))
    assert open_writer(out, fields).read() == full.rows
    assert open_writer(poses, pose_fields()).read() == full.pose_rows
    assert sorted(os.listdir(tmp_path)) == sorted([f"r{suffix}", f"p{suffix}"])


def test_pandas_and_arrow_tables(full):
    pytest.importorskip("pandas", reason="pandas is in the batch extra")
    frame = full.to_pandas()
    assert len(frame) == len(full.rows) and "center_of_mass_x" in frame.columns
    first = next(k for k, row in enumerate(full.rows) if row["status"] == "ok")
    assert frame["mass"].tolist()[first] == full.rows[first]["mass"]
    assert full.to_arrow(poses=True).num_rows == len(full.pose_rows)


def _rows_in(path):
    with open(path) as handle:
        return [json.loads(line) for line in handle if line.strip()]


def test_resume_keeps_finished_rows_and_redoes_the_rest(tmp_path):
    folder = str(tmp_path / "corpus")
    make_corpus(folder)  # its own: one of its files is touched below
    out = str(tmp_path / "r.jsonl")
    first = plumbob.batch.run([folder], poses=True, jobs=1, out=out, units="mm")
    lines = open(out).read().splitlines(keepends=True)
    # An interrupted run: 5 rows on disk in completion order and half of a sixth.
    with open(out, "w") as handle:
        handle.write("".join(lines[:5]) + lines[5][: len(lines[5]) // 2])
    again = plumbob.batch.run([folder], poses=True, jobs=1, out=out, units="mm", resume=True)
    assert again.rows == first.rows and _rows_in(out) == first.rows
    assert again.summary.resumed == 5 and again.summary.computed == len(first.rows) - 5
    # A file changed since: measured again; a file only touched: kept by content hash.
    changed = os.path.join(folder, "torus_0.stl")
    os.utime(changed, ns=(time.time_ns(), time.time_ns()))
    by_time = plumbob.batch.run([folder], poses=True, jobs=1, out=out, units="mm", resume=True)
    assert by_time.summary.computed == 1 and by_time.rows != first.rows  # new mtime
    by_hash = plumbob.batch.run([folder], poses=True, jobs=1, out=out, units="mm", resume=True,
                                resume_by="hash")
    assert by_hash.summary.computed == 0


def test_resume_refuses_a_table_of_other_options(tmp_path, corpus):
    folder, _ = corpus
    out = str(tmp_path / "r.csv")
    plumbob.batch.run([os.path.join(folder, "stepped_cylinder.toml")], jobs=1, out=out)
    with pytest.raises(PlumbobError, match="other options"):
        plumbob.batch.run([folder], check=True, jobs=1, out=out, resume=True)


def _cli(*args, **kwargs):
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"))
    return subprocess.Popen([sys.executable, "-m", "plumbob.cli", "batch", *args], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kwargs)


def test_killed_run_resumes_to_the_same_table(tmp_path, corpus, full):
    folder, _ = corpus
    out = str(tmp_path / "r.csv")
    args = [folder, "--out", out, "--check", "--poses", "--inertial", "urdf,mjcf", *OPTIONS]
    run = _cli(*args, "--jobs", "1", "--timeout", "60")
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and run.poll() is None:
        if os.path.exists(out) and len(open(out).read().splitlines()) > 4:
            break
        time.sleep(0.01)
    run.kill()
    run.wait()
    done = open_writer(out, full.fields).read()
    assert 0 < len(done)
    finished = _cli(*args, "--resume")
    stdout, stderr = finished.communicate(timeout=300)
    assert finished.returncode == 1, stderr  # three broken files
    assert stdout == "" and "3 failed" in stderr
    assert open_writer(out, full.fields).read() == full.rows
    if len(done) < len(full.rows):
        assert f"{len(done)} of them done before, kept" in stderr


#: a valid spec that takes tens of seconds: two overlapping spheres faceted at the
#: finest segment count plumbob allows (plumbob.limits.MAX_SEGMENTS)
SLOW_SPEC = """[shape]
segments = 2048
[[part]]
type = "sphere"
radius = 1
[[part]]
type = "sphere"
radius = 1
at = [0.5, 0, 0]
"""


def test_a_file_over_the_time_limit_is_a_row(tmp_path, corpus):
    folder, _ = corpus
    slow = tmp_path / "slow.toml"
    slow.write_text(SLOW_SPEC)
    good = os.path.join(folder, "stepped_cylinder.toml")
    result = plumbob.batch.run([str(slow), good], jobs=1, timeout=3)
    assert [r["status"] for r in result.rows] == ["timeout", "ok"]
    assert "time limit of 3 s" in result.rows[0]["reason"]


def test_a_pipe_is_a_failed_row_at_once(tmp_path, corpus):
    folder, _ = corpus
    fifo = str(tmp_path / "hangs.stl")
    os.mkfifo(fifo)  # reading it would block for ever: it is refused before any read
    good = os.path.join(folder, "stepped_cylinder.toml")
    result = plumbob.batch.run([fifo, good], jobs=1, timeout=5)
    assert [r["status"] for r in result.rows] == ["failed", "ok"]
    assert "not a regular file" in result.rows[0]["reason"]


def test_inputs_folders_globs_and_names(tmp_path, corpus):
    from plumbob.batch.inputs import discover

    folder, expect = corpus
    every = discover([folder])
    assert len(every) == len(expect) and not any(p.endswith(".txt") for p in every)
    tori = discover([os.path.join(folder, "**", "torus_*.stl"), os.path.join(folder, "sub")])
    assert len(tori) == 8  # the folder's files were already named by the glob
    named = discover([os.path.join(folder, "notes.txt")])  # named files are kept: a failed row
    assert named == [os.path.join(folder, "notes.txt")]
    with pytest.raises(PlumbobError, match="holds no file"):
        discover([os.path.join(folder, "*.step")])


def test_missing_extra_is_one_line_naming_it(monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "pyarrow", None)
    monkeypatch.setitem(sys.modules, "distributed", None)
    block = os.path.join(ROOT, "shapes", "block.toml")
    with pytest.raises(PlumbobError, match=r"plumbob\[batch\]"):
        plumbob.batch.run([block], out=str(tmp_path / "r.parquet"))
    with pytest.raises(PlumbobError, match=r"plumbob\[batch\]") as error:
        plumbob.batch.run([block], scheduler="tcp://127.0.0.1:1")
    assert "\n" not in str(error.value)


def test_cli_writes_the_table_quietly_off_a_terminal(tmp_path, capsys):
    out = str(tmp_path / "r.jsonl")
    block = os.path.join(ROOT, "shapes", "block.toml")
    assert main(["batch", block, "--out", out, "--check", "--require-tilt", "10"]) == 0
    captured = capsys.readouterr()
    assert captured.out == "" and "1 ok" in captured.err and "\r" not in captured.err
    (row,) = _rows_in(out)
    assert row["passes"] is True and row["required_tilt_deg"] == 10


def test_parquet_columns_have_real_types(tmp_path, corpus):
    """Read back with pyarrow alone: poses an integer, exact and stands booleans, the
    notes a list of text (a CSV keeps them as JSON text)."""
    pa = pytest.importorskip("pyarrow", reason="Parquet needs the batch extra")
    import pyarrow.parquet as pq

    folder, _ = corpus
    out = str(tmp_path / "r.parquet")
    plumbob.batch.run([folder], check=True, poses=True, units="mm", jobs=1, out=out)
    schema = pq.read_schema(out)
    assert schema.field("poses").type == pa.int64()
    assert schema.field("exact").type == pa.bool_() and schema.field("stands").type == pa.bool_()
    assert schema.field("notes").type == pa.list_(pa.string())
    notes = [n for n in pq.read_table(out).column("notes").to_pylist() if n]
    assert notes and all(isinstance(n, list) and all(isinstance(x, str) for x in n)
                         for n in notes)


def test_a_row_sweeps_the_rocker_of_its_first_pose_only(tmp_path):
    """A row shows the first pose only, so only its rocker is swept
    (``resting_poses(critical_tilts=1)``): the row is the one the full poses give, and
    the pose table still gets every rocking pose's critical tilt."""
    import math

    import numpy as np
    import trimesh

    from plumbob.batch.options import Options
    from plumbob.batch.rows import process_file
    from plumbob.bodies.solid import MeshSolid
    from plumbob.stability import resting_poses

    mesh = trimesh.creation.icosphere(subdivisions=2)  # four rocking poses
    mesh.apply_scale((3.0, 2.2, 1.3))
    mesh.vertices[:, 0] += 0.1 * mesh.vertices[:, 1] ** 2
    body = MeshSolid(np.asarray(mesh.triangles, dtype=float))
    every, first = resting_poses(body), resting_poses(body, critical_tilts=1)
    assert [p.kind for p in every] == ["rocking"] * 4
    assert first[0].critical_tilt_deg == every[0].critical_tilt_deg > 0
    assert all(math.isnan(p.critical_tilt_deg) for p in first.poses[1:])
    for a, b in zip(every, first):
        assert a.probability == b.probability and np.array_equal(a.down, b.down)
        assert a.energy_barrier == b.energy_barrier and a.com_height == b.com_height
    path = str(tmp_path / "egg.stl")
    mesh.export(path)
    row = process_file(path, Options(poses=True))
    table = process_file(path, Options(pose_table=True))
    assert row.row == table.row and row.row["pose_critical_tilt_deg"] > 0
    assert len(table.pose_rows) == 4
    assert all(r["critical_tilt_deg"] > 0 for r in table.pose_rows)


@pytest.mark.parametrize("suffix", [".csv", ".jsonl"])
def test_the_final_table_reuses_the_texts_written_and_formats_other_rows(tmp_path, full,
                                                                         suffix):
    """The end of a run writes each row's text as appended (no second formatting, the one
    part of a run no worker shares); a row object it never wrote, even an equal copy, is
    formatted afresh. The file equals one written from scratch in input order."""
    rows, fields = full.rows, full.fields
    out, fresh = str(tmp_path / f"a{suffix}"), str(tmp_path / f"b{suffix}")
    writer = open_writer(out, fields)
    writer.start(rows[:2])  # as kept by --resume
    for row in reversed(rows[2:-1]):  # as workers finish, out of order
        writer.append(row)
    copy = dict(rows[-1])
    writer.append(rows[-1])
    writer.finish([*rows[:-1], copy])
    scratch = open_writer(fresh, fields)
    scratch.start(rows)
    scratch.close()
    with open(out, encoding="utf-8") as a, open(fresh, encoding="utf-8") as b:
        assert a.read() == b.read()
    assert open_writer(out, fields).read() == rows


def test_a_pool_measures_the_largest_files_first_and_tables_them_in_input_order(corpus,
                                                                                full):
    """Rows come back as they finish, so the pool sends the largest files first (no
    worker left alone on a big part at the end); the table is in input order still, and
    the same as one job's."""
    from plumbob.batch.pool import largest_first

    folder, _ = corpus
    names = sorted(os.listdir(folder))
    tasks = [(k, os.path.join(folder, n), n) for k, n in enumerate(names)]
    tasks.append((len(tasks), os.path.join(folder, "no such file.stl"), "gone"))
    ordered = largest_first(tasks)
    sizes = [os.stat(t[1]).st_size for t in ordered[:-1]]
    assert sizes == sorted(sizes, reverse=True) and ordered[-1][2] == "gone"
    equal = [[t[0] for t in ordered[:-1] if os.stat(t[1]).st_size == s] for s in set(sizes)]
    assert all(group == sorted(group) for group in equal)  # input order among equals
    pooled = plumbob.batch.run([folder], check=True, poses=True, pose_table=True,
                               inertial=("urdf", "mjcf"), units="mm", material="aluminium",
                               jobs=2, timeout=60)
    assert [r["path"] for r in pooled.rows] == [r["path"] for r in full.rows]
    assert pooled.rows == full.rows and pooled.pose_rows == full.pose_rows
