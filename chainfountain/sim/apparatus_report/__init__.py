"""Measuring a running pulley apparatus (:mod:`chainfountain.sim.apparatus`).

:func:`analyse` turns one recorded step into tensions along the path (the exact
momentum balance of :mod:`chainfountain.sim.measure`, with the guide joints'
impulses reconstructed), speeds and the fountain's shape; :func:`report` compares
a run's window with the paper's apparatus relations and this model's rig laws
(the ``apparatus`` object of ``summary.json``).

Modules: :mod:`.sample` (:func:`analyse`, :class:`ApparatusSample`), :mod:`.impulses`
(the lower guides' impulses the contacts miss), :mod:`.summary` (:func:`report`,
:func:`catenary_through`).
"""

from chainfountain.sim.apparatus_report.impulses import (
    guided_impulses,
    open_guide_impulses,
    pivot_offset,
)
from chainfountain.sim.apparatus_report.sample import ApparatusSample, analyse
from chainfountain.sim.apparatus_report.summary import catenary_through, report

__all__ = [
    "ApparatusSample",
    "analyse",
    "catenary_through",
    "guided_impulses",
    "open_guide_impulses",
    "pivot_offset",
    "report",
]
