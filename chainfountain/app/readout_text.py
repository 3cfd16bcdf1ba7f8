"""The readout's rows in words: plain words for a class (the paper's symbols beside them)
or the paper's symbols for an expert (E switches). No pygame here: a row names its colour
and :mod:`chainfountain.app.draw` paints it."""

from __future__ import annotations

import math
from dataclasses import dataclass

from chainfountain.app.readout import Readout


@dataclass(frozen=True)
class Row:
    """One readout row: its text, a colour name (``text``, ``dim``, ``t0``, ``te``, ``ok``,
    ``warn``) and, in the plain readout, the paper's symbol for it (drawn at the right)."""

    text: str
    colour: str = "text"
    symbol: str = ""


def _num(v: float | None, fmt: str = ".4g") -> str:
    return "--" if v is None or not math.isfinite(v) else format(v, fmt)


def plain_rows(ro: Readout, lam: float) -> list[Row]:
    """The readout in plain words, SI units, for a class. ``lam``: the chain's mass per
    length (kg/m), which turns the scaled end tensions into newtons (``T = Tbar*lambda*v^2``,
    paper eq. for ``Tbar``)."""
    rows = [] if ro.measured else [Row("predicted: no fountain yet", "dim")]
    rows.append(Row(f"chain speed  {_num(ro.v, '.2f')} m/s", "text", "v"))
    top = f"top  {_num(ro.h, '.2f')} m above the {ro.origin}"
    rows.append(Row(top, "text", "h"))
    if math.isfinite(ro.paper_h):
        who = "the paper" if ro.theory == "catenary" else f"the {ro.theory_label}"
        rows.append(Row(f"   {who} predicts {ro.paper_h:.2f} m", "dim"))
    elif ro.theory_note:
        rows.append(Row(f"   {ro.theory_note}", "warn"))
    if ro.settle_note:
        rows.append(Row(f"   {ro.settle_note}", "warn"))
    rows.append(Row(f"lands  {_num(ro.l, '.2f')} m away, {_num(ro.H, '.2f')} m down",
                    "text", "l, H"))
    if ro.origin != "launch":
        return rows  # a beaker: the pile's push is in the Biggins & Warner line below
    flux = lam * ro.v * ro.v if math.isfinite(ro.v) else math.nan
    for name, bar, theory, col, sym in (
            ("pull at the launch", ro.T0_bar, ro.T0_theory, "t0", "Tbar_0"),
            ("pull at the landing", ro.TE_bar, ro.TE_theory, "te", "Tbar_E")):
        newton = bar * flux
        who = "paper" if ro.theory == "catenary" else "theory"
        paper = f"  ({who} {theory * flux:.2f})" if math.isfinite(theory * flux) else ""
        rows.append(Row(f"{name}  {_num(newton, '.2f')} N{paper}", col, sym))
    return rows


def expert_rows(ro: Readout) -> list[Row]:
    """The readout in the paper's symbols (``k = g/v^2``, ``q``, scaled tensions)."""
    src = "measured" if ro.measured else "predicted"
    f3 = ".3f"
    return [
        Row(f"{src}; theory: the catenary through the ends" if ro.theory == "catenary"
            else f"{src}; theory: {ro.theory_label}, {ro.joints}", "dim"),
        Row(f"v  {_num(ro.v, f3)} m/s     k = g/v^2  {_num(ro.k)} 1/m"),
        Row(f"q  {_num(ro.q)} 1/m     h  {_num(ro.h, f3)} m"),
        Row(f"l  {_num(ro.l, f3)} m     H  {_num(ro.H, f3)} m"),
        Row(f"Tbar_0  {_num(ro.T0_bar, f3)}  (theory {_num(ro.T0_theory, f3)})", "t0"),
        Row(f"Tbar_E  {_num(ro.TE_bar, f3)}  (theory {_num(ro.TE_theory, f3)})", "te"),
    ]


def readout_rows(ro: Readout, lam: float, expert: bool, stopped: bool = False) -> list[Row]:
    """The rows above the plots: the numbers (plain or expert) and whether it is steady
    (``stopped``: the run stopped itself, and the status says so instead)."""
    rows = expert_rows(ro) if expert else plain_rows(ro, lam)
    if stopped:
        rows.append(Row("the run has stopped (R starts it again)", "warn"))
    elif expert:
        rows.append(Row("steady" if ro.steady else "not steady (yet)",
                        "ok" if ro.steady else "warn"))
    else:
        rows.append(Row("steady: it keeps its shape" if ro.steady else
                        "still forming (not steady yet)", "ok" if ro.steady else "warn"))
    return rows
