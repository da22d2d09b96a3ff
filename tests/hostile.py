"""The hostile-input harness: run the CLI as a user would, inside the limits a bad
file must never break (10 s of wall time, 1 GiB of address space), and check that it
ends in one line and exit status 2 — or in the right answer.

Each hostile case is its own test (``tests/test_hostile_*.py``); a case is a file
the test writes into ``tmp_path`` and the command line that reads it.
"""

from __future__ import annotations

import os
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


class _Server:
    """This test process's fork server (``tests/_fork_server.py``), started on first use."""

    process: subprocess.Popen | None = None

    @classmethod
    def ask(cls, request: dict, timeout: float, command: str) -> int:
        """Run one command; its exit status (a hang is killed and fails the test)."""
        import json
        import select
        import signal

        if cls.process is None or cls.process.poll() is not None:
            env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"), OPENBLAS_NUM_THREADS="1",
                       OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
            env.pop("PLUMBOB_DEBUG", None)
            cls.process = subprocess.Popen(
                [sys.executable, os.path.join(ROOT, "tests", "_fork_server.py"), str(MEMORY_LIMIT)],
                env=env, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, bufsize=1)
        server = cls.process
        server.stdin.write(json.dumps(request) + "\n")
        server.stdin.flush()
        pid = json.loads(server.stdout.readline())["pid"]
        if not select.select([server.stdout], [], [], timeout)[0]:
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:  # it ended at the limit itself: not a hang
                return json.loads(server.stdout.readline())["status"]
            server.stdout.readline()  # the server has waited for it
            raise AssertionError(f"{command} ran over {timeout} s")
        return json.loads(server.stdout.readline())["status"]


def run_limited(*args: str, cwd: str | os.PathLike | None = None,
                timeout: float = TIME_LIMIT, stdin: str | None = None) -> Outcome:
    """``plumbob *args`` in a fresh process with the time and memory limits; a hang
    fails the calling test with the command line.

    The process is forked from a server that has loaded numpy and plumbob already
    (``tests/_fork_server.py``): what ``python -m plumbob`` spends a third of a second
    on, some 300 times in the suite, is done once; the child has the streams, the
    warning filters and the limits of a command started afresh."""
    import tempfile

    with tempfile.TemporaryDirectory(prefix="plumbob-hostile-") as folder:
        files = [os.path.join(folder, name) for name in ("stdin", "stdout", "stderr")]
        for name, text in zip(files, (stdin or "", "", "")):
            with open(name, "w", encoding="utf-8") as f:
                f.write(text)
        status = _Server.ask({"args": [str(a) for a in args],
                              "cwd": None if cwd is None else os.fspath(cwd), "files": files},
                             timeout, "plumbob " + " ".join(map(str, args)))
        out, err = (open(name, encoding="utf-8", errors="replace").read() for name in files[1:])
    return Outcome(status, out, err)


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
