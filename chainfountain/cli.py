"""The ``chainfountain`` command line (also ``python -m chainfountain``)."""

from __future__ import annotations

import os
import sys
from collections.abc import Sequence

from chainfountain import __version__
from chainfountain.commands import (
    converge,
    design,
    figures,
    levels,
    play,
    run,
    sweep,
    theory,
)
from chainfountain.commands.args import OneLineParser
from chainfountain.errors import OutputError, UserError

_COMMANDS = [play, theory, design, levels, run, converge, sweep, figures]


def build_parser() -> OneLineParser:
    parser = OneLineParser(
        prog="chainfountain",
        description="Chain fountain simulator after Mayet & Pfeiffer. "
        "Without a command it shows the default fountain.",
        allow_abbrev=False,
    )
    parser.add_argument("--version", action="version", version=f"chainfountain {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=OneLineParser)
    for mod in _COMMANDS:
        mod.add_parser(sub)
    return parser


def default_job() -> int:
    """What ``chainfountain`` with no command does: the window on the default level.

    Without a display it says so and runs the default level headless.
    """
    from chainfountain.app.launch import run_default

    return run_default()


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit status."""
    args_list = list(sys.argv[1:] if argv is None else argv)
    parser = build_parser()
    args, extra = parser.parse_known_args(args_list)
    if extra:  # FIELD=VALUE after an option (run LEVEL --duration 3 feed.speed=6)
        if getattr(args, "command", None) == "run" and all(
                "=" in a and not a.startswith("-") for a in extra):
            args.overrides += extra
        else:
            parser.error(f"unrecognized arguments: {' '.join(extra)}")
    try:
        if args.command is None:
            return default_job()
        return int(args.func(args) or 0)
    except OutputError as exc:
        print(f"chainfountain: error: {exc}", file=sys.stderr)
        return 4
    except UserError as exc:
        print(f"chainfountain: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("chainfountain: interrupted", file=sys.stderr)
        return 130


def console_main() -> None:  # pragma: no cover - thin wrapper
    try:
        status = main()
        sys.stdout.flush()
    except BrokenPipeError:
        # the reader went away (``chainfountain levels | head``): stop quietly, as a Unix
        # tool does, and keep Python from reporting the pipe again at exit
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        status = 0
    sys.exit(status)
