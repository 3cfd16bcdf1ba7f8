"""``chainfountain theory``: the paper's analytic fountain for a geometry and speed."""

from __future__ import annotations

import argparse
import json
import math
import sys

from chainfountain.commands.args import number
from chainfountain.errors import UserError
from chainfountain.theory import G0, Fountain

LENGTH = "a length in m"
LENGTH_MIN, LENGTH_MAX = 1e-4, 1e4
"""Range of the fountain's lengths (m): the solver's numbers stay finite inside it."""


def add_fountain_args(p: argparse.ArgumentParser, *, speed_required: bool) -> None:
    """The paper's fountain flags: ``--l --h --H``, ``--k`` or ``--v``, ``--g``."""
    p.add_argument("--l", type=number(LENGTH, min=LENGTH_MIN, max=LENGTH_MAX), required=True,
                   metavar="L", help="horizontal distance start to end (m)")
    p.add_argument("--h", type=number(LENGTH, min=0, max=LENGTH_MAX), required=True,
                   metavar="OVERSHOOT", help="height of the vertex above the start (m)")
    p.add_argument("--H", type=number(LENGTH, min=LENGTH_MIN, max=LENGTH_MAX), required=True,
                   metavar="DROP", help="drop from the start to the end (m)")
    speed = p.add_mutually_exclusive_group(required=speed_required)
    speed.add_argument("--k", type=number("k = g/v^2 in 1/m", min=1e-6, max=1e6),
                       help="k = g/v^2 (1/m)")
    speed.add_argument("--v", type=number("a speed in m/s", min=1e-3, max=1e4),
                       help="chain speed (m/s)")
    p.add_argument("--g", type=number("gravity in m/s^2", min=0.01, max=1000.0),
                   default=G0, help=f"gravitational acceleration (default {G0})")


def finite_or_refuse(values: object, args: argparse.Namespace) -> None:
    """Refuse (one line naming the fountain's flags) a result with a number that is not
    finite: a geometry or speed at the edge of the ranges the solver cannot follow."""
    def finite(x: object) -> bool:
        if isinstance(x, float):
            return math.isfinite(x)
        if isinstance(x, dict):
            return all(finite(v) for v in x.values())
        if isinstance(x, list | tuple):
            return all(finite(v) for v in x)
        return True

    if not finite(values):
        raise UserError(geometry_error(args, "a result of the solver is not a finite number"))


def geometry_error(args: argparse.Namespace, why: str) -> str:
    """One line naming the fountain's flags and their values, and why they fail."""
    given = " ".join(f"--{n} {getattr(args, n):g}" for n in ("l", "h", "H", "k", "v", "g")
                     if getattr(args, n, None) is not None)
    return (f"arguments {given}: {why}; allowed: a less extreme geometry (ratios of l, h "
            "and H nearer 1) or speed")


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "theory",
        help="the paper's steady fountain for a geometry (l, h, H) and speed",
        description=(
            "Inverted-catenary fountain of Mayet & Pfeiffer for the horizontal span --l, "
            "overshoot --h and drop --H (metres), at speed --v (m/s) or k = g/v^2 (--k, 1/m). "
            "Without --k/--v it reports the admissible range of k."
        ),
        allow_abbrev=False,
    )
    add_fountain_args(p, speed_required=False)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


def _range_report(f: Fountain) -> dict:
    k_lo, k_hi = f.k_range()
    r = f.force_ranges()
    return {
        "q": f.q,
        "qH": f.qH,
        "k_range": [k_lo, k_hi],
        "k_range_empty": r.empty,
        "k_max": k_hi,
        "v_min": f.v_min,
        "v_kmax": f.v_kmax,
        "v_max": f.v_max,
        "T0_bar_range": list(r.T0),
        "TE_bar_range": list(r.TE),
        "alpha0_deg": math.degrees(f.alpha0),
        "alphaE_deg": math.degrees(f.alphaE),
        "start": list(f.start),
        "end": list(f.end),
    }


def _table(rows: list[tuple[str, str, str]]) -> str:
    w0 = max(len(r[0]) for r in rows)
    w1 = max(len(r[1]) for r in rows)
    return "\n".join(f"  {a:<{w0}}  {b:>{w1}}  {c}" for a, b, c in rows)


def run(args: argparse.Namespace) -> int:
    try:
        return _run(args)
    except (ValueError, ArithmeticError) as exc:  # the solver failed at an extreme geometry
        raise UserError(geometry_error(args, f"the solver fails ({exc})")) from None


def _run(args: argparse.Namespace) -> int:
    # k is a placeholder here; it only matters once the user gives a speed.
    base = Fountain(l=args.l, h=args.h, H=args.H, k=1.0, g=args.g)
    if args.k is None and args.v is None:
        rep = _range_report(base)
        finite_or_refuse([v for k, v in rep.items() if k not in ("k_range", "T0_bar_range",
                                                                 "TE_bar_range")], args)
        if args.json:
            print(json.dumps(rep, indent=2))
            return 0
        k_lo, k_hi = rep["k_range"]
        print(f"Fountain with l = {args.l:g} m, h = {args.h:g} m, H = {args.H:g} m "
              f"(xi = {base.xi:.4g}, kappa = {base.kappa:.4g}):")
        print(_table([
            ("q", f"{base.q:.6g}", "1/m   shape, from q*l = acosh(1+q(h+H)) + acosh(1+qh)"),
            ("q*H", f"{base.qH:.6g}", ""),
            ("k range", f"({k_lo:.4g}, {k_hi:.4g}]", "1/m   energy bound < k <= k_max"),
            ("v range", f"[{base.v_kmax:.4g}, {base.v_max:.4g})", "m/s   v(k_max) <= v < v_max"),
            ("v_min", f"{base.v_min:.4g}", "m/s   sqrt(g(h+H)), the paper's looser bound"),
            ("Tbar_0 range", f"[{rep['T0_bar_range'][0]:.4g}, {rep['T0_bar_range'][1]:.4g})", ""),
            ("Tbar_E range", f"[{rep['TE_bar_range'][0]:.4g}, {rep['TE_bar_range'][1]:.4g})", ""),
            ("alpha0", f"{rep['alpha0_deg']:.4g}", "deg   launch angle above horizontal"),
            ("alphaE", f"{rep['alphaE_deg']:.4g}", "deg   landing angle below horizontal"),
        ]))
        if rep["k_range_empty"]:
            print("  note: the energy bound leaves no admissible speed (q*H*(1-xi) <= 1)")
        print("Give --k or --v for the tensions.")
        return 0

    if args.k is not None:
        f = base.with_k(args.k)
        flag, val = "--k", args.k
    else:
        f = base.with_k(args.g / args.v**2)
        flag, val = "--v", args.v
    if f.TE_bar < -1e-12:
        allowed = (f"k <= k_max = {f.k_max:.6g} 1/m" if flag == "--k"
                   else f"v >= sqrt(g/k_max) = {f.v_kmax:.6g} m/s")
        raise UserError(
            f"argument {flag}: {val:g} gives a pushing end force (Tbar_E = {f.TE_bar:.4g} < 0), "
            f"impossible for a chain; allowed: {allowed}"
        )
    finite_or_refuse(f.to_dict(), args)
    b = f.bounds()
    if not b.below_v_max:
        print(f"warning: v = {f.v:.4g} m/s is not below the rough energy bound "
              f"v_max = {f.v_max:.4g} m/s (k <= 1/(2H)); bounds_ok is false", file=sys.stderr)
    if args.json:
        print(json.dumps(f.to_dict(), indent=2))
        return 0
    sx, sy = f.start
    ex, ey = f.end
    yes = {True: "holds", False: "FAILS"}
    print(f"Fountain with l = {f.l:g} m, h = {f.h:g} m, H = {f.H:g} m, g = {f.g:g} m/s^2:")
    print(_table([
        ("q", f"{f.q:.6g}", "1/m"),
        ("q*H", f"{f.qH:.6g}", ""),
        ("k", f"{f.k:.6g}", "1/m   g/v^2"),
        ("v", f"{f.v:.6g}", "m/s"),
        ("k_max", f"{f.k_max:.6g}", "1/m   zero end tension"),
        ("v(k_max)", f"{f.v_kmax:.6g}", "m/s"),
        ("v_min", f"{f.v_min:.6g}", "m/s   sqrt(g(h+H))"),
        ("v_max", f"{f.v_max:.6g}", "m/s   sqrt(2gH)"),
        ("Tbar_0", f"{f.T0_bar:.6g}", "      start tension / (lambda v^2)"),
        ("Tbar_E", f"{f.TE_bar:.6g}", "      end tension / (lambda v^2)"),
        ("vertex", "(0, 0)", "m"),
        ("start", f"({sx:.4g}, {sy:.4g})", "m     beaker"),
        ("end", f"({ex:.4g}, {ey:.4g})", "m     floor"),
        ("alpha0", f"{math.degrees(f.alpha0):.4g}", "deg"),
        ("alphaE", f"{math.degrees(f.alphaE):.4g}", "deg"),
        ("chain in flight", f"{f.length:.4g}", "m"),
    ]))
    print("Bounds:")
    print(_table([
        ("Tbar_0 >= 0", yes[b.tensile_start], ""),
        ("Tbar_E >= 0 (k <= k_max)", yes[b.tensile_end], ""),
        ("v >= v_min", yes[b.above_v_min], ""),
        ("v < v_max", yes[b.below_v_max], ""),
    ]))
    return 0
