"""Compressed and archived inputs (``.zip``, ``.gz``, ``.bz2``, ``.xz``, ``.tar``, ``.tgz``):
the good ones read as the file they hold, the hostile ones — bombs, members reaching
outside, links, several or no readable members, corrupt streams — end in one line and
exit status 2 inside the hostile-input limits (10 s, 1 GiB), writing nothing outside
plumbob's own temporary folder."""

from __future__ import annotations

import bz2
import gzip
import io
import json
import lzma
import os
import tarfile
import zipfile
import zlib

import numpy as np
import pytest
from hostile import assert_bad_input, run_limited
from hypothesis import given, settings
from hypothesis import strategies as st
from test_hostile_meshes import CUBE_F, CUBE_V, binary_stl, obj_text

from plumbob import limits
from plumbob.errors import FormatError, LimitError, PlumbobError
from plumbob.formats import read
from plumbob.formats.archives import _safe_name

CUBE_STL = binary_stl(CUBE_V[CUBE_F])
OPEN_STL = binary_stl(CUBE_V[CUBE_F[:-2]])  # a cube without one side


def zipped(members: dict[str, bytes]) -> bytes:
    packed = io.BytesIO()
    with zipfile.ZipFile(packed, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, data in members.items():
            archive.writestr(name, data)
    return packed.getvalue()


def tarred(members: dict[str, bytes] | list[tuple[str, bytes]],
           links: dict[str, str] | None = None) -> bytes:
    packed = io.BytesIO()
    with tarfile.open(fileobj=packed, mode="w") as archive:
        for name, data in dict(members).items() if isinstance(members, dict) else members:
            member = tarfile.TarInfo(name)
            member.size = len(data)
            archive.addfile(member, io.BytesIO(data))
        for name, target in (links or {}).items():
            member = tarfile.TarInfo(name)
            member.type, member.linkname = tarfile.SYMTYPE, target
            archive.addfile(member)
    return packed.getvalue()


def gzip_of_zeros(size: int) -> bytes:
    """``size`` zero bytes gzip-compressed, built in chunks (never all in memory)."""
    packer = zlib.compressobj(9, zlib.DEFLATED, 31)
    chunk = bytes(1 << 20)
    parts = [packer.compress(chunk) for _ in range(size >> 20)]
    return b"".join(parts) + packer.flush()


GOOD = {
    "cube.stl.gz": gzip.compress(CUBE_STL),
    "cube.stl.bz2": bz2.compress(CUBE_STL),
    "cube.stl.xz": lzma.compress(CUBE_STL),
    "cube.obj.gz": gzip.compress(obj_text(CUBE_F + 1).encode()),
    "cube.zip": zipped({"parts/cube.stl": CUBE_STL, "readme.txt": b"a cube",
                        "__MACOSX/parts/._cube.stl": b"resource fork"}),
    "cube.tar": tarred({"cube.stl": CUBE_STL, "notes.md": b"x"}),
    "cube.tar.gz": gzip.compress(tarred({"kt/cube.stl": CUBE_STL})),
    "cube.tgz": gzip.compress(tarred({"cube.stl": CUBE_STL})),
    "cube.tar.xz": lzma.compress(tarred({"cube.stl": CUBE_STL})),
}


@pytest.mark.parametrize("name", sorted(GOOD))
def test_a_packed_cube_reads_as_the_cube_and_says_which_member(tmp_path, name):
    (tmp_path / name).write_bytes(GOOD[name])
    outcome = run_limited("mass", name, "--json", "--units", "m", cwd=tmp_path)
    assert outcome.status == 0, outcome.stderr
    data = json.loads(outcome.stdout)
    assert data["volume"] == pytest.approx(1.0, rel=1e-12)
    assert np.allclose(data["center_of_mass"], 0.5, rtol=1e-12)
    assert any(n.startswith(("gzip: read", "bzip2: read", "xz: read", "zip: read", "tar"))
               and "cube." in n and "from the archive" in n for n in data["notices"])
    assert list(tmp_path.iterdir()) == [tmp_path / name]  # nothing unpacked beside it


def _write(tmp_path, name: str, data: bytes) -> str:
    (tmp_path / name).write_bytes(data)
    return name


BAD = {
    # decompression bombs: refused while counting, long before the limits of the harness
    "gzip bomb": ("bomb.stl.gz", lambda: gzip_of_zeros(200 << 20), ("possible", "bomb")),
    "bzip2 bomb": ("bomb.stl.bz2", lambda: bz2.compress(bytes(20 << 20)), ("bomb",)),
    "xz bomb": ("bomb.stl.xz", lambda: lzma.compress(bytes(50 << 20)), ("bomb",)),
    "zip bomb": ("bomb.zip", lambda: zipped({"bomb.stl": bytes(100 << 20)}), ("bomb",)),
    "tar.gz bomb": ("bomb.tar.gz", lambda: gzip.compress(tarred({"bomb.stl": bytes(60 << 20)}),
                                                          compresslevel=1), ("bomb",)),
    # members reaching outside
    "zip ../": ("up.zip", lambda: zipped({"../evil.stl": CUBE_STL}), ("outside", "../evil")),
    "zip absolute": ("abs.zip", lambda: zipped({"/tmp/evil.stl": CUBE_STL}), ("outside",)),
    "zip backslash ..": ("bs.zip", lambda: zipped({"..\\evil.stl": CUBE_STL}), ("outside",)),
    "tar ../": ("up.tar", lambda: tarred({"a/../../evil.stl": CUBE_STL}), ("outside",)),
    "tar symlink": ("link.tar", lambda: tarred({}, {"part.stl": "/etc/passwd"}),
                    ("no file plumbob reads",)),
    "control characters": ("esc.zip", lambda: zipped({"a\x1b[31m.stl": CUBE_STL}),
                           ("outside", "\\x1b")),
    # what is inside
    "two meshes": ("two.zip", lambda: zipped({"a.stl": CUBE_STL, "b.obj": b"v 0 0 0\n"}),
                   ("2 files plumbob reads", "a.stl", "b.obj")),
    "nothing readable": ("none.zip", lambda: zipped({"a.txt": b"x", "b.png": b"y"}),
                         ("no file plumbob reads", "a.txt")),
    "empty zip": ("empty.zip", lambda: zipped({}), ("no file plumbob reads",)),
    "archive in archive": ("nested.zip", lambda: zipped({"cube.stl.gz": GOOD["cube.stl.gz"]}),
                           ("no file plumbob reads", "inside archives")),
    "duplicate members": ("dup.tar", lambda: tarred([("a.stl", CUBE_STL), ("a.stl", OPEN_STL)]),
                          ("two members named",)),
    "open mesh inside": ("open.zip", lambda: zipped({"open.stl": OPEN_STL}),
                         ("open.zip:open.stl", "open")),
    "no inner extension": ("part.gz", lambda: gzip.compress(CUBE_STL), ("name it like",)),
    "dots for a name": ("..stl.gz", lambda: gzip.compress(CUBE_STL), ("name it like",)),
    # corrupt streams
    "not gzip": ("junk.stl.gz", lambda: b"this is not gzip at all", ("not a readable gzip",)),
    "truncated gzip": ("cut.stl.gz", lambda: gzip.compress(CUBE_STL)[:-20],
                       ("not a readable gzip",)),
    "not bzip2": ("junk.stl.bz2", lambda: b"BZh9 not really", ("not a readable bzip2",)),
    "not xz": ("junk.stl.xz", lambda: b"\xfd7zXZ\x00 broken", ("not a readable xz",)),
    "not zip": ("junk.zip", lambda: b"PK\x03\x04 broken", ("not a readable zip",)),
    "not tar": ("junk.tgz", lambda: gzip.compress(b"not a tar" * 100), ("not a readable tar",)),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_a_hostile_archive_is_refused_in_one_line(tmp_path, case):
    name, build, phrases = BAD[case]
    inside = tmp_path / "in"
    inside.mkdir()
    _write(inside, name, build())
    outcome = run_limited("mass", name, "--units", "m", cwd=inside)
    assert_bad_input(outcome, name, *phrases)
    assert sorted(p.name for p in tmp_path.rglob("*")) == sorted(["in", name])


def test_the_total_expansion_limit_binds_whatever_the_ratio(tmp_path, monkeypatch):
    path = tmp_path / "cube.stl.gz"
    path.write_bytes(gzip.compress(CUBE_STL))
    monkeypatch.setattr(limits, "MAX_ARCHIVE_BYTES", 500)
    with pytest.raises(LimitError, match="MAX_ARCHIVE_BYTES"):
        read(str(path), units="m")


def test_the_member_count_limit_is_checked_before_unpacking(tmp_path, monkeypatch):
    path = tmp_path / "many.zip"
    path.write_bytes(zipped({f"{i}.txt": b"" for i in range(5)} | {"cube.stl": CUBE_STL}))
    monkeypatch.setattr(limits, "MAX_ARCHIVE_MEMBERS", 3)
    with pytest.raises(LimitError, match="archive members 6"):
        read(str(path), units="m")


def test_an_error_inside_names_the_archive_and_member(tmp_path):
    path = tmp_path / "open.zip"
    path.write_bytes(zipped({"sub/open.stl": OPEN_STL}))
    with pytest.raises(PlumbobError) as caught:
        read(str(path), units="m")
    assert str(caught.value).startswith(f"{path}:sub/open.stl: ")
    assert "plumbob-" not in str(caught.value)  # the temporary folder is never shown


def test_a_gltf_in_a_zip_finds_its_buffer_beside_it(tmp_path):
    trimesh = pytest.importorskip("trimesh")  # the glTF reader is trimesh's
    box = trimesh.creation.box([1.0, 2.0, 3.0])
    files = box.export(file_type="gltf")  # {"model.gltf": ..., "gltf_buffer_0.bin": ...}
    path = tmp_path / "box.zip"
    path.write_bytes(zipped({f"scene/{k}": v for k, v in files.items()}))
    reading = read(str(path), units="m")
    assert reading.body.mass_properties().volume == pytest.approx(6.0, rel=1e-12)
    assert reading.path == str(path)


@settings(max_examples=300, deadline=None)
@given(st.lists(st.sampled_from(["..", ".", "", "a", "b.stl", "/", "\\", "C:", "__MACOSX",
                                 "._x", "é", "\x00", "\n"]), max_size=6).map("/".join))
def test_a_member_name_is_refused_or_lands_inside_the_folder(name):
    # the invariant that keeps unpacking inside plumbob's temporary folder, for any name
    try:
        relative = _safe_name(name, "a.zip")
    except FormatError:
        return
    if relative is not None:
        folder = os.path.realpath("/unpack")
        target = os.path.realpath(os.path.join(folder, relative))
        assert os.path.commonpath([folder, target]) == folder and target != folder
        assert relative.isprintable() and not os.path.isabs(relative)
