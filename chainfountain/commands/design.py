"""``chainfountain design``: the paper's two-step procedure, from a target fountain to a machine."""

from __future__ import annotations

import argparse
import json
import math

from chainfountain.commands.args import number, path_arg, writable_file
from chainfountain.commands.theory import add_fountain_args, finite_or_refuse, geometry_error
from chainfountain.errors import OutputError, UserError
from chainfountain.theory import Fountain
from chainfountain.theory.design import Design, DesignError, design


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "design",
        help="design an apparatus (offsets, carts) that generates a target fountain",
        description=(
            "Step 1: the free fountain for span --l, overshoot --h, drop --H at speed --v "
            "(or --k). Step 2: offsets xi2, xi3 and cart masses so that the paper's pulley "
            "apparatus supplies its end tensions. --out writes a fed level that generates the "
            "fountain."
        ),
        allow_abbrev=False,
    )
    add_fountain_args(p, speed_required=True)
    p.add_argument("--xi2", type=number("an offset (fraction of H)", min=0, max=100),
                   default=None, help="beaker offset below the fountain start, as a fraction "
                   "of H")
    p.add_argument("--xi3", type=number("an offset (fraction of H)", min=0, max=100),
                   default=None, help="bottom offset above the fountain end, as a fraction "
                   "of H")
    p.add_argument("--lambda", dest="lam", metavar="KG_PER_M", default=0.05,
                   type=number("a linear density in kg/m", min=0, min_inclusive=False,
                               max=1000),
                   help="linear density of the chain (default 0.05 kg/m)")
    p.add_argument("--slope", type=number("a track angle in degrees", min=0, max=90,
                                          min_inclusive=False), default=30.0,
                   help="cart track angle in degrees (default 30)")
    p.add_argument("--out", type=path_arg("a level file"), default=None, metavar="LEVEL.toml",
                   help="write a level that generates the fountain (run/play accept it)")
    p.add_argument("--accuracy", type=number("a relative accuracy", min=0.0, max=0.1,
                                             min_inclusive=False), default=0.005,
                   help="accuracy the written level's settings are chosen for (relative; "
                   "default 0.005): link length, step and iterations from the error model "
                   "(solver.accuracy)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


def design_dict(d: Design) -> dict:
    f, s = d.fountain, d.settings
    return {
        "fountain": f.to_dict(),
        "choice": d.label,
        "xi2": s.xi2,
        "xi3": s.xi3,
        "beaker_drop_m": d.beaker_drop,
        "bottom_rise_m": d.bottom_rise,
        "T_uc_bar": s.T_uc,
        "T_lc_bar": s.T_lc,
        "T0_bar": s.T0_bar,
        "TE_bar": s.TE_bar,
        "lambda": d.lam,
        "slope_deg": math.degrees(d.slope_uc),
        "cart_gain": d.cart_gain,
        "m_uc_kg": d.m_uc,
        "m_lc_kg": d.m_lc,
        "launch_speed": f.v,
        "launch_angle_deg": math.degrees(f.alpha0),
        "alternatives": [
            {"label": lab, "xi2": a.xi2, "xi3": a.xi3, "T_uc_bar": a.T_uc, "T_lc_bar": a.T_lc}
            for lab, a in d.alternatives
        ],
    }


def run(args: argparse.Namespace) -> int:
    if args.out is not None:
        writable_file(args.out, "--out")
    try:
        base = Fountain(l=args.l, h=args.h, H=args.H, k=1.0, g=args.g)
        f = base.with_k(args.k if args.k is not None else args.g / args.v**2)
        d = design(f, args.lam, xi2=args.xi2, xi3=args.xi3, slope=math.radians(args.slope))
        out = design_dict(d)
    except DesignError as exc:
        raise UserError(str(exc)) from None
    except (ValueError, ArithmeticError) as exc:
        raise UserError(geometry_error(args, f"the solver fails ({exc})")) from None
    finite_or_refuse(out, args)
    if args.out is not None:
        from chainfountain.design_level import (
            design_estimate,
            near_critical_note,
            write_design_level,
        )
        from chainfountain.sim.accuracy import OutOfReach

        try:
            est = design_estimate(d, args.accuracy)
        except OutOfReach as exc:
            least = (f"at least {math.ceil(exc.best * 1e4) / 1e4:g}" if math.isfinite(exc.best)
                     else "a fountain inside the model")
            raise UserError(f"argument --accuracy: {args.accuracy:g}: {exc}; allowed: "
                            f"{least}") from None
        if est is not None:
            st = est.settings
            out["level_settings"] = {
                "link_length": st.link_length, "dt": st.dt, "iterations": st.iterations,
                "links_in_flight": est.links, "accuracy": args.accuracy,
                "error_model_bounds": {"h": est.bounds["vertex_y"],
                                       "vertex_x": est.bounds["vertex_x"],
                                       "l": est.bounds["landing_x"]}}
        try:
            out["level"] = str(write_design_level(d, args.out, accuracy=args.accuracy))
        except OSError as exc:
            raise OutputError(f"argument --out: cannot write {str(args.out)!r} "
                              f"({exc.strerror or exc})") from None
    if args.json:
        print(json.dumps(out, indent=2))
        return 0
    s = d.settings
    print(f"Step 1, the free fountain: l = {f.l:g} m, h = {f.h:g} m, H = {f.H:g} m, "
          f"v = {f.v:.4g} m/s (k = {f.k:.4g} 1/m)")
    print(f"  q*H = {f.qH:.4g}, launch angle {math.degrees(f.alpha0):.4g} deg, "
          f"Tbar_0 = {f.T0_bar:.4f}, Tbar_E = {f.TE_bar:.4f}")
    print(f"Step 2, the apparatus ({d.label}):")
    print(f"  beaker  xi2 = {s.xi2:.4f}  ({d.beaker_drop:.4g} m below the fountain start)")
    print(f"  bottom  xi3 = {s.xi3:.4f}  ({d.bottom_rise:.4g} m above the fountain end)")
    print(f"  upper cart Tbar_uc = {s.T_uc:.4f} -> {d.m_uc:.4g} kg on a {args.slope:g} deg track")
    print(f"  lower cart Tbar_lc = {s.T_lc:.4f} -> {d.m_lc:.4g} kg on a {args.slope:g} deg track")
    print(f"  (a cart passes on {d.cart_gain:g} of its force, as the simulated roller does; "
          "the paper's carts pass on all of it and need half these masses)")
    print(f"  supplies Tbar_0 = 1/2 + Tbar_uc + xi2*k*H = {s.T0_bar:.4f}, "
          f"Tbar_E = 1/2 + Tbar_lc - xi3*k*H = {s.TE_bar:.4f}")
    print("Alternatives:")
    for lab, a in d.alternatives:
        print(f"  {lab}: xi2 = {a.xi2:.4f}, xi3 = {a.xi3:.4f}, "
              f"Tbar_uc = {a.T_uc:.4f}, Tbar_lc = {a.T_lc:.4f}")
    if "level" in out:
        print(f"wrote {out['level']} (fed level: guide at v and alpha0, floor pulling with "
              f"Tbar_E); try: chainfountain run {out['level']}")
        ls = out.get("level_settings")
        if ls:
            b = ls["error_model_bounds"]
            print(f"  settings for {100 * ls['accuracy']:g} % (error model): "
                  f"{ls['link_length'] * 1e3:g} mm links ({ls['links_in_flight']} in flight), "
                  f"dt = {ls['dt'] * 1e6:g} us, {ls['iterations']} iterations; vertex height "
                  f"+-{100 * b['h']:.2f} %, vertex x +-{100 * b['vertex_x']:.2f} %, landing "
                  f"+-{100 * b['l']:.2f} %")
        note = near_critical_note(d)
        if note:
            print(" ", note.strip())
    return 0
