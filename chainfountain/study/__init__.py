"""Studies from Python and at scale: a run as a function call (:func:`run`), a level
stepped by hand (:func:`start`, a :class:`Stepper`), levels changed field by field with
the same validation as files (:func:`with_changes`), and parameter sweeps run in parallel
(:mod:`chainfountain.study.sweep`)."""

from chainfountain.study.api import RunResult, Stepper, run, start
from chainfountain.study.changes import with_changes

__all__ = ["RunResult", "Stepper", "run", "start", "with_changes"]
