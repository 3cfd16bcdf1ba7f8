"""The gripped folds' start region as a map: every measured start from rest over drop and
start speed, and over the launch angle, with the region the level check admits.

Reads the tables of the sweeps in this folder (``chainfountain sweep
research/contact_region/fold_drop.toml --out runs/contact_region/fold_drop``, and
``fold_speed``, ``fold_angle``, ``special_drop``) and the random draws of
:mod:`research.contact_region.draws` (``--save runs/contact_region/draws_<preset>.json``)
and writes ``docs/img/contact_region.png``; and the floor machine's sweeps
(``floor_drop``, ``floor_speed``, ``floor_angle``, ``floor_depth``) as strips beside the
span the window's sliders and the level check admit, ``docs/img/contact_region_floor.png``::

    python -m research.contact_region.map runs/contact_region
"""

from __future__ import annotations

import argparse
import csv
import json
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from chainfountain.sim.apparatus import region  # noqa: E402

SWEEPS = ("fold_drop", "fold_speed", "fold_angle", "special_drop")
IMG = Path(__file__).resolve().parents[2] / "docs" / "img"
OUT = IMG / "contact_region.png"
FLOOR_SWEEPS = (("floor_drop", "apparatus.drop", "drop H (m)", 1.0),
                ("floor_speed", "apparatus.speed", "start speed v0 (m/s)", 1.0),
                ("floor_angle", "apparatus.launch_angle", "launch angle alpha0 (deg)",
                 180.0 / math.pi),
                ("floor_depth", "apparatus.floor_depth", "floor below the end d (m)", 1.0))
SHIPPED = {"apparatus.drop": 0.5, "apparatus.speed": 3.0,
           "apparatus.launch_angle": math.radians(60.0)}
G, TE = 9.81, 0.17


def outcome(row: dict[str, str]) -> str:
    """One sweep point (a row of its results.csv): 'refused' by the level check, 'fails'
    (the run ended early), 'swings' (ran its full length, its speed still wandering by
    more than the steady test allows) or 'holds' (ran its full length, steady)."""
    if row["status"] == "refused":
        return "refused"
    if row["status"] != "done":
        return "fails"
    return "holds" if row.get("steady") == "True" else "swings"


STYLE = {"holds": dict(marker="o", color="tab:green"),
         "swings": dict(marker="o", color="tab:green", fillstyle="none"),
         "fails": dict(marker="x", color="tab:red"),
         "refused": dict(marker="s", color="0.6", fillstyle="none")}


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("runs", type=Path, help="folder holding the sweeps' --out folders")
    p.add_argument("--out", type=Path, default=OUT)
    a = p.parse_args(argv)
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 5.8),
                                  gridspec_kw={"width_ratios": [2.2, 1]})
    v = np.linspace(2.4, 3.8, 200)
    m_lo, m_hi = region.MEASURED_Q
    ax.fill_between(v, (m_lo - TE) * v * v / G, (m_hi - TE) * v * v / G, color="0.5",
                    alpha=0.08, label=f"measured to hold: {m_lo:.3f} <= Tbar_E + gH/v0^2 <= "
                    f"{m_hi:.3f}")
    q_lo, q_hi = region.FROM_REST_Q
    s_lo, s_hi = region.FROM_REST_SPEED
    vin = np.linspace(s_lo, s_hi, 100)
    ax.fill_between(vin, (q_lo - TE) * vin * vin / G, (q_hi - TE) * vin * vin / G,
                    color="tab:green", alpha=0.18,
                    label=f"admitted (the inner half): Q {q_lo:.4g}-{q_hi:.4g}, v0 "
                    f"{s_lo:g}-{s_hi:g} m/s")
    for q in (1.0,):
        ax.plot(v, (q - TE) * v * v / G, "k:", lw=1, label="no fountain above (Q = 1)")
    seen: set[str] = set()
    angle_rows = []
    for name in SWEEPS:
        f = a.runs / name / "results.csv"
        if not f.exists():
            continue
        with f.open() as fh:
            rows = list(csv.DictReader(fh))
        for row in rows:
            o = outcome(row)
            seed = int(row.get("seed") or 0)
            if name == "fold_angle":
                angle_rows.append((math.degrees(float(row["apparatus.launch_angle"])), seed, o))
                continue
            H = float(row.get("apparatus.drop") or SHIPPED["apparatus.drop"])
            vv = float(row.get("apparatus.speed") or SHIPPED["apparatus.speed"])
            shift = 0.012 * (seed - 0.5) + (0.03 if name.startswith("special") else 0.0)
            label = f"sweep start {o}" if o not in seen else None
            seen.add(o)
            ax.plot(vv + shift, H, ls="none", ms=6, label=label, **STYLE[o])
    for draws in sorted(a.runs.glob("draws*.json")):
        data = json.loads(draws.read_text())
        shift = 0.03 if "special" in data["preset"] else 0.0  # its geometry: as shipped
        a_lo, a_hi = (math.degrees(x) for x in region.FROM_REST_ANGLE)
        for r in data["rows"]:
            c = {**SHIPPED, **r["changes"]}
            o = "fails" if r["rc"] != 0 or r["ended"] else "holds" if r["steady"] else "swings"
            label = (f"random draw {o} (every field drawn; {a_lo:g}-{a_hi:g} deg)"
                     if f"d{o}" not in seen else None)
            seen.add(f"d{o}")
            ax.plot(c["apparatus.speed"] + shift, c["apparatus.drop"], ls="none", ms=4,
                    label=label,
                    marker="X" if o == "fails" else "D",
                    fillstyle="none" if o == "swings" else "full",
                    color="tab:red" if o == "fails" else "tab:blue")
    ax.plot(SHIPPED["apparatus.speed"], SHIPPED["apparatus.drop"], marker="*", ms=16,
            color="gold", mec="k", ls="none", label="shipped (both presets)")
    ax.annotate("at 3.0 m/s: apparatus_fold_gripped (left pair),\n"
                "apparatus_special_gripped (right pair)", (3.06, 0.33), fontsize=7)
    ax.set_xlabel("start speed v0 = apparatus.speed (m/s)")
    ax.set_ylabel("drop H = apparatus.drop (m)")
    ax.set_ylim(0.2, 0.8)
    ax.set_title("gripped folds from rest, 30 s (Tbar_E = 0.17)")
    fig.legend(*ax.get_legend_handles_labels(), fontsize=8, loc="lower center", ncol=3,
               frameon=False)
    ax.grid(alpha=0.3)
    lo, hi = (math.degrees(x) for x in region.MEASURED_ANGLE)
    ax2.axvspan(lo, hi, color="0.5", alpha=0.08, label="measured to hold")
    lo, hi = (math.degrees(x) for x in region.FROM_REST_ANGLE)
    ax2.axvspan(lo, hi, color="tab:green", alpha=0.18, label="admitted")
    for deg, seed, o in angle_rows:
        ax2.plot(deg, seed, ls="none", ms=7, **STYLE[o])
    ax2.plot(60.0, 0.5, marker="*", ms=16, color="gold", mec="k", ls="none")
    ax2.set_yticks([0, 1], ["start 0", "start 1"])
    ax2.set_ylim(-0.6, 1.6)
    ax2.set_xlabel("launch angle alpha0 (deg); H = 0.5 m, v0 = 3 m/s")
    ax2.set_title("launch angle")
    ax2.grid(alpha=0.3)
    fig.tight_layout(rect=(0, 0.17, 1, 1))
    fig.savefig(a.out, dpi=110)
    print(f"wrote {a.out}")
    floor = a.out.with_name("contact_region_floor.png")
    floor_strips(a.runs, floor)
    print(f"wrote {floor}")
    return 0


def floor_strips(runs: Path, out: Path) -> None:
    """The floor machine's 1-D sweeps, each beside the span its slider admits."""
    from chainfountain.app.controls import spec_for
    from chainfountain.app.spans import admissible
    from chainfountain.fields import get_value
    from chainfountain.level.io import load
    from chainfountain.level.library import resolve

    level = load(resolve("apparatus_floor"))
    fig, axes = plt.subplots(1, len(FLOOR_SWEEPS), figsize=(14, 3.7))
    for ax, (name, path, label, scale) in zip(axes, FLOOR_SWEEPS, strict=True):
        span = admissible(level, spec_for(level.sim, path), level.sim)
        if span is not None:
            ax.axvspan(span[0] * scale, span[1] * scale, color="tab:green", alpha=0.12,
                       label="admitted")
        f = runs / name / "results.csv"
        if f.exists():
            with f.open() as fh:
                for row in csv.DictReader(fh):
                    o = outcome(row)
                    ax.plot(float(row[path]) * scale, int(row.get("seed") or 0), ls="none",
                            ms=7, **STYLE[o])
        ax.plot(float(get_value(level.sim, path)) * scale, 0.5, marker="*", ms=16,
                color="gold", mec="k", ls="none")
        ax.set_yticks([0, 1], ["start 0", "start 1"])
        ax.set_ylim(-0.6, 1.6)
        ax.set_xlabel(label)
        ax.grid(alpha=0.3)
    handles = [plt.Line2D([], [], ls="none", ms=7, label=k, **v) for k, v in STYLE.items()]
    fig.legend(handles=handles, fontsize=8, loc="lower center", ncol=len(handles), frameon=False)
    fig.suptitle("apparatus_floor from rest, 30 s each (star: shipped; green: admitted)")
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    fig.savefig(out, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    raise SystemExit(main())
