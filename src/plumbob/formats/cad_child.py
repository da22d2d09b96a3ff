"""OpenCASCADE's child process, started once and kept for the reads that follow.

A STEP, IGES or BREP file is read in a child process (:mod:`.step_worker`) so that a
crash of the C++ library costs one line, never this process. Starting that child
costs more than most reads (Python, then OpenCASCADE's libraries: about a second),
so one child serves every read of this process in turn: each request is one line on
its standard input (``[path, out, deviation]`` as JSON), each answer the line
``done`` once the result is in ``out``. A child that dies (a crash, its memory
limit) or runs over the time limit is gone with that one read; the next read starts
a fresh one. The child ends when this process closes its standard input (at exit,
or when this process dies), and is replaced after :data:`RECYCLE` reads so memory
OpenCASCADE keeps does not grow without bound.

Where ``select`` cannot wait on a pipe (Windows), each read starts its own child.
"""

from __future__ import annotations

import atexit
import json
import os
import select
import subprocess
import tempfile
import threading
from collections.abc import Callable

__all__ = ["ChildFailed", "ChildTimedOut", "read_in_child"]

#: reads one child serves before a fresh one takes over
RECYCLE = 100


class ChildFailed(Exception):
    """The child ended with ``status`` (a negative status: killed by that signal) without
    answering: ``how`` it ended, and the last line of its standard error (may be empty)."""

    def __init__(self, status: int, errors: bytes) -> None:
        lines = errors.decode("utf-8", "replace").strip().splitlines()
        self.how = f"signal {-status}" if status < 0 else f"exit status {status}"
        self.last_line = lines[-1] if lines else ""
        super().__init__(self.how, self.last_line)


class ChildTimedOut(Exception):
    """The child took longer than the time allowed (it has been stopped)."""


class _Child:
    """One running child, its pipes and the file its standard error goes to."""

    def __init__(self, argv: list[str], env: dict, limit: Callable[[], None] | None) -> None:
        self.argv, self.env, self.owner = argv, env, os.getpid()
        self.errors = tempfile.TemporaryFile()
        self.process = subprocess.Popen(argv, env=env, stdin=subprocess.PIPE,
                                        stdout=subprocess.PIPE, stderr=self.errors,
                                        preexec_fn=limit, text=True, bufsize=1)
        self.reads = 0

    def ask(self, request: list, timeout: float) -> None:
        """Send one request and wait for its answer (see the module's docstring)."""
        self.reads += 1
        try:
            self.process.stdin.write(json.dumps(request) + "\n")
            self.process.stdin.flush()
        except (BrokenPipeError, OSError):
            pass  # it died before reading: the answer below says how
        ready, _, _ = select.select([self.process.stdout], [], [], timeout)
        if not ready:
            self.close()
            raise ChildTimedOut
        if self.process.stdout.readline().strip() != "done":
            status = self.process.wait()
            self.errors.seek(0)
            errors = self.errors.read()
            self.close()
            raise ChildFailed(status, errors)

    def close(self) -> None:
        """Stop the child (closing its input ends it; a hung one is killed)."""
        try:
            self.process.stdin.close()
        except OSError:
            pass
        try:
            self.process.wait(timeout=2)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
        self.process.stdout.close()
        self.errors.close()


_lock = threading.Lock()
_child: _Child | None = None


def _close_child() -> None:
    global _child
    if _child is not None and _child.owner == os.getpid():
        _child.close()
    _child = None


atexit.register(_close_child)


def read_in_child(argv: list[str], env: dict, request: list, *, timeout: float,
                  limit: Callable[[], None] | None = None) -> None:
    """Have the child started by ``argv`` (with ``env``; ``limit`` run in it before it
    starts: its memory limit) answer ``request``; :class:`ChildTimedOut` after
    ``timeout`` s, :class:`ChildFailed` when it dies. Reads are served one at a time."""
    global _child
    if os.name != "posix":
        _one_shot(argv + [str(part) for part in request], env, timeout, limit)
        return
    with _lock:
        if _child is not None and _child.owner != os.getpid():
            _child = None  # a forked copy of the process that started it: not ours to use
        argv = argv + ["--serve"]
        if _child is not None and (_child.process.poll() is not None or _child.reads >= RECYCLE
                                   or (_child.argv, _child.env) != (argv, env)):
            _close_child()
        if _child is None:
            _child = _Child(argv, env, limit)
        child = _child
        try:
            child.ask(request, timeout)
        except (ChildFailed, ChildTimedOut):
            _child = None  # ask() has closed it
            raise


def _one_shot(argv: list[str], env: dict, timeout: float,
              limit: Callable[[], None] | None) -> None:
    """One child for one read (platforms without ``select`` on pipes)."""
    try:
        done = subprocess.run(argv, env=env, stdin=subprocess.DEVNULL,
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                              timeout=timeout, preexec_fn=limit)
    except subprocess.TimeoutExpired:
        raise ChildTimedOut from None
    if done.returncode != 0:
        raise ChildFailed(done.returncode, done.stderr)
