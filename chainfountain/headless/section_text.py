"""The terminal's lines about each section of a run's summary, one function per section:
:data:`STEADINESS` (what the run's second line says instead of "steady since ...") and
:data:`LINES` (the lines after it), each keyed by the section's name in
:data:`chainfountain.headless.summary.SECTIONS`."""

from __future__ import annotations

import textwrap
from collections.abc import Callable
from typing import Any

from chainfountain.headless.report import RunSummary, Theory


def pct(x: float | None) -> str:
    """A relative error as a signed percentage (``n/a`` without one)."""
    return "n/a" if x is None else f"{100 * x:+.2f} %"


def _open_steadiness(o: dict[str, Any] | None) -> str | None:
    """The paper's non-stationary arrangement: its measurement is the reaction's rate."""
    if not o:
        return None
    rate, pred = o.get("tail_reaction_rate_N_per_s"), o.get("tail_reaction_rate_predicted")
    text = "non-stationary by design"
    if rate is not None and pred:
        text += (f"; lower plate reaction grows at {rate:.3f} N/s, lambda g v "
                 f"{pred:.3f} N/s ({pct(rate / pred - 1.0)})")
    return text


STEADINESS: dict[str, Callable[[Any], str | None]] = {
    "apparatus": lambda ap: _open_steadiness(ap.get("open")),
    "open": _open_steadiness,
}
"""Sections that say, instead of the window's steadiness, how the run is measured (the
first that has something to say)."""


def apparatus_lines(ap: dict[str, Any], s: RunSummary) -> list[str]:
    """A braked fold selects its speed: the measured against the paper's laws'; a fold's
    flight against the paper's fountain (``flight``: the relation across it and the
    catenary through its ends, with the means' standard errors)."""
    v_sel = (ap.get("predicted_paper") or {}).get("v_steady")
    v_meas = (ap.get("measured") or {}).get("v")
    if not v_meas:
        return []
    w0, w1 = ap["window"]
    if ap.get("variant") != "fold":
        return _floor_lines(ap, w0, w1) + step_lines(((ap.get("flight") or {}).get("step"))
                                                     or {})
    lines = []
    f = ap.get("flight") or {}

    def bar(x: float | None) -> str:
        return f" +- {x:.3f}" if x is not None else ""

    if v_sel:  # two lines of at most 100 characters
        lines += [f"  over {w0:.1f}-{w1:.1f} s: speed {v_meas:.3f}{bar(f.get('v_se'))} m/s;",
                  f"    the carts and the brake select {v_sel:.3f} m/s by the paper's laws "
                  f"({pct(v_meas / v_sel - 1.0)})"]
    if f.get("relation_miss") is not None and f.get("T0_bar") is not None:
        vert = f.get("vertex_y_rel_error")
        lines += [  # two lines of at most 100 characters
            f"  the flight: Tbar_0 {f['T0_bar']:.3f}{bar(f.get('T0_bar_se'))}, Tbar_E "
            f"{f['TE_bar']:.3f}{bar(f.get('TE_bar_se'))}; Tbar_0 - Tbar_E - k dy "
            f"{f['relation_miss']:+.3f}{bar(f.get('relation_miss_se'))}",
            f"    (k H {f['kH']:.3f}); vertex {pct(vert)} off the catenary through the ends "
            "(+-: statistical, not the step's)"]
    return lines + step_lines(f.get("step") or {})


def _floor_lines(ap: dict[str, Any], w0: float, w1: float) -> list[str]:
    """A floor machine selects its speed by its pick-up: the measured against this model's
    pick-up law and the paper's (``speed_selection``)."""
    sel = ap.get("speed_selection") or {}
    v, rig, paper = sel.get("v_measured"), sel.get("v_rig_2cm"), sel.get("v_paper_p_half")
    if not (v and rig and paper):
        return []
    return [f"  over {w0:.1f}-{w1:.1f} s: speed {v:.3f} m/s; its cart selects {rig:.3f} m/s by "
            f"this model's pick-up ({pct(v / rig - 1.0)}),",
            f"    {paper:.3f} m/s by the paper's ({pct(v / paper - 1.0)}: docs/apparatus.md, "
            "\"Pick-up force\")"]


def step_lines(step: dict[str, Any]) -> list[str]:
    """How far halving the step moved the flight's figures: this run's refinement
    (``run --error-bars``) or the presets' measured moves; or why neither."""
    moves = step.get("moves")
    if not moves:
        return textwrap.wrap(f"the step's error: {step['how']}", 96, initial_indent="  ",
                             subsequent_indent="    ", break_on_hyphens=False) \
            if step.get("how") else []

    def move(key: str, scale: float = 1.0, fmt: str = ".3f") -> str:
        m = moves.get(key)
        return "n/a" if m is None else f"{scale * m:{fmt}}"

    if "half_dt" not in step:
        return [f"  halving the step moved them by up to {move('T0_bar')}, "
                f"{move('TE_bar')}, {move('relation_miss')} and "
                f"{move('vertex_y_rel_error', 100, '.1f')} % (refined at the presets)"]
    return [f"  again at half the step ({1e6 * step['half_dt']:g} us), the speed moved "
            f"{move('v_rel', 100, '.2f')} %, Tbar_0 {move('T0_bar')}, Tbar_E {move('TE_bar')},",
            f"    the relation {move('relation_miss')}, the vertex "
            f"{move('vertex_y_rel_error', 100, '.1f')} % (one run each: step and "
            "statistics together)"]


def beaker_lines(bk: dict[str, Any], s: RunSummary) -> list[str]:
    """The speed, the rise and the pile's push ``alpha`` (Biggins & Warner)."""
    a = bk.get("alpha")
    if not a:
        return []
    w0, w1 = bk["window_s"]
    lines = [
        f"  over {w0:.1f}-{w1:.1f} s: speed {bk['speed']:.3f} m/s (links the floor took), "
        f"top {bk['rise_above_rim']:.3f} m above the rim,",
        f"    {bk['rise_above_pickup']:.3f} m above the pick-up, which is "
        f"{bk['drop_from_pickup']:.3f} m above the floor",
        f"  the pile's push alpha (Biggins & Warner, beta = 0): {a['from_speed']:.3f} from "
        f"the speed, {a['from_rise']:.3f} from the rise",
        "    of a zero-width fountain"
        + (f", {a['from_paper_catenary']:.3f} from the paper's curve through the ends"
           if a.get("from_paper_catenary") is not None else "")]
    bars = bk.get("error_bars") or {}
    low, zero = bars.get("shortfall") or {}, bars.get("zero_step") or {}
    if "speed" in low and "rise_above_rim" in low:
        if bars.get("accuracy"):
            lines.append(f"  solver.accuracy = {100 * bars['accuracy']:g} % chose a "
                         f"{1e6 * bars['dt']:.3g}-us step")
        lines += [f"  discretisation error (error model, first order in the step): speed "
                  f"-0/+{100 * low['speed']:.0f} %,",
                  f"    top -0/+{100 * low['rise_above_rim']:.0f} %, alpha from the speed "
                  f"-0/+{100 * low['alpha_from_speed']:.0f} % (at a zero step: "
                  f"{zero['speed']:.2f} m/s, {zero['rise_above_rim']:.2f} m, "
                  f"{zero['alpha_from_speed']:.3f})"]
    elif bars.get("how"):
        lines.append(f"  discretisation error: {bars['how']}")
    return lines


def theory_lines(th: Theory, s: RunSummary) -> list[str]:
    """The vertex height and landing against the paper's (and a selecting machine's
    speed against its laws'); a stiff chain's against the stiff-chain theory, with the
    catenary's beside them, or why it has no steady fountain."""
    f = s.fountain
    if f is None or f.h is None or f.l is None:
        return []
    if th.stiff:
        return stiff_lines(th, f.h, f.l, f.v)
    err = th.rel_error
    own = th.at_speed
    if own and own.get("h") and own.get("l") and th.v and f.v:
        oe = own["rel_error"]
        return [f"  speed {f.v:.4f} m/s; the machine's laws select {th.v:.4f} m/s ({pct(err.v)})",
                f"  vertex height {f.h:.4f} m, landing {f.l:.4f} m; the paper's fountain",
                f"    at this speed:      {own['h']:.4f} m ({pct(oe['h'])}), "
                f"{own['l']:.4f} m ({pct(oe['l'])})",
                f"    at the laws' speed: {th.h:.4f} m ({pct(err.h)}), {th.l:.4f} m ({pct(err.l)})"]
    return [f"  vertex height {f.h:.4f} m (theory {th.h:.4f}, {pct(err.h)}), "
            f"landing {f.l:.4f} m (theory {th.l:.4f}, {pct(err.l)}), speed {f.v:.4f} m/s"
            + (f" (the machine's laws select {th.v:.4f}, {pct(err.v)})"
               if s.sections.get("machine") == "selects" and th.v else "")]


def stiff_lines(th: Theory, h: float, l: float, v: float | None) -> list[str]:  # noqa: E741
    """A stiff chain's vertex height and landing against the stiff-chain theory's (or
    why there is none) and the catenary's."""
    j = th.joints or {}
    joints = f"c = {j.get('c') or 0:.4g} N*m/rad, d = {j.get('d') or 0:.4g} N*m*s/rad"
    cat = th.catenary or {}
    ce = cat.get("rel_error") or {}
    speed = "" if v is None else f", speed {v:.4f} m/s"
    beside = (f"  the catenary (no joint resistance): vertex height {cat.get('h', 0):.4f} m "
              f"({pct(ce.get('h'))}), landing {cat.get('l', 0):.4f} m ({pct(ce.get('l'))})"
              if cat.get("h") is not None and cat.get("l") is not None else None)
    if th.h is None or th.l is None:
        lines = [f"  vertex height {h:.4f} m, landing {l:.4f} m{speed}: "
                 f"{th.why_none or f'no steady stiff fountain at {joints}'}"]
    else:
        err = th.rel_error
        lines = [f"  vertex height {h:.4f} m (stiff-chain theory {th.h:.4f}, {pct(err.h)}), "
                 f"landing {l:.4f} m (stiff-chain theory {th.l:.4f}, {pct(err.l)}){speed}; "
                 f"joints {joints}"]
    if j.get("settles") is False:
        lines.append(f"  the damper decays the stiff chain's standing waves by A = "
                     f"{j.get('damper_decay') or 0:.2g} a pass, below the 2.2 at which stiff "
                     "fountains settle: this one does not (docs/stiff_stability.md)")
    return lines + ([beside] if beside else [])


def error_bars_lines(bars: dict[str, Any], s: RunSummary) -> list[str]:
    """The refinement's error bars (``run --error-bars``)."""
    d = bars.get("error_bar")
    if not d:
        return []

    def bar(x: float | None) -> str:
        return "n/a" if x is None else f"+-{100 * x:.2f} %"

    return [f"  discretisation error bars at this link length and step (refinement): vertex "
            f"height {bar(d.get('h'))}, vertex x {bar(d.get('vertex_x'))}, landing "
            f"{bar(d.get('l'))}"]


def error_model_lines(m: dict[str, Any], s: RunSummary) -> list[str]:
    """The error model's bounds for the level's settings, or why the solver is short."""
    if m.get("bounds"):
        b = m["bounds"]
        at = "the flight at its speed: " if m.get("flight_at_speed") else ""
        chose = (f"the settings solver.accuracy = {100 * m['accuracy']:g} % chose "
                 f"({1000 * s.link_length:g}-mm links, {1e6 * s.dt:g}-us step)"
                 if m.get("accuracy") else "this link length, step and iterations")
        return [f"  discretisation error (error model) at {chose}:",
                f"    {at}vertex height +-{100 * b['h']:.2f} %, vertex x "
                f"+-{100 * b['vertex_x']:.2f} %, landing +-{100 * b['l']:.2f} %"]
    if m.get("solver_converged") is False:
        return [f"  WARNING: {m['why_none']}"]
    if m.get("why_none"):
        return [f"  discretisation error: no error model here: {m['why_none']}"]
    return []


LINES: dict[str, Callable[[Any, RunSummary], list[str]]] = {
    "apparatus": apparatus_lines,
    "beaker": beaker_lines,
    "theory": theory_lines,
    "error_bars": error_bars_lines,
    "error_model": error_model_lines,
}
"""Each section's lines, in the order printed."""


def section_lines(s: RunSummary) -> list[str]:
    """Every section's lines (:data:`LINES`), in order."""
    out: list[str] = []
    for name, fn in LINES.items():
        if s.sections.get(name):
            out += fn(s.sections[name], s)
    return out


def steadiness(s: RunSummary, default: str) -> str:
    """What the run's second line says about its steadiness (:data:`STEADINESS`)."""
    for name, fn in STEADINESS.items():
        text = fn(s.sections[name]) if s.sections.get(name) else None
        if text:
            return text
    return default
