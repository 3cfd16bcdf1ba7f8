"""Plotting hooks for figures that need simulator output (wired up later).

Both take plain numpy arrays / dicts, so the simulator side only has to
collect data:

* :func:`fig_apparatus` draws the pulley/cart machine of the paper's section
  "Generating Steady-State Chain Fountains" to scale with force arrows.
* :func:`fig_sim_vs_theory` overlays a (time-averaged) simulated steady fountain
  on the predicted catenary and compares the measured tension with
  ``Tbar = 1 - k/q + k*y`` (paper, section "Inverted Catenary").
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Circle, Polygon
from numpy.typing import ArrayLike

from chainfountain.figures._io import plt

__all__ = ["fig_apparatus", "fig_sim_vs_theory"]


def _xy(a: ArrayLike) -> np.ndarray:
    arr = np.asarray(a, dtype=float)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"expected an (n, 2) array of points, got shape {arr.shape}")
    return arr


def fig_apparatus(data: Mapping[str, Any]) -> tuple[Figure, str]:
    """Draw the apparatus to scale (metres, equal aspect) with force arrows.

    ``data`` keys (all optional except ``chain``):

    * ``chain``: ``(n, 2)`` points of the chain path (fountain and guided parts);
      ``fountain``: ``(m, 2)`` points of the free fountain, drawn bold.
    * ``pulleys``: sequence of ``(x, y, r)``.
    * ``carts``: sequence of dicts ``{"x", "y", "w", "h", "angle"}`` (centre, size, rad).
    * ``tracks``: sequence of ``((x0, y0), (x1, y1))`` segments (inclined planes, floor).
    * ``forces``: sequence of dicts ``{"x", "y", "fx", "fy", "label"}``; arrows are
      scaled so that the largest is ``force_scale`` metres long (default 0.3).
    * ``labels``: sequence of ``(x, y, text)``; ``title``: str; ``caption``: str.
    """
    chain = _xy(data["chain"])
    fig, ax = plt.subplots(figsize=(7.0, 5.5), layout="constrained")
    ax.plot(chain[:, 0], chain[:, 1], color="0.35", lw=1.0, label="chain")
    if "fountain" in data:
        fnt = _xy(data["fountain"])
        ax.plot(fnt[:, 0], fnt[:, 1], color="tab:blue", lw=2.2, label="free fountain")
    for (x0, y0), (x1, y1) in data.get("tracks", ()):
        ax.plot([x0, x1], [y0, y1], color="k", lw=1.5)
    for x, y, r in data.get("pulleys", ()):
        ax.add_patch(Circle((x, y), r, fill=False, ec="k", lw=1.2))
    for cart in data.get("carts", ()):
        w, hgt, ang = cart["w"], cart["h"], cart.get("angle", 0.0)
        c, s = np.cos(ang), np.sin(ang)
        corners = np.array(
            [[-w / 2, -hgt / 2], [w / 2, -hgt / 2], [w / 2, hgt / 2], [-w / 2, hgt / 2]]
        )
        rot = corners @ np.array([[c, s], [-s, c]]) + [cart["x"], cart["y"]]
        ax.add_patch(Polygon(rot, closed=True, fc="tab:gray", ec="k", alpha=0.6))
    forces: Sequence[Mapping[str, Any]] = data.get("forces", ())
    if forces:
        fmax = max(float(np.hypot(f["fx"], f["fy"])) for f in forces) or 1.0
        scale = float(data.get("force_scale", 0.3)) / fmax
        for f in forces:
            ax.annotate(
                "",
                xy=(f["x"] + f["fx"] * scale, f["y"] + f["fy"] * scale),
                xytext=(f["x"], f["y"]),
                arrowprops={"arrowstyle": "-|>", "color": "tab:red", "lw": 1.5},
            )
            if f.get("label"):
                ax.text(
                    f["x"] + f["fx"] * scale,
                    f["y"] + f["fy"] * scale,
                    f" {f['label']}",
                    color="tab:red",
                    fontsize=8,
                )
    for x, y, text in data.get("labels", ()):
        ax.text(x, y, text, fontsize=8)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(data.get("title", "Apparatus (to scale)"))
    ax.legend(fontsize=8, loc="best")
    caption = data.get(
        "caption",
        "Fig. apparatus: pulley and cart arrangement generating a steady fountain, drawn to "
        "scale; red arrows: forces (paper section 'Generating Steady-State Chain Fountains').",
    )
    return fig, caption


def fig_sim_vs_theory(
    sim_x: ArrayLike,
    sim_y: ArrayLike,
    theory_x: ArrayLike,
    theory_y: ArrayLike,
    tension_y: ArrayLike,
    tension_bar: ArrayLike,
    q: float,
    k: float,
    *,
    sim_y_spread: ArrayLike | None = None,
    tension_err: ArrayLike | None = None,
    title: str = "Simulated steady fountain against the theory",
) -> tuple[Figure, str]:
    """Simulated fountain over the predicted catenary, and measured ``Tbar`` against ``y``.

    Coordinates in the vertex frame of the theory (vertex at the origin, ``y`` up).
    ``sim_x, sim_y``: time-averaged link positions; ``sim_y_spread`` an optional
    band half-width (e.g. standard deviation). ``tension_y, tension_bar``: heights
    and measured scaled tensions ``T/(lambda v^2)`` of the joints, compared with
    ``1 - k/q + k*y``. Reports the RMS deviations in the caption.
    """
    sx, sy = np.asarray(sim_x, float), np.asarray(sim_y, float)
    tx, ty = np.asarray(theory_x, float), np.asarray(theory_y, float)
    Ty, Tb = np.asarray(tension_y, float), np.asarray(tension_bar, float)
    if sx.shape != sy.shape or tx.shape != ty.shape or Ty.shape != Tb.shape:
        raise ValueError("x/y (and tension y/value) arrays must have equal shapes")
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(9.5, 4.8), layout="constrained")
    ax0.plot(tx, ty, color="k", lw=1.2, label="catenary $qy = 1 - \\cosh(qx)$")
    if sim_y_spread is not None:
        sp = np.asarray(sim_y_spread, float)
        ax0.fill_between(sx, sy - sp, sy + sp, color="tab:blue", alpha=0.25, lw=0)
    ax0.plot(sx, sy, ".", color="tab:blue", ms=2.5, label="simulation (mean)")
    ax0.set_aspect("equal")
    ax0.set_xlabel("x [m]")
    ax0.set_ylabel("y [m]")
    ax0.legend(fontsize=8, loc="lower left")
    yy = np.linspace(min(Ty.min(), ty.min()), max(Ty.max(), 0.0), 50)
    ax1.plot(yy, 1 - k / q + k * yy, color="k", lw=1.2, label=r"$1 - k/q + ky$")
    if tension_err is not None:
        ax1.errorbar(Ty, Tb, yerr=np.asarray(tension_err, float), fmt="none", ecolor="0.6", lw=0.6)
    ax1.plot(Ty, Tb, ".", color="tab:red", ms=3, label="measured")
    ax1.set_xlabel("y [m]")
    ax1.set_ylabel(r"$\bar T$")
    ax1.legend(fontsize=8)
    fig.suptitle(title)
    # deviation of the shape: nearest-point distance of each simulated point to the curve
    d = np.min(np.hypot(sx[:, None] - tx[None, :], sy[:, None] - ty[None, :]), axis=1)
    rms_shape = float(np.sqrt(np.mean(d**2))) if d.size else float("nan")
    dT = Tb - (1 - k / q + k * Ty)
    rms_T = float(np.sqrt(np.mean(dT**2))) if dT.size else float("nan")
    caption = (
        f"Fig. sim_vs_theory: simulated steady fountain (dots) over the predicted catenary "
        f"q = {q:.4g} 1/m (left) and measured scaled tension against Tbar = 1 - k/q + k*y, "
        f"k = {k:.4g} 1/m (right). RMS distance to the curve {rms_shape:.3g} m, "
        f"RMS tension deviation {rms_T:.3g}."
    )
    return fig, caption
