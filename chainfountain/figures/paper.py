"""The paper's figures recomputed from ``chainfountain.theory``.

Each ``fig_<name>()`` returns ``(figure, caption)``; nothing is written here
(see :func:`chainfountain.figures.main`). Example geometry of the paper:
``H = 2 m``, ``xi = h/H = 0.14``, ``kappa = l/H = 0.165``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from matplotlib.colors import LogNorm
from matplotlib.figure import Figure

from chainfountain.figures._io import plt
from chainfountain.theory import Fountain, solve_qH
from chainfountain.theory.stiff import StiffFountain, continued

__all__ = [
    "EXAMPLE",
    "example_fountain",
    "fig_force_ranges",
    "fig_schematic_chain_fountain",
    "fig_sol",
    "paper_stiff_fountains",
]

EXAMPLE = {"H": 2.0, "xi": 0.14, "kappa": 0.165, "k": 0.377}


def example_fountain(k: float = EXAMPLE["k"]) -> Fountain:
    """The paper's example fountain (``l = 0.33, h = 0.28, H = 2`` m) at ``k``."""
    H = EXAMPLE["H"]
    return Fountain.from_geometry(l=EXAMPLE["kappa"] * H, h=EXAMPLE["xi"] * H, H=H, k=k)


def fig_sol(n: int = 240) -> tuple[Figure, str]:
    """Fig. "sol": ``qbar = H*q`` from Eq. (kinemat_constraint) over ``(xi, kappa)``."""
    xi = np.linspace(0.0, 0.99, n)
    kappa = np.geomspace(0.05, 2.0, n)
    XI, KA = np.meshgrid(xi, kappa)
    QB = np.asarray(solve_qH(XI, KA))
    ex = example_fountain()
    fig, ax = plt.subplots(figsize=(6.4, 4.6), layout="constrained")
    levels = np.array([1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000])
    levels = levels[(levels >= QB.min()) & (levels <= QB.max() * 1.01)]
    fill = ax.contourf(
        XI, KA, QB, levels=np.geomspace(QB.min(), QB.max(), 60), norm=LogNorm(), cmap="viridis"
    )
    fill.set_rasterized(True)  # keeps the SVG small
    lines = ax.contour(XI, KA, QB, levels=levels, colors="white", linewidths=0.8)
    ax.clabel(lines, fmt="%g", fontsize=8)
    cb = fig.colorbar(fill, ax=ax, ticks=levels)
    cb.ax.set_yticklabels([f"{v:g}" for v in levels])
    cb.set_label(r"$\bar q = Hq$")
    ax.set_yscale("log")
    ax.plot(ex.xi, ex.kappa, "r*", ms=12, mec="k")
    ax.annotate(
        rf"example $\xi={ex.xi:.2f}$, $\kappa={ex.kappa:.3f}$" + "\n" + rf"$\bar q={ex.qH:.2f}$",
        (ex.xi, ex.kappa),
        xytext=(0.3, 0.09),
        color="white",
        fontsize=9,
        arrowprops={"arrowstyle": "->", "color": "white"},
    )
    ax.set_xlabel(r"$\xi = h/H$")
    ax.set_ylabel(r"$\kappa = l/H$")
    ax.set_title(r"Shape parameter from $ql = \mathrm{acosh}(1+q(h+H)) + \mathrm{acosh}(1+qh)$")
    caption = (
        "Fig. sol: numerical solution qbar = H*q of the kinematic constraint "
        "q*l = acosh(1 + q*(h+H)) + acosh(1 + q*h) (paper Eq. kinemat_constraint) over "
        "xi = h/H in [0, 0.99] and kappa = l/H in [0.05, 2] (log scale). The shape of a "
        "string fountain depends on l, h, H only. Star: the paper's example xi = 0.14, "
        f"kappa = 0.165, qbar = {ex.qH:.2f} (the paper's caption quotes 44.4)."
    )
    return fig, caption


PAPER_E2 = {"A": 2e-4, "B": 4e-4, "C": 8e-4}
"""The paper's ``e2`` (m^2) of fountains A-C; its ``e1`` (1e-5, 2e-5) multiplies the
tension and has no origin in a bending moment, so it is not part of the stiff theory."""


@dataclass(frozen=True)
class PaperCurve:
    """One fountain of Fig. "schematic_chain_fountain" from the launch (origin)."""

    label: str
    s: np.ndarray
    x: np.ndarray
    y: np.ndarray
    alpha: np.ndarray
    T_bar: np.ndarray

    @property
    def h(self) -> float:
        """Vertex height above the launch (m)."""
        return float(self.y.max())

    @property
    def l(self) -> float:  # noqa: E743 - the paper's name
        """Landing, horizontally from the launch (m)."""
        return float(self.x[-1])


PAPER_START_E = 1e-4
"""The loosest stiffness (m^2) whose steady fountain the example's catenary guess reaches;
the fountains A-C are continued upwards from it."""


def paper_stiff(e2: float) -> StiffFountain | None:
    """The steady stiff fountain of the paper's example launch at ``e = e2`` (m^2) on the
    branch continued upwards from :data:`PAPER_START_E` in steps of at most 25 % (a second
    branch, which solves from the catenary's guess find, exists above 5.3e-4 m^2 and folds
    there; ``research/stiff_branches.py`` maps both). ``None`` where none is found."""
    return paper_stiffs([e2])[e2]


def paper_stiffs(es: list[float]) -> dict[float, StiffFountain | None]:
    """:func:`paper_stiff` at each of ``es``, along one continuation through all of them."""
    base = example_fountain()
    top = max(max(es), PAPER_START_E)
    n = max(2, math.ceil(math.log(top / PAPER_START_E) / math.log(1.25)) + 1)
    path = sorted({float(e) for e in np.geomspace(PAPER_START_E, top, n)} | set(es))
    found = continued(base.v, base.alpha0, base.H, base.TE_bar, path)
    return {e: found[path.index(e)] for e in es}


def paper_stiff_fountains() -> dict[str, PaperCurve]:
    """Fountains A, B, C (the steady stiff theory at the paper's ``e2``), D (the catenary,
    ``k = 0.377``) and D' (the same curve at ``k = 0.430``), all launched as the example
    catenary is (5.10 m/s at 82.0 deg, ``qH = 44.20``) onto the floor 2 m below pulling with
    ``Tbar_E = 0.123`` (:func:`paper_stiff`)."""
    base = example_fountain()
    out: dict[str, PaperCurve] = {}
    solved = paper_stiffs(list(PAPER_E2.values()))
    for name, e2 in PAPER_E2.items():
        f = solved[e2]
        if f is None:
            empty = np.array([np.nan])
            out[name] = PaperCurve(f"{name}: e2={e2:.0e}, no steady solution found", empty,
                                   empty, empty, empty, empty)
            continue
        out[name] = PaperCurve(f"{name}: e2={e2:.0e}", f.s, f.x, f.y, f.alpha, f.T_bar)
    for name, k in (("D", base.k), ("D'", 0.430)):
        x, y = base.curve(600)
        x0, y0 = base.start
        s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])
        alpha = -np.arctan(np.sinh(base.q * x))
        out[name] = PaperCurve(f"{name}: catenary, k={k:.3f}", s, x - x0, y - y0, alpha,
                               base.with_k(k).tension_bar(y) if name == "D'" else
                               base.tension_bar(y))
    return out


_COLORS = {"A": "tab:green", "B": "tab:red", "C": "tab:purple", "D": "tab:blue", "D'": "tab:orange"}


def fig_schematic_chain_fountain(
    fountains: dict[str, PaperCurve] | None = None,
) -> tuple[Figure, str]:
    """Fig. "schematic_chain_fountain" recomputed with the steady stiff-chain theory:
    fountains A-D, shape, ``Tbar(s)``, ``alpha(s)``."""
    fs = paper_stiff_fountains() if fountains is None else fountains
    fig = plt.figure(figsize=(9.0, 6.4), layout="constrained")
    gs = fig.add_gridspec(2, 2, width_ratios=[1, 1.6])
    ax_shape = fig.add_subplot(gs[:, 0])
    ax_T = fig.add_subplot(gs[0, 1])
    ax_a = fig.add_subplot(gs[1, 1], sharex=ax_T)
    for name, b in fs.items():
        lw = 1.0 if name.startswith("D") else 1.2
        ls = "--" if name == "D'" else "-"
        c = _COLORS.get(name)
        ax_shape.plot(b.x, b.y, color=c, lw=lw, ls=ls, label=b.label)
        ax_T.plot(b.s, b.T_bar, color=c, lw=lw, ls=ls)
        ax_a.plot(b.s, b.alpha, color=c, lw=lw, ls=ls)
    ax_shape.axhline(-EXAMPLE["H"], color="0.5", lw=0.8)
    ax_shape.set_aspect("equal")
    ax_shape.set_xlabel("x from launch [m]")
    ax_shape.set_ylabel("y from launch [m]")
    fig.legend(fontsize=8, loc="outside lower center", ncols=3)
    ax_shape.set_title("fountain")
    ax_T.axhline(0, color="0.5", lw=0.6)
    ax_T.set_ylabel(r"$\bar T = T/(\lambda v^2)$")
    ax_T.set_title("scaled tension")
    ax_a.set_ylabel(r"$\alpha$ [rad]")
    ax_a.set_xlabel("arc length s from launch [m]")
    rows = ", ".join(f"{n}: h={b.h:.3f} m, l={b.l:.3f} m" for n, b in fs.items() if n != "D'")
    caption = (
        "Fig. schematic_chain_fountain: the paper's fountains A-D recomputed with the steady "
        "stiff-chain theory (chainfountain.theory.stiff: bending moment M = e2*lambda*v^2*"
        "alpha', guide fixing the launch point and direction, floor end free of moment and "
        "shear and pulled with Tbar_E), H = 2 m, xi = 0.14, kappa = 0.165 (qH = 44.20), all "
        "launched at the example catenary's 5.10 m/s and 82.0 deg onto a floor pulling with "
        "Tbar_E = 0.123; the paper's e1 (a tension-dependent term with no bending origin) is "
        f"left out. Overshoot height and landing distance: {rows}. D and D' (k = 0.430, "
        "dashed) have the same shape; only the tension differs (Tbar_E = 0.123 and ~0). "
        "A-C lie on the branch continued from e = 1e-4 m^2 (docs/stiff_chain.md): they rise "
        "higher than the catenary, as the paper's do, but land wider, where the paper's land "
        "narrower."
    )
    return fig, caption


def fig_force_ranges(n: int = 200) -> tuple[Figure, str]:
    """Fig. "force_ranges": admissible ``Tbar_0``, ``Tbar_E`` against ``k`` (Eq. range_forces)."""
    f = example_fountain()
    k_lo, k_hi = f.k_range()
    k = np.linspace(k_lo, k_hi, n)
    T0 = 1 - k / f.q - k * f.h
    TE = 1 - k / f.q - k * (f.h + f.H)
    fig, ax = plt.subplots(figsize=(6.4, 4.4), layout="constrained")
    ax.axhspan(0.5, 1.0, color="tab:blue", alpha=0.12, label=r"paper: $\bar T_0\in(1/2,1)$")
    ax.axhspan(0.0, 0.5, color="tab:orange", alpha=0.12, label=r"paper: $\bar T_E\in[0,1/2)$")
    ax.plot(k, T0, color="tab:blue", lw=2, label=r"$\bar T_0 = 1 - k/q - kh$")
    ax.plot(k, TE, color="tab:orange", lw=2, label=r"$\bar T_E = 1 - k/q - k(h+H)$")
    for kk, txt in ((0.377, "k = 0.377 (5.1 m/s)"), (f.k_max, f"k_max = {f.k_max:.4f}")):
        ax.axvline(kk, color="0.3", lw=0.8, ls=":")
        ax.text(kk, 1.02, txt, rotation=0, ha="center", va="bottom", fontsize=8)
    ax.axvline(k_lo, color="0.3", lw=0.8, ls=":")
    ax.text(k_lo, 1.02, r"$1/(2H)$", ha="center", va="bottom", fontsize=8)
    ax.set_xlim(k_lo - 0.02, k_hi + 0.02)
    ax.set_ylim(-0.05, 1.1)
    ax.set_xlabel(r"$k = g/v^2$ [1/m]")
    ax.set_ylabel("scaled end tension")
    ax.legend(fontsize=8, loc="center left")
    g = f.g
    sec = ax.secondary_xaxis(
        "bottom",
        functions=(
            lambda kk: np.sqrt(g / np.clip(kk, 1e-9, None)),
            lambda v: g / np.clip(v, 1e-9, None) ** 2,
        ),
    )
    sec.set_xlabel("v [m/s]")
    sec.spines["bottom"].set_position(("outward", 36))
    fr = f.force_ranges()
    caption = (
        "Fig. force_ranges: end tensions of the example fountain (H = 2 m, xi = 0.14, "
        f"kappa = 0.165, qH = {f.qH:.2f}) over the admissible k in (1/(2H), k_max] = "
        f"({k_lo:.3f}, {k_hi:.4f}] (paper Eq. k_upper_bound and the energy bound v < "
        f"sqrt(2gH)). Tbar_0 spans [{fr.T0[0]:.3f}, {fr.T0[1]:.3f}), Tbar_E spans "
        f"[{fr.TE[0]:.3f}, {fr.TE[1]:.3f}); shaded: the paper's general ranges "
        "(1/2, 1) and [0, 1/2) (Eq. range_forces). Tbar_0 - Tbar_E = k*H throughout; "
        "at k_max the floor force vanishes."
    )
    return fig, caption
