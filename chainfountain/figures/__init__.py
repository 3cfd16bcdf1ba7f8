"""Figures of the paper, recomputed (matplotlib, Agg backend).

``main(out_dir)`` writes every registered figure as ``<name>.png``, ``<name>.svg``
and the caption ``<name>.txt``, each atomically. The simulator-backed figures
("apparatus", "sim_vs_theory") are plotting hooks in :mod:`chainfountain.figures.hooks`
that take plain arrays; "sim_vs_theory" is registered through
:mod:`chainfountain.figures.simulated`, which runs a shipped feed level.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Sequence
from pathlib import Path

from matplotlib.figure import Figure
from tqdm import tqdm

from chainfountain.figures._io import save_figure
from chainfountain.figures.apparatus_design import fig_apparatus_paper
from chainfountain.figures.hooks import fig_apparatus, fig_sim_vs_theory
from chainfountain.figures.paper import (
    fig_force_ranges,
    fig_schematic_chain_fountain,
    fig_sol,
)
from chainfountain.figures.simulated import fig_sim_vs_theory_run

__all__ = [
    "FIGURES",
    "fig_apparatus",
    "fig_force_ranges",
    "fig_schematic_chain_fountain",
    "fig_sim_vs_theory",
    "fig_sol",
    "main",
    "save_figure",
]

FIGURES: dict[str, Callable[[], tuple[Figure, str]]] = {
    "sol": fig_sol,
    "force_ranges": fig_force_ranges,
    "schematic_chain_fountain": fig_schematic_chain_fountain,
    "sim_vs_theory": fig_sim_vs_theory_run,
    "apparatus": fig_apparatus_paper,
}


def main(
    out_dir: Path | str,
    progress: bool | None = None,
    names: Sequence[str] | None = None,
    formats: Sequence[str] = ("png", "svg"),
    dpi: int = 110,
) -> list[Path]:
    """Write the paper's figures into ``out_dir``; return the written paths.

    ``progress``: show a tqdm bar on stderr (default: only if stderr is a TTY).
    ``names``: subset of :data:`FIGURES` (default all). Unknown names raise ``KeyError``.
    """
    chosen = list(FIGURES) if names is None else list(names)
    unknown = [n for n in chosen if n not in FIGURES]
    if unknown:
        raise KeyError(f"unknown figure(s) {unknown}; known: {sorted(FIGURES)}")
    if progress is None:
        progress = sys.stderr.isatty()
    written: list[Path] = []
    bar = tqdm(chosen, desc="figures", unit="fig", disable=not progress, file=sys.stderr)
    for name in bar:
        bar.set_postfix_str(name)
        fig, caption = FIGURES[name]()
        written += save_figure(fig, Path(out_dir), name, caption, formats=formats, dpi=dpi)
    return written
