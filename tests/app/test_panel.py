"""The control panel's texts (:mod:`chainfountain.app.panel`): plain words in the student
view, the field's path and the level file's units in the expert view."""

from __future__ import annotations

import pytest

from chainfountain.app import controls, spans
from chainfountain.app.panel import tooltip


@pytest.mark.parametrize(("name", "path"), [("apparatus_fold_gripped", "carts[0].mass"),
                                            ("ideal_fold", "feed.lower_cart_force"),
                                            ("beaker", "beaker.drop")])
def test_a_student_s_tooltip_says_what_the_field_is_without_its_path(level, name, path):
    lvl = level(name)
    spec = spans.narrowed(lvl, controls.spec_for(lvl.sim, path), lvl.sim)
    student, expert = tooltip(spec, expert=False), tooltip(spec, expert=True)
    assert path not in student and "level file" not in student and "Changing it" in student
    assert expert.startswith(f"{path}: ")
    if path == "carts[0].mass":  # shown in g, kept in kg
        assert "in the level file a number in (1e-06, 1000] (kg)" in expert
