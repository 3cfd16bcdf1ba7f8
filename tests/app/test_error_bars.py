"""The expert view's error line for a contact machine: the gripped presets' measured step
moves at their settings, elsewhere how to refine (:mod:`chainfountain.app.error_bars`)."""

from __future__ import annotations

from chainfountain.app.error_bars import error_bars_line
from chainfountain.sim.apparatus_report import step_change
from chainfountain.sim.world import Simulation
from chainfountain.study.changes import with_changes


def test_a_gripped_preset_shows_its_measured_step_moves(level) -> None:
    line = error_bars_line(Simulation(level("apparatus_fold_gripped").sim))
    m = step_change.MOVES
    assert f"Tbar_0 +-{m['T0_bar']:.3f}" in line and "refined at the presets" in line
    assert f"vertex +-{100 * m['vertex_y_rel_error']:.1f} %" in line


def test_a_contact_machine_off_the_refined_settings_says_how_to_refine(level) -> None:
    for lvl in (level("apparatus_floor"),
                with_changes(level("apparatus_fold_gripped"), {"chain.link_length": 0.018})):
        line = error_bars_line(Simulation(lvl.sim))
        assert "not refined here" in line and "--error-bars" in line
