"""The designed apparatus drawn to scale (paper Fig. "pulley_experiment"), from theory.design."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from chainfountain.figures.hooks import fig_apparatus
from chainfountain.theory import Fountain
from chainfountain.theory.design import Design, design


def apparatus_data(d: Design, roller: float | None = None) -> dict[str, Any]:
    """Geometry and forces of the paper's arrangement for design ``d`` (vertex frame, metres).

    Upper mechanism: the chain rests on the "beaker" table ``xi2*H`` below the
    fountain start; the unfolding roller (alpha = 0) sends it along the table
    and a guide pulley turns it up to the start. Lower mechanism: a guide
    pulley at the fountain end turns it up ``xi3*H`` to the "bottom" table,
    where the folding roller lays it down. Carts on 30-degree tracks pull the
    rollers (``Tbar_uc``, ``Tbar_lc``). Rollers are drawn small, as the paper
    assumes.
    """
    f, s = d.fountain, d.settings
    H = f.H
    r = roller if roller is not None else 0.02 * H
    (x0, y0), (xe, ye) = f.start, f.end
    y_up, y_lo = y0 - s.xi2 * H, ye + s.xi3 * H
    run = 0.35 * H
    xf, yf = f.curve(300)
    chain = np.array([
        [x0 - 1.6 * run, y_up], [x0 - run, y_up], [x0, y_up], [x0, y0],
    ])
    lower = np.array([[xe, ye], [xe + 0.0, y_lo], [xe + run, y_lo], [xe + 1.6 * run, y_lo]])
    beta = d.slope_uc
    cu, su = math.cos(beta), math.sin(beta)
    ux0, uy0 = x0 - run - 0.5 * run, y_up + r
    lx0, ly0 = xe + run + 0.5 * run, y_lo + r
    force_T0 = f.T0_bar
    forces = [
        {"x": x0, "y": y0, "fx": -math.cos(f.alpha0) * force_T0,
         "fy": -math.sin(f.alpha0) * force_T0, "label": f"Tbar_0 = {f.T0_bar:.3f}"},
        {"x": xe, "y": ye, "fx": math.cos(f.alphaE) * f.TE_bar,
         "fy": -math.sin(f.alphaE) * f.TE_bar, "label": f"Tbar_E = {f.TE_bar:.3f}"},
        {"x": ux0, "y": uy0, "fx": -cu * max(s.T_uc, 1e-9), "fy": -su * max(s.T_uc, 1e-9),
         "label": f"Tbar_uc = {s.T_uc:.3f}"},
        {"x": lx0, "y": ly0, "fx": cu * max(s.T_lc, 1e-9), "fy": -su * max(s.T_lc, 1e-9),
         "label": f"Tbar_lc = {s.T_lc:.3f}"},
    ]
    track = 0.25 * H
    tracks = [
        ((x0 - 1.8 * run, y_up), (x0 + 0.1 * run, y_up)),  # beaker table
        ((xe - 0.1 * run, y_lo), (xe + 1.8 * run, y_lo)),  # bottom table
        ((ux0 - r, uy0), (ux0 - r - track * cu, uy0 - track * su)),  # upper cart track
        ((lx0 + r, ly0), (lx0 + r + track * cu, ly0 - track * su)),  # lower cart track
        ((xe - 0.2 * run, ye), (xe + 0.2 * run, ye)),  # fountain end level
    ]
    w = 0.06 * H
    carts = [
        {"x": ux0 - r - 0.5 * track * cu, "y": uy0 - 0.5 * track * su + 0.5 * w * 0.6,
         "w": w, "h": 0.6 * w, "angle": beta},
        {"x": lx0 + r + 0.5 * track * cu, "y": ly0 - 0.5 * track * su + 0.5 * w * 0.6,
         "w": w, "h": 0.6 * w, "angle": -beta},
    ]
    return {
        "chain": np.vstack([chain, np.column_stack([xf, yf]), lower]),
        "fountain": np.column_stack([xf, yf]),
        "pulleys": [(ux0, uy0, r), (x0, y_up + r, r), (xe, y_lo - r, r), (lx0, ly0, r)],
        "carts": carts,
        "tracks": tracks,
        "forces": forces,
        "force_scale": 0.25 * H,
        "labels": [
            (x0 - 0.33 * H, 0.5 * (y0 + y_up), f"xi2*H = {s.xi2 * H:.3g} m"),
            (xe + 0.02 * H, 0.5 * (ye + y_lo), f"xi3*H = {s.xi3 * H:.3g} m"),
            (x0 - 1.6 * run, y_up - 0.07 * H, "beaker (chain at rest)"),
            (xe + 0.2 * run, y_lo - 0.07 * H, "bottom (chain at rest)"),
        ],
        "title": f"Apparatus for fountain D ({d.label})",
        "caption": (
            f"Fig. apparatus: the paper's pulley arrangement for fountain D (H = {H:g} m, "
            f"xi = {f.xi:.3g}, kappa = {f.kappa:.3g}, k = {f.k:.4g} 1/m), drawn to scale in the "
            f"vertex frame from chainfountain.theory.design ({d.label}): xi2 = {s.xi2:.4g}, "
            f"xi3 = {s.xi3:.4g}, Tbar_uc = {s.T_uc:.4f}, Tbar_lc = {s.T_lc:.4f}; they supply "
            f"Tbar_0 = 1/2 + Tbar_uc + xi2*k*H = {s.T0_bar:.4f} and "
            f"Tbar_E = 1/2 + Tbar_lc - xi3*k*H = {s.TE_bar:.4f}. Red arrows: scaled forces "
            "(cart arrows along their 30-degree tracks). Rollers drawn enlarged. With "
            "xi2 = xi3 = 1/2 both tables lie at the same height: the chain at rest above and "
            "below has the same potential energy, and the carts balance."),
    }


def fig_apparatus_paper() -> tuple[Figure, str]:
    """The apparatus for the paper's fountain D at ``k = 0.377`` (the special case)."""
    f = Fountain.from_geometry(0.33, 0.28, 2.0, k=0.377)
    return fig_apparatus(apparatus_data(design(f, lam=0.05)))
