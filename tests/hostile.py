"""The hostile-input harness: run the CLI as a user would, inside the limits a bad
file must never break (10 s of wall time, 1 GiB of address space), and check that it
ends in one line and exit status 2 — or in the right answer.

Each hostile case is its own test (``tests/test_hostile_*.py``); a case is a file
the test writes into ``tmp_path`` and the command line that reads it.
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
from dataclasses import dataclass

from conftest import ROOT

#: What a bad input may cost before the harness calls it a hang or a blow-up.
TIME_LIMIT = 10.0
MEMORY_LIMIT = 1024**3


@dataclass(frozen=True)
class Outcome:
    """How one command ended: exit status, standard output and standard error."""

    status: int
    stdout: str
    stderr: str

    @property
    def lines(self) -> list[str]:
        return [line for line in self.stderr.splitlines() if line.strip()]


def _limit_memory() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))


def run_limited(*args: str, cwd: str | os.PathLike | None = None,
                timeout: float = TIME_LIMIT, stdin: str | None = None) -> Outcome:
    """``plumbob *args`` in a fresh process with the time and memory limits; a hang
    fails the calling test with the command line."""
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"), OPENBLAS_NUM_THREADS="1",
               OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    env.pop("PLUMBOB_DEBUG", None)
    try:
        done = subprocess.run([sys.executable, "-m", "plumbob", *map(str, args)], cwd=cwd,
                              env=env, capture_output=True, text=True, timeout=timeout,
                              input=stdin, preexec_fn=_limit_memory)
    except subprocess.TimeoutExpired:
        raise AssertionError(f"plumbob {' '.join(map(str, args))} ran over {timeout} s") from None
    return Outcome(done.returncode, done.stdout, done.stderr)


def assert_bad_input(outcome: Outcome, *phrases: str) -> str:
    """The command refused its input as a user expects: exit status 2, one line on
    standard error starting ``plumbob:``, no traceback, nothing on standard output,
    naming each of ``phrases`` (case-insensitive). Returns the line."""
    assert outcome.status == 2, (outcome.status, outcome.stderr[-2000:])
    assert len(outcome.lines) == 1, outcome.stderr[-2000:]
    line = outcome.lines[0]
    assert line.startswith("plumbob: "), line
    assert "Traceback" not in outcome.stderr
    for phrase in phrases:
        assert phrase.lower() in line.lower(), (phrase, line)
    return line


def run_in_process(capsys, *args: str, cwd: str | os.PathLike | None = None) -> Outcome:
    """``plumbob *args`` through :func:`plumbob.cli.main` in this process: the same exit
    status and output as the command, without a process start-up (for corpora of many
    files whose limits :func:`run_limited` already covers case by case)."""
    from plumbob.cli import main

    capsys.readouterr()
    here = os.getcwd()
    try:
        if cwd is not None:
            os.chdir(cwd)
        status = main([str(arg) for arg in args])
    finally:
        os.chdir(here)
    out, err = capsys.readouterr()
    return Outcome(status, out, err)
