"""The fold-variant runs under their old name, for the tests of ``sim/pickup.py`` and
``sim/cart_step.py`` that still live in this folder (the runs are
:mod:`tests.sim.apparatus.runs`; this file goes when those tests move)."""

from tests.sim.apparatus.runs import load_on_path, load_undamped

__all__ = ["load_on_path", "load_undamped"]
