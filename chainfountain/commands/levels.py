"""``chainfountain levels``, ``chainfountain check`` and ``chainfountain schema``: list,
validate and document level files."""

from __future__ import annotations

import argparse
import sys

from chainfountain import atomic
from chainfountain.commands.args import path_arg, writable_file
from chainfountain.errors import OutputError, UserError


def add_parser(sub: argparse._SubParsersAction) -> None:
    lv = sub.add_parser(
        "levels",
        help="list the levels this installation has (shipped and the user's)",
        description="List every level a name on the command line finds: the ones shipped "
        "inside the package, then the user's ($CHAINFOUNTAIN_HOME/levels, or "
        "~/.local/share/chainfountain/levels), each with its kind and file.",
        allow_abbrev=False,
    )
    lv.set_defaults(func=run_levels)
    p = sub.add_parser(
        "check",
        help="validate level files",
        description="Validate level TOML files: one line for each, 'ok' or what is wrong; "
        "exits 2 when any is bad.",
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


def run_levels(args: argparse.Namespace) -> int:
    from chainfountain.level import io, library

    found = library.available()
    if not found:
        raise UserError(f"no levels found in {library.shipped_dir()} or {library.user_dir()}; "
                        "the installation is broken: reinstall chainfountain")
    width = max(len(p.stem) for p in found)
    for path in found:
        try:
            level = io.load(path)
            what = level.sim.kind
        except UserError as exc:
            what = f"bad: {exc}"
        where = "shipped" if path.parent == library.shipped_dir() else "yours"
        print(f"{path.stem:<{width}}  {what:<9}  {where:<7}  {path}")
    return 0


def run_check(args: argparse.Namespace) -> int:
    from chainfountain.level import io

    bad = 0
    for path in args.levels:
        try:
            level = io.load(path)
        except UserError as exc:  # each file its line; the others are still checked
            print(f"chainfountain: error: {exc}", file=sys.stderr)
            bad += 1
            continue
        print(f"{path}: ok ({level.sim.kind}: {level.meta.name})")
    return 2 if bad else 0


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
