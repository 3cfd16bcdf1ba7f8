"""``chainfountain check`` and ``chainfountain schema``: validate and document level files."""

from __future__ import annotations

import argparse

from chainfountain import atomic
from chainfountain.commands.args import path_arg, writable_file
from chainfountain.errors import OutputError


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "check",
        help="validate level files",
        description="Validate level TOML files; exits non-zero on the first bad one.",
        allow_abbrev=False,
    )
    p.add_argument("levels", nargs="+", metavar="LEVEL", help="level .toml files")
    p.set_defaults(func=run_check)

    s = sub.add_parser(
        "schema",
        help="print (or write) the level-file reference",
        description="Print the level schema as Markdown (the source of docs/levels.md).",
        allow_abbrev=False,
    )
    s.add_argument("--out", type=path_arg("a Markdown file"),
                   help="write to this file instead of printing")
    s.set_defaults(func=run_schema)


def run_check(args: argparse.Namespace) -> int:
    from chainfountain.level import io

    for path in args.levels:
        level = io.load(path)  # LevelError propagates as one line, exit 2
        print(f"{path}: ok ({level.sim.kind}: {level.meta.name})")
    return 0


def run_schema(args: argparse.Namespace) -> int:
    from chainfountain.level import io

    text = io.schema_markdown()
    if args.out is not None:
        writable_file(args.out, "--out")
        try:
            atomic.write_text(args.out, text)
        except OSError as exc:
            raise OutputError(f"argument --out: cannot write {str(args.out)!r} "
                              f"({exc.strerror or exc})") from None
        print(f"wrote {args.out}")
    else:
        print(text, end="")
    return 0
