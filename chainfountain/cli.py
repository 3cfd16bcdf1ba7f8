"""The ``chainfountain`` command line (also ``python -m chainfountain``)."""

from __future__ import annotations

import sys
from collections.abc import Sequence

from chainfountain import __version__
from chainfountain.commands import figures, levels, run, theory
from chainfountain.commands.args import OneLineParser
from chainfountain.errors import UserError

_COMMANDS = [theory, levels, run, figures]


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
    """What ``chainfountain`` with no command does: the paper's example fountain."""
    return main(["theory", "--l", "0.33", "--h", "0.28", "--H", "2", "--k", "0.377"])


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit status."""
    args_list = list(sys.argv[1:] if argv is None else argv)
    parser = build_parser()
    args = parser.parse_args(args_list)
    try:
        if args.command is None:
            return default_job()
        return int(args.func(args) or 0)
    except UserError as exc:
        print(f"chainfountain: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("chainfountain: interrupted", file=sys.stderr)
        return 130


def console_main() -> None:  # pragma: no cover - thin wrapper
    sys.exit(main())
