"""The ``>>>`` examples in README.md and docs/ run as doctests, from the repository's
root (their paths, like shapes/spring_pair.toml, are the console examples' paths)."""

import doctest
import os

import pytest
from conftest import ROOT

DOCS = os.path.join(ROOT, "docs")
WITH_EXAMPLES = sorted(
    name for name in os.listdir(DOCS)
    if name.endswith(".md") and ">>> " in open(os.path.join(DOCS, name), encoding="utf-8").read()
) + [os.path.join("..", "README.md")]


def test_simulate_md_has_examples():
    assert "simulate.md" in WITH_EXAMPLES
    assert ">>> " in open(os.path.join(ROOT, "README.md"), encoding="utf-8").read()


@pytest.mark.parametrize("name", WITH_EXAMPLES)
def test_doc_examples(name, monkeypatch):
    monkeypatch.chdir(ROOT)
    result = doctest.testfile(os.path.join(DOCS, name), module_relative=False,
                              optionflags=doctest.ELLIPSIS, verbose=False, report=True)
    assert result.attempted > 0
    assert result.failed == 0, f"{result.failed} example(s) of docs/{name} failed (see above)"
