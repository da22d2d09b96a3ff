"""What a command tells the user it assumed, on stderr, once it has succeeded.

No default that changes an answer is silent: the reader's notices (an assumed unit,
repairs) and what was assumed where neither the file nor the options said (a density
of 1, the up axis) go to stderr, one line each, whatever the output — text, JSON or an
inertial block. They are held until the command succeeds, so a refusal stays one line.
"""

from __future__ import annotations

import argparse
import sys

from ..errors import printable
from ..reading import Reading

__all__ = ["ORIENTED_COMMANDS", "default_down", "flush_notices", "oriented", "print_notices"]

#: notices waiting for the command to succeed (:func:`flush_notices`): a command that
#: fails says so in one line, never after notes about a reading it could not use
_PENDING: list[str] = []


def print_notices(reading: Reading, stream=None, *, oriented: bool = False) -> None:
    """Notices go to stderr so stdout stays one JSON object (or one inertial block): the
    reader's, then what was assumed (:meth:`~plumbob.reading.Reading.assumed`: the
    density; with ``oriented``, the up axis), one line each, whatever the output. Held
    until the command succeeds (:func:`flush_notices`) unless a ``stream`` is given."""
    lines = [f"plumbob: note: {printable(notice)}" for notice in reading.notices + tuple(
        a for a in reading.assumed(oriented) if a not in reading.notices)]
    if stream is not None:
        for line in lines:
            print(line, file=stream)
        return
    _PENDING.extend(line for line in lines if line not in _PENDING)


def flush_notices(succeeded: bool) -> None:
    """Print the held notices on stderr when the command ``succeeded``; forget them either
    way (the command line calls it once a command ends)."""
    lines, _PENDING[:] = list(_PENDING), []
    if succeeded and lines:
        print("\n".join(lines), file=sys.stderr)


def default_down(args: argparse.Namespace, reading: Reading):
    """Gravity's direction: ``--down``, else against the file's up axis (glTF: −y), else
    None (the stability code's default, −z)."""
    down = getattr(args, "down", None)
    return down if down is not None else reading.default_down()


#: the commands that rest a body on the ground (the others need no up axis)
ORIENTED_COMMANDS = ("check", "balance", "report")


def oriented(args: argparse.Namespace) -> bool:
    """Whether the command rests the body in a direction the user did not give."""
    return (getattr(args, "command", None) in ORIENTED_COMMANDS
            and all(getattr(args, k, None) is None for k in ("down", "pose", "target_pose")))
