"""``chainfountain converge LEVEL``: the discretisation error of a fed level by refinement."""

from __future__ import annotations

import argparse
import json
import sys

from chainfountain.commands.args import integer, number, path_arg, writable_file
from chainfountain.errors import OutputError


def add_parser(sub: argparse._SubParsersAction) -> None:
    from chainfountain.refine import SETTLE, WINDOW

    p = sub.add_parser(
        "converge",
        help="estimate a fed level's discretisation error: rerun it at half the link "
        "length and step and print the table",
        description="Run LEVEL (kind 'feed') from the predicted catenary at its link length "
        "L and step dt, then at L/2 and dt/2 (and L/4, dt/4 with --refinements 3), each "
        f"settled {SETTLE:g} s and averaged {WINDOW:g} s. Prints each run's errors against "
        "the paper's catenary and the first-order estimate of the level's discretisation "
        "error, 2 (f(L) - f(L/2)), with its statistical error. Each refinement costs about "
        "four times the run before it.",
        allow_abbrev=False,
    )
    p.add_argument("level", metavar="LEVEL", help="fed level file or name (e.g. paper_tall)")
    p.add_argument("--refinements", type=integer("a number of runs", min=2, max=4), default=2,
                   help="runs in the ladder L, L/2, L/4, ... (default 2)")
    p.add_argument("--settle", type=number("a duration in s", min=0, max=60), default=SETTLE,
                   help=f"simulated seconds before averaging (default {SETTLE:g})")
    p.add_argument("--window", type=number("a duration in s", min=0.1, max=600),
                   default=WINDOW, help=f"simulated seconds averaged (default {WINDOW:g})")
    p.add_argument("--json", type=path_arg("a JSON file"), default=None,
                   help="also write the table and the estimate to this file")
    p.set_defaults(func=run)


def _pct(x: float | None, absolute: bool) -> str:
    if x is None or x != x:
        return "-"
    return f"{x:+.4f}" if absolute else f"{x:+.2%}"


def format_table(res) -> str:
    """The ladder and the estimate as plain text."""
    from chainfountain.refine import BLOCKS, FIGURES

    names = {"h": "vertex y", "vertex_x": "vertex x", "l": "landing", "v": "speed",
             "T0_bar": "Tbar_0"}
    head = f"{'L mm':>6s} {'dt us':>7s} {'links':>6s} " + " ".join(
        f"{names[f]:>9s}" for f in FIGURES) + f" {'stretch':>8s} {'RTF':>5s}"
    lines = [f"{res.level}: errors against the paper's catenary (Tbar_0 absolute)", head]
    for r in res.runs:
        lines.append(f"{r.link_length * 1e3:6.2f} {r.dt * 1e6:7.2f} {r.links:6d} " + " ".join(
            f"{_pct(r.errors[f], f == 'T0_bar'):>9s}" for f in FIGURES)
            + f" {r.stretch:8.3%} {r.realtime_factor:5.2f}")
    d, s, x = res.discretisation_error(), res.statistical_error(), res.extrapolated()
    lines.append(f"{'discretisation error':21s} " + " ".join(
        f"{_pct(d[f], f == 'T0_bar'):>9s}" for f in FIGURES))
    lines.append(f"{'+- statistical':21s} " + " ".join(
        f"{_pct(s[f], f == 'T0_bar').replace('+', ''):>9s}" for f in FIGURES))
    bar, ok = res.error_bar(), res.resolved()
    lines.append(f"{'error bar of L, dt':21s} " + " ".join(
        f"{_pct(bar[f], f == 'T0_bar').replace('+', '') + ('' if ok[f] else '*'):>9s}"
        for f in FIGURES))
    lines.append(f"{'extrapolated to 0':21s} " + " ".join(
        f"{_pct(x[f], f == 'T0_bar'):>9s}" for f in FIGURES))
    order = res.observed_order()
    if any(v is not None for v in order.values()):
        lines.append(f"{'observed order':21s} " + " ".join(
            f"{'-' if order[f] is None else format(order[f], '.2f'):>9s}" for f in FIGURES))
    lines.append("estimate: 2 (f(L) - f(L/2)), first order in L and dt together; "
                 f"statistical: standard error of the window means ({BLOCKS} blocks); error bar: "
                 "|estimate| + 2 x statistical (* not resolved: the estimate is within twice "
                 "its statistical error; a longer --window resolves more)")
    return "\n".join(lines)


def run(args: argparse.Namespace) -> int:
    from chainfountain import atomic
    from chainfountain.headless import json_safe
    from chainfountain.level import io, library
    from chainfountain.refine import refine

    level = io.load(library.resolve(args.level))
    if args.json is not None:
        writable_file(args.json, "--json")  # before the refinements, not after them
    name = level.meta.name
    res = refine(level.sim, name, refinements=args.refinements, settle=args.settle,
                 window=args.window, progress=lambda m: print(m, file=sys.stderr, flush=True))
    print(format_table(res))
    if args.json is not None:
        try:
            atomic.write_text(args.json, json.dumps(json_safe(res.as_dict()), indent=1))
        except OSError as exc:
            raise OutputError(f"argument --json: cannot write {str(args.json)!r} "
                              f"({exc.strerror or exc}); the table is printed above") from None
        print(f"wrote {args.json}")
    return 0
