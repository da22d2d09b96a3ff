"""The ``plumbob`` command: argument parsing and dispatch only.

Each subcommand lives in ``plumbob.commands.<name>`` and provides
``register(subparsers)`` (adding its parser, with ``func`` set to its runner)
and a runner ``run(args) -> int``. Runners return the exit status and write
their report to stdout; they never catch :class:`PlumbobError` themselves —
this module turns it into one line on stderr and exit status 2 (1 for a
:class:`~plumbob.errors.TargetNotMet`: a design target the means given cannot reach).
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import os
import re
import sys
import warnings

from .errors import PlumbobError, printable

#: exit status of an unexpected failure: distinct from 1 (a requirement failed), 2 (bad input)
INTERNAL_ERROR = 3

COMMANDS = ("mass", "check", "poses", "lift", "report", "materials", "simulate", "collide", "batch",
            "balance")


def _columns() -> int:
    """The terminal's width as ``shutil.get_terminal_size`` finds it: ``COLUMNS`` if set,
    else standard output's terminal, else 80."""
    try:
        columns = int(os.environ.get("COLUMNS", "0"))
    except ValueError:
        columns = 0
    if columns <= 0:
        try:
            columns = os.get_terminal_size(sys.__stdout__.fileno()).columns
        except (AttributeError, ValueError, OSError):
            columns = 0
    return columns if columns > 0 else 80


class _Parser(argparse.ArgumentParser):
    # No option of plumbob looks like a negative number, so "-1,0,0", "-3.5" or "-inf"
    # after an option is its value (argparse would otherwise take it for an unknown
    # option), for the option's type to accept or refuse.
    _NEGATIVE_VALUE = re.compile(r"^-(\.?\d[\w.,+\-]*|inf(inity)?|nan)$", re.IGNORECASE)

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        if hasattr(self, "_negative_number_matcher"):
            self._negative_number_matcher = self._NEGATIVE_VALUE

    def _get_formatter(self) -> argparse.HelpFormatter:
        # The width argparse would take from shutil.get_terminal_size, found the same
        # way without importing shutil (and with it bz2 and lzma): argparse makes a
        # formatter for every option it adds, so every command paid for that import.
        return self.formatter_class(prog=self.prog, width=_columns() - 2)

    def error(self, message: str) -> None:  # one line, status 2, no usage dump
        choice = re.search(r"invalid choice: '([^']*)' \(choose from (.*)\)$", message)
        if choice:  # a mistyped command or choice: the closest ones first
            import difflib

            options = re.findall(r"'([^']*)'", choice[2])
            close = difflib.get_close_matches(choice[1], options, n=2, cutoff=0.6)
            if close:
                message += f"; did you mean {' or '.join(close)}?"
        self.exit(2, f"plumbob: {printable(message)} (see '{printable(self.prog)} --help')\n")

    def parse_args(self, args=None, namespace=None):  # type: ignore[override]
        """As argparse's, but an unknown option names the subcommand's closest ones
        (``--requre-tilt``: did you mean --require-tilt?) and points at its help."""
        parsed, extras = self.parse_known_args(args, namespace)
        if extras:
            command = self._subcommand(getattr(parsed, "command", None))
            where = command or self
            self.exit(2, f"plumbob: {_unrecognized(extras, where)} "
                      f"(see '{printable(where.prog)} --help')\n")
        return parsed

    def _subcommand(self, name: str | None) -> argparse.ArgumentParser | None:
        for action in self._actions:
            if isinstance(action, argparse._SubParsersAction) and name in action.choices:
                return action.choices[name]
        return None


def _unrecognized(extras: list[str], parser: argparse.ArgumentParser) -> str:
    """The one line for arguments no option takes, with the closest options' names."""
    import difflib

    known = sorted(parser._option_string_actions)
    words = ", ".join(printable(word) for word in extras)
    for word in extras:
        if word.startswith("-"):
            close = difflib.get_close_matches(word.split("=", 1)[0], known, n=2, cutoff=0.6)
            if close:
                return f"unrecognized argument {printable(word)}; did you mean {' or '.join(close)}?"
    return f"unrecognized arguments: {words}"


class _VersionAction(argparse.Action):
    """--version, looked up only when asked for (importlib.metadata is slow to import)."""

    def __init__(self, option_strings, dest, **kwargs) -> None:
        super().__init__(option_strings, dest, nargs=0, help="print the version and exit")

    def __call__(self, parser, namespace, values, option_string=None) -> None:
        # On stdout, where `plumbob --version | ...` looks (argparse's exit writes stderr).
        print(f"plumbob {_version()}")
        parser.exit(0)


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The parser; given a known ``command``, only that subcommand's module is imported."""
    parser = _Parser(prog="plumbob", description="Mass properties, stability and energy from geometry alone.")
    parser.add_argument("--version", action=_VersionAction)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for name in (command,) if command in COMMANDS else COMMANDS:
        try:
            module = importlib.import_module(f".commands.{name}", __package__)
        except ModuleNotFoundError as exc:
            if exc.name != f"{__package__}.commands.{name}":
                raise
            continue
        module.register(sub)
    return parser


def _version() -> str:
    from .version import __version__

    return __version__


class _Escaping:
    """A text stream that shows control characters other than newline as escapes: the
    last line of defence, behind :func:`printable` in the reports, against a name from
    a file reaching the terminal raw (JSON escapes its own control characters)."""

    def __init__(self, stream) -> None:
        self._stream = stream

    def write(self, text: str) -> int:
        # lines that are all printable stay as they are: the lines looked at one by one
        # only when one is not (a 360 kB JSON report of 4,500 lines: 0.85 ms less)
        if not text.isprintable() and not text.replace("\n", "").isprintable():
            text = "\n".join(printable(line) for line in text.split("\n"))
        return self._stream.write(text)

    def __getattr__(self, name: str):
        return getattr(self._stream, name)


@contextlib.contextmanager
def _escaped_output():
    """Standard output escaped while a command runs (standard error carries only
    plumbob's own lines, already :func:`printable`, and the batch progress bar, whose
    control characters are meant)."""
    stream = sys.stdout
    sys.stdout = _Escaping(stream)
    try:
        yield
    finally:
        sys.stdout = stream


@contextlib.contextmanager
def _warnings_caught():
    """No warning text reaches the terminal while a command runs: a ``RuntimeWarning``
    (numpy's or scipy's overflow, invalid value or division by zero: numbers out of double
    precision's range) stops the command as an exception, which :func:`main` turns into
    the one line; any other warning (a library's advice to its programmer) is dropped, as
    what a user must know reaches them as plumbob's own notices."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        warnings.simplefilter("error", RuntimeWarning)
        yield


def _numeric_failure(args: argparse.Namespace, warning: Warning) -> str:
    """The one line for a computation that left double precision's range."""
    path = getattr(args, "path", None) or getattr(args, "spec", None)
    where = f"{printable(path)}: " if isinstance(path, str) else ""
    what = " ".join(str(warning).split())[:200]
    return (f"plumbob: {where}a number left double precision's range ({printable(what)}): the "
            "input's lengths, densities, positions or options are too large or too small to "
            "compute with; check them, or give lengths in other units")


def main(argv: list[str] | None = None, *, blas_on_one_thread: bool = False) -> int:
    """Run the command line ``argv`` (default: this process's arguments); its exit status.
    ``blas_on_one_thread``: BLAS already runs on one thread (the entry point had it start
    so, :func:`plumbob.__main__.blas_starts_with_one_thread`), else it is limited here."""
    argv = sys.argv[1:] if argv is None else list(argv)
    parser = build_parser(argv[0] if argv else None)
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 2
    from .commands._notices import flush_notices

    succeeded = False
    try:
        with _escaped_output(), _warnings_caught():
            if not blas_on_one_thread:  # thin products: BLAS threads would only spin
                from .blockwise import blas_on_one_thread as limit_blas

                limit_blas()
            status = int(args.func(args) or 0)
        succeeded = True
        return status
    except PlumbobError as error:
        print(f"plumbob: {printable(error)}", file=sys.stderr)
        return getattr(error, "exit_status", 2)  # 1 for a target not met (TargetNotMet)
    except RuntimeWarning as warning:
        if os.environ.get("PLUMBOB_DEBUG"):
            raise
        print(_numeric_failure(args, warning), file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("plumbob: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0
    except (RecursionError, MemoryError) as error:  # a limit that should have been checked
        if os.environ.get("PLUMBOB_DEBUG"):
            raise
        what = "nested too deeply to follow" if isinstance(error, RecursionError) else \
            "too large for this machine's memory"
        print(f"plumbob: internal error: the input is {what} ({type(error).__name__}); a limit "
              "in plumbob.limits should have refused it first, so this is a bug in plumbob, "
              "please report it; set PLUMBOB_DEBUG=1 for the traceback", file=sys.stderr)
        return INTERNAL_ERROR
    except Exception as error:  # a bug, never a failed requirement (1) or bad input (2)
        if os.environ.get("PLUMBOB_DEBUG"):
            raise
        detail = printable(" ".join(str(error).split())[:300])
        print(f"plumbob: internal error ({type(error).__name__}: {detail}); this is a bug in "
              "plumbob, please report it; set PLUMBOB_DEBUG=1 for the traceback", file=sys.stderr)
        return INTERNAL_ERROR
    finally:
        flush_notices(succeeded)


if __name__ == "__main__":
    sys.exit(main())
