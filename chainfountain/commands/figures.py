"""``chainfountain figures --out DIR``: recompute the paper's figures."""

from __future__ import annotations

import argparse
from pathlib import Path

from chainfountain.commands.args import path_arg
from chainfountain.errors import UserError


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "figures",
        help="write the paper's figures (PNG, SVG and a caption file each)",
        description="Recompute the figures of Mayet & Pfeiffer that carry data.",
        allow_abbrev=False,
    )
    p.add_argument("--out", type=path_arg("an output folder"), default=Path("figures"),
                   help="output folder")
    p.add_argument("--only", nargs="+", metavar="NAME", help="only these figures")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from chainfountain.figures import FIGURES, main
    from chainfountain.headless import prepare_out_dir

    if args.only:
        unknown = [n for n in args.only if n not in FIGURES]
        if unknown:
            raise UserError(f"argument --only: {unknown[0]!r} is not a figure; allowed: "
                            + ", ".join(sorted(FIGURES)))
    prepare_out_dir(args.out, "--out")
    paths = main(args.out, progress=None, names=args.only)
    for p in paths:
        print(f"wrote {p}")
    return 0
