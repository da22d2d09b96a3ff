"""The ``plumbob`` command: argument parsing and dispatch only.

Each subcommand lives in ``plumbob.commands.<name>`` and provides
``register(subparsers)`` (adding its parser, with ``func`` set to its runner)
and a runner ``run(args) -> int``. Runners return the exit status and write
their report to stdout; they never catch :class:`PlumbobError` themselves —
this module turns it into one line on stderr and exit status 2.
"""

from __future__ import annotations

import argparse
import importlib
import sys

from .errors import PlumbobError

COMMANDS = ("mass", "check", "poses", "lift", "materials", "simulate", "collide")


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # one line, status 2, no usage dump
        self.exit(2, f"plumbob: {message} (see 'plumbob {self.prog.split()[-1]} --help')\n")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="plumbob", description="Mass properties, stability and energy from geometry alone."
    )
    parser.add_argument("--version", action="version", version=f"plumbob {_version()}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for name in COMMANDS:
        try:
            module = importlib.import_module(f".commands.{name}", __package__)
        except ModuleNotFoundError as exc:
            if exc.name != f"{__package__}.commands.{name}":
                raise
            continue
        module.register(sub)
    return parser


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("plumbob")
    except PackageNotFoundError:
        return "unknown"


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 2
    try:
        return int(args.func(args) or 0)
    except PlumbobError as error:
        print(f"plumbob: {error}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("plumbob: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0


if __name__ == "__main__":
    sys.exit(main())
