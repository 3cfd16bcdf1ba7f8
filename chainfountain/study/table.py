"""A sweep's results: each point's numbers as flat columns, the table (Parquet and CSV)
and the figure."""

from __future__ import annotations

import csv
import io as stdio
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

from chainfountain import atomic

if TYPE_CHECKING:
    from chainfountain.study.sweep_file import Sweep


def flatten(summary: dict[str, Any]) -> dict[str, Any]:
    """The numbers of a ``summary.json`` as flat columns (``theory.rel_error.h`` becomes
    ``theory_rel_error_h``; a list of numbers one column per item, ``window_0`` and
    ``window_1``; other lists and texts other than the level's name are left out)."""
    out: dict[str, Any] = {}

    def walk(prefix: str, obj: Any) -> None:
        if isinstance(obj, dict):
            for k, v in obj.items():
                walk(f"{prefix}_{k}" if prefix else str(k), v)
        elif isinstance(obj, list) and all(
                x is None or (isinstance(x, int | float) and not isinstance(x, bool))
                for x in obj):
            for i, x in enumerate(obj):
                out[f"{prefix}_{i}"] = x
        elif isinstance(obj, bool):
            out[prefix] = obj
        elif isinstance(obj, int | float) or obj is None:
            out[prefix] = obj

    walk("", {k: v for k, v in summary.items()
              if k not in ("outputs", "write_failed", "analysis_failed", "ended_early")})
    return out


def write_table(rows: list[dict], out: Path) -> None:
    """``results.parquet`` and ``results.csv`` (each atomically), one row per point."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    cols: list[str] = []
    for r in rows:
        cols += [c for c in r if c not in cols]
    table = pa.table({c: _column([_cell(r.get(c)) for r in rows]) for c in cols}) \
        if rows else pa.table({})
    with atomic.atomic_path(out / "results.parquet") as tmp:
        pq.write_table(table, tmp)
    buf = stdio.StringIO()
    w = csv.DictWriter(buf, fieldnames=cols, lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow({c: r.get(c) for c in cols})
    atomic.write_text(out / "results.csv", buf.getvalue())


def _column(cells: list[Any]) -> Any:
    """One column: its values as they are, or as texts when they mix types Arrow cannot
    hold in one column (a number and a text)."""
    import pyarrow as pa

    try:
        return pa.array(cells)
    except (pa.ArrowInvalid, pa.ArrowTypeError):
        return pa.array([None if c is None else str(c) for c in cells], type=pa.string())


def _cell(x: Any) -> Any:
    return None if isinstance(x, float) and not math.isfinite(x) else x


def figure(sweep: Sweep, rows: list[dict], path: Path) -> Path | None:
    """The vertex height's error against the paper (a scene: its closed form's scale
    or free-end speed error) over the first swept field, one line per combination of the
    others (``None`` when no point has the figure)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    key, y_label = "theory_rel_error_h", "vertex height error against the paper (%)"
    form = sweep.base.sim.scene.closed_form  # "none" outside a scene (its table's default)
    if form == "scale":
        key, y_label = "closed_form_force_rel_error", "scale's error against 3 lambda g y (%)"
    elif form == "folded_fall":
        key = "closed_form_speed_rel_error_2"
        y_label = "free end's speed error at 3/4 of the fall (%)"
    names = sweep.columns or ["seed"]
    x_name, others = names[0], names[1:]
    groups: dict[tuple, list[tuple[float, float, bool]]] = {}
    for r in rows:
        y, x = r.get(key), r.get(x_name)
        if r.get("status") != "done" or y is None or not isinstance(x, int | float):
            continue
        seed = (r.get("seed"),) if x_name != "seed" else (None,)
        groups.setdefault(tuple(r.get(o) for o in others) + seed, []).append(
            (float(x), 100.0 * float(y), r.get("steady") is not False))
    if not groups:
        return None
    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=110)
    unsteady = False
    for g, pts in sorted(groups.items(), key=lambda kv: str(kv[0])):
        pts.sort()
        label = ", ".join(f"{o} = {v}" for o, v in zip([*others, "seed"], g, strict=True)
                          if v is not None)
        (line,) = ax.plot([p[0] for p in pts], [p[1] for p in pts], "-", label=label or None)
        for x, y, steady in pts:
            ax.plot([x], [y], "o", color=line.get_color(),
                    markerfacecolor=line.get_color() if steady else "none")
            unsteady |= not steady
    ax.axhline(0.0, color="0.5", lw=0.8)
    ax.set_xlabel(x_name)
    ax.set_ylabel(y_label)
    run = f"{sweep.duration:g} s per point" if sweep.duration else "the level's duration"
    ax.set_title(f"sweep of {sweep.base_name} ({run}"
                 + ("; hollow: never steady" if unsteady else "") + ")", fontsize=10)
    if len(groups) > 1:
        ax.legend(fontsize=7)
    fig.tight_layout()
    with atomic.atomic_path(path) as tmp:
        fig.savefig(tmp, format="png")
    plt.close(fig)
    return path
