"""The hostile-input harness's fork server: ``plumbob`` commands without the start-up.

Started once per test process (``python tests/_fork_server.py MEMORY``) by
:func:`hostile.run_limited`, it loads numpy and plumbob — what ``python -m plumbob``
spends most of a short run on — and then, for each request on its standard input
(one JSON line: ``args``, ``cwd``, ``files``), forks a child that is that command: its
standard streams the three ``files``, its address space limited to ``MEMORY`` bytes
above what the server had mapped, Python's own warning filters (the server is a
fresh interpreter, not pytest). It answers with two JSON lines: the child's ``pid``
(so the harness can kill a hang), then its exit ``status`` once the child has ended.

The server is single-threaded — it only reads, forks and waits — so forking it is
safe, unlike forking pytest (which runs threads).
"""

from __future__ import annotations

import io
import json
import os
import resource
import sys
import traceback


def _address_space() -> int:
    with open("/proc/self/statm") as f:
        return int(f.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")


def _be_the_command(request: dict, memory: int) -> int:
    """In the forked child: run ``plumbob *args`` as its own process would."""
    status = 1
    try:
        limit = _address_space() + memory
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
        modes = (os.O_RDONLY, os.O_WRONLY | os.O_TRUNC, os.O_WRONLY | os.O_TRUNC)
        for fd, (name, mode) in enumerate(zip(request["files"], modes)):
            os.dup2(os.open(name, mode), fd)
        sys.stdin = io.TextIOWrapper(io.FileIO(0, "r", closefd=False), encoding="utf-8")
        sys.stdout = io.TextIOWrapper(io.FileIO(1, "w", closefd=False), encoding="utf-8")
        sys.stderr = io.TextIOWrapper(io.FileIO(2, "w", closefd=False), encoding="utf-8",
                                      line_buffering=True)
        if request["cwd"] is not None:
            os.chdir(request["cwd"])
        sys.argv = ["plumbob", *request["args"]]
        from plumbob.__main__ import entry

        try:
            status = entry()
        except SystemExit as done:
            if isinstance(done.code, (int, type(None))):
                status = done.code
            else:  # sys.exit("message"): the message on standard error, status 1
                print(done.code, file=sys.stderr)
                status = 1
        status = 0 if status is None else int(status)
    except BaseException:  # noqa: BLE001 - what an uncaught exception does to a process
        traceback.print_exc()
        status = 1
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except Exception:  # noqa: BLE001, S110 - a stream the command closed
            pass
    return status


def serve(memory: int) -> None:
    import numpy  # noqa: F401 - loaded once here, not in every child
    import scipy.spatial  # noqa: F401
    import shapely  # noqa: F401

    import plumbob.cli  # noqa: F401
    import plumbob.commands  # noqa: F401
    import plumbob.formats  # noqa: F401
    import plumbob.spec.loader  # noqa: F401
    import plumbob.stability  # noqa: F401

    replies = sys.stdout
    for line in sys.stdin:
        request = json.loads(line)
        pid = os.fork()
        if pid == 0:
            os._exit(_be_the_command(request, memory))
        replies.write(json.dumps({"pid": pid}) + "\n")
        replies.flush()
        _, status = os.waitpid(pid, 0)
        replies.write(json.dumps({"status": os.waitstatus_to_exitcode(status)}) + "\n")
        replies.flush()


if __name__ == "__main__":
    serve(int(sys.argv[1]))
