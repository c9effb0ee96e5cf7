"""The ``jackpy`` command.

Subcommands live one per module in :mod:`jackpy.commands`; each module defines
``register(subparsers)`` which adds its parser and sets ``func`` (a callable taking the parsed
namespace and returning an exit code). A :class:`~jackpy.errors.JackpyError` raised by a subcommand is
printed as one line on stderr and turns into its ``exit_code``; no traceback reaches the user.
"""

from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys
from collections.abc import Sequence

from jackpy import __version__
from jackpy.errors import JackpyError


def build_parser() -> argparse.ArgumentParser:
    """Build the argument parser with every subcommand found in :mod:`jackpy.commands`."""
    parser = argparse.ArgumentParser(
        prog="jackpy",
        description="jackpy: pose, analyse and drive articulated human figures.",
    )
    parser.add_argument("--version", action="version", version=f"jackpy {__version__}")
    parser.add_argument("--flock", metavar="PORT", default=None,
                        help="start the workbench connected to a Flock of Birds on PORT or URL")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    import jackpy.commands as commands_pkg

    for info in sorted(pkgutil.iter_modules(commands_pkg.__path__), key=lambda m: m.name):
        module = importlib.import_module(f"jackpy.commands.{info.name}")
        register = getattr(module, "register", None)
        if register is not None:
            register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``jackpy`` console script; returns the process exit code."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        args.command = "open"
        args.scene = None
        args.func = _default_command(parser)
    try:
        return int(args.func(args) or 0)
    except JackpyError as exc:
        print(f"jackpy: error: {exc}", file=sys.stderr)
        return exc.exit_code
    except KeyboardInterrupt:
        print("jackpy: interrupted", file=sys.stderr)
        return 130
    except (OSError, ValueError) as exc:  # a user's bad path or value: one line, no traceback
        print(f"jackpy: error: {exc}", file=sys.stderr)
        return 1


def _default_command(parser: argparse.ArgumentParser):
    """With no subcommand: open the workbench (``open``) if available, else print help."""
    sub_actions = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    if sub_actions and "open" in sub_actions[0].choices:
        return sub_actions[0].choices["open"].get_default("func")

    def _help(_args: argparse.Namespace) -> int:
        parser.print_help()
        return 0

    return _help


if __name__ == "__main__":
    sys.exit(main())
