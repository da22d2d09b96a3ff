"""Every file of tests/bad_inputs gives its specific error (or its fix and notice).

The corpus is written by ``tests/bad_inputs/make_bad_inputs.py``; the tests read a
fresh copy (generated once per session) and check that the copy in the
repository matches the generator.
"""

import os
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "bad_inputs"))
from make_bad_inputs import CASES, contents, generate  # noqa: E402

from plumbob import cli, errors  # noqa: E402
from plumbob.errors import InputFileError, PlumbobError  # noqa: E402
from plumbob.formats import read  # noqa: E402


@pytest.fixture(scope="session")
def corpus(tmp_path_factory) -> str:
    directory = str(tmp_path_factory.mktemp("bad_inputs"))
    generate(directory)
    return directory


def _id(case) -> str:
    return case.name + ("+repair" if case.read.get("repair") else "")


@pytest.mark.parametrize("case", CASES, ids=_id)
def test_case_gives_its_error_or_notice(corpus, case):
    path = os.path.join(corpus, case.name)
    if case.error is not None:
        with pytest.raises(PlumbobError) as info:
            read(path, **case.read)
        error = info.value
        assert type(error) is getattr(errors, case.error)
        assert case.message in str(error)
        assert str(error).startswith(path + ": ")  # the message names the file
        assert "\n" not in str(error)
    else:
        reading = read(path, **case.read)
        assert any(case.message in notice for notice in reading.notices), reading.notices
        props = reading.body.mass_properties()
        assert props.measure == pytest.approx(case.measure, rel=1e-6)


ERRORS = [c for c in CASES if c.error is not None and not c.read]


@pytest.mark.parametrize("case", ERRORS, ids=_id)
def test_cli_prints_one_line_and_exits_2(corpus, case, capsys):
    status = cli.main(["mass", os.path.join(corpus, case.name)])
    out, err = capsys.readouterr()
    assert status == 2
    assert out == ""
    assert err.count("\n") == 1 and err.startswith("plumbob: ")
    assert case.message in err
    assert "Traceback" not in err


def test_unreadable_file(tmp_path, monkeypatch):
    path = tmp_path / "locked.stl"
    path.write_bytes(b"solid x\nendsolid x\n")

    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr("plumbob.formats.stl.open", refuse, raising=False)
    with pytest.raises(InputFileError, match="cannot be read: Permission denied"):
        read(str(path))


def test_checked_in_corpus_matches_the_generator():
    folder = os.path.join(HERE, "bad_inputs")
    for name, data in contents().items():
        path = os.path.join(folder, name)
        if data is None:
            assert os.path.isdir(path), name
            continue
        with open(path, "rb") as f:
            assert f.read() == data, f"{name} is stale: run tests/bad_inputs/make_bad_inputs.py"
    assert not os.path.exists(os.path.join(folder, "missing.stl"))


def test_every_case_has_a_file_or_is_meant_to_be_missing():
    made = set(contents())
    for case in CASES:
        assert case.name in made or case.name == "missing.stl", case.name
