"""Command-line interface: ``dynstiff`` (or ``python -m dynstiff``).

One module per command group (``report``, ``analysis``, ``sweep``, ``simulate``, ``exchange``,
``workspace``), each adding its subcommands to the parser; :mod:`dynstiff.cli.common` holds
what they share, :mod:`dynstiff.cli.options` the options several commands take (one meaning
per flag) and :mod:`dynstiff.cli.console` the warnings and progress bars.
"""

import argparse
import sys

from dynstiff.cli.common import check_outputs
from dynstiff.cli.console import compile_notice, one_line_warnings
from dynstiff.errors import DynstiffError

__all__ = ["build_parser", "main"]


def build_parser():
    """The argument parser of the ``dynstiff`` command."""
    parser = _Parser(
        prog="dynstiff",
        description="Vibration analysis of cable-driven parallel robots with sagging cables.")
    parser.add_argument("--debug", action="store_true",
                        help="show the full traceback of an error")
    from dynstiff._version import __version__
    parser.add_argument("--version", action="version", version=f"dynstiff {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    from dynstiff.cli import analysis, exchange, report, simulate, sweep, workspace
    for group in (report, analysis, sweep, simulate, exchange, workspace):
        group.add_parsers(sub)
    return parser


def main(argv=None):
    """Entry point; returns the process exit code: 0 done (``check``: all passed), 1 a check
    failed, 2 an error, reported on one line (``--debug`` shows the traceback), 130
    interrupted (Ctrl-C; a workspace map says what it saved and how to resume)."""
    parser = build_parser()
    argv = sys.argv[1:] if argv is None else list(argv)
    try:
        args = parser.parse_args(argv)
    except _UsageError as exc:
        from dynstiff.cli.options import renamed_hint
        hint = next((renamed_hint(c, argv) for c in argv if renamed_hint(c, argv)), None)
        sys.stderr.write(f"dynstiff: error: {exc}" + (f"; {hint}" if hint else "")
                         + " (dynstiff -h, or dynstiff COMMAND -h)\n")
        return 2
    try:
        check_outputs(args)
        if args.command != "scenes":
            compile_notice(getattr(args, "quiet", False))
        with one_line_warnings():
            return args.func(args)
    except BrokenPipeError:             # output piped into e.g. `head`: stop quietly
        import os
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except KeyboardInterrupt as exc:    # Ctrl-C: what is saved (dynstiff.errors.Interrupted)
        if args.debug:
            raise
        sys.stderr.write(f"\ndynstiff: {str(exc) or 'interrupted'}\n")
        return 130
    except (DynstiffError, OSError, UnicodeDecodeError, MemoryError) as exc:
        if args.debug:
            raise
        what = f"{type(exc).__name__}: " if isinstance(exc, (UnicodeDecodeError,
                                                             MemoryError)) else ""
        sys.stderr.write(f"dynstiff: error: {what}{exc}\n")
        return 2


class _UsageError(Exception):
    """A command line argparse rejects (one line instead of the usage block)."""

class _Parser(argparse.ArgumentParser):
    def error(self, message):
        raise _UsageError(f"{self.prog}: {message}")


if __name__ == "__main__":
    sys.exit(main())
