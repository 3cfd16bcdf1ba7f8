"""Tuning the contact machine: the speed ``apparatus_floor`` selects against the laws.

Runs ``chainfountain sweep`` on ``apparatus_floor`` (the paper's idealized beaker with a
real floor, built of parts) over a grid of upper-cart masses and beaker offsets ``xi2``,
each point from rest for ``--duration`` simulated seconds (the starter lets go about 4 s
in; the figure uses each run's last ``recording.window``), and draws the speed the machine
selects against three predictions (``summary.json`` ``apparatus.speed_selection``):

- the paper's laws (pick-up ``lambda v^2/2``, the whole cart force): ``v_paper_p_half``;
- the rig law measured for these links (pick-up ``p_inf + R/(lambda v^2)``, cart gain
  0.526; ``chainfountain.sim.apparatus.PICKUP_RIG_2CM``): ``v_rig_2cm``;
- the ideal machine with the paper's laws, which ``ideal_floor`` runs, is the first.

Points the level check refuses (no fountain at that start) are listed, not drawn.

Usage::

    python -m research.contact_tuning --out /tmp/contact_tuning --jobs 2 \\
        --figure docs/img/contact_tuning.png

Cost: 15 points of 20 s at about 3x real time: about 1 min on two cores.
"""

from __future__ import annotations

import sys

import numpy as np

from research.ideal_tuning import (
    run_grid,
    save_figure,
    tuning_args,
)

MASSES = (0.005, 0.009, 0.013, 0.017, 0.021)
XI2 = (0.2, 0.3, 0.4)
KEY = "apparatus_speed_selection_"


def main(argv: list[str] | None = None) -> int:
    a = tuning_args(__doc__, 20.0, argv)
    rows = run_grid("apparatus_floor", {"carts[0].mass": MASSES, "apparatus.xi2": XI2}, a)
    print(f"{'cart g':>7s} {'xi2':>5s} {'status':>8s} {'paper':>7s} {'rig law':>8s} "
          f"{'measured':>9s} {'vs rig':>8s}")
    pts = []
    for r in rows:
        v = r.get(KEY + "v_measured")
        paper, rig = r.get(KEY + "v_paper_p_half"), r.get(KEY + "v_rig_2cm")
        status = r["status"]
        m, xi2 = r["carts[0].mass"], r["apparatus.xi2"]
        if status == "done" and v and rig:
            print(f"{1e3 * m:7.1f} {xi2:5.2f} {status:>8s} {paper:7.3f} {rig:8.3f} {v:9.3f} "
                  f"{v / rig - 1:+8.2%}")
            pts.append((m, xi2, paper, rig, v))
        else:
            print(f"{1e3 * m:7.1f} {xi2:5.2f} {status:>8s}  {str(r.get('reason', ''))[:70]}")
    if a.figure and pts:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        p = np.array(pts)
        fig, ax = plt.subplots(figsize=(6.4, 4.4), dpi=110)
        for i, xi2 in enumerate(XI2):
            sel = p[:, 1] == xi2
            if not sel.any():
                continue
            col = f"C{i}"
            g = 1e3 * p[sel, 0]
            ax.plot(g, p[sel, 4], "o", color=col, label=f"measured, xi2 = {xi2:g}")
            ax.plot(g, p[sel, 3], "-", color=col, lw=1)
            ax.plot(g, p[sel, 2], ":", color=col, lw=1)
        ax.plot([], [], "-", color="0.4", lw=1, label="rig law of these links (p 0.27, gain 0.53)")
        ax.plot([], [], ":", color="0.4", lw=1, label="paper's laws (p 1/2, gain 1) = ideal_floor")
        ax.set_xlabel("upper cart mass (g), on a 30 deg track")
        ax.set_ylabel("chain speed (m/s)")
        ax.set_title(f"apparatus_floor from rest: selected speed, last 2 s of {a.duration:g}-s "
                     "runs", fontsize=10)
        save_figure(fig, ax, a.figure, 7)
    return 0


if __name__ == "__main__":
    sys.exit(main())
