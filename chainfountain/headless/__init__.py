"""Headless runs: step a level without a window, record, compare with theory, write files.

Outputs (all written atomically into the output folder):

- ``summary.json``: headline measurements over the steady window and the
  paper's prediction with relative errors;
- ``tensions.csv``: time, joint index, arc length, x, y, signed tension (N),
  scaled tension, decimated to at most ``MAX_TENSION_SAMPLES`` time samples;
- ``speed.csv``: one row per recorded sample (speed, vertex, stretch, ...);
- ``snapshot.png``: the chain at the end with the predicted catenary (metres);
- apparatus levels: ``apparatus.csv``, one row per recorded apparatus sample (roller
  speeds, end tensions, cart forces, the lower plate's reaction, ...);
- the 'open' arrangement: ``reaction.png``, the lower plate's reaction against time
  with the paper's rate.

``summary.json`` lists the files written under ``outputs``; :class:`RunSummary` is its
typed form (:mod:`chainfountain.headless.report`), each kind's section built by one function
of :data:`SECTIONS`.
"""

from chainfountain.exits import EXIT_STATUS
from chainfountain.headless.files import MAX_TENSION_SAMPLES, write_reaction_figure, write_snapshot
from chainfountain.headless.report import OLD_NAMES, RunSummary, json_safe
from chainfountain.headless.run import (
    DEFAULT_DURATION,
    DEFAULT_OUTPUTS,
    FORMING_DURATION,
    MACHINE_FORMING_DURATION,
    check_run,
    default_duration,
    default_out_dir,
    describe_outputs,
    exit_status,
    prepare_out_dir,
    run_and_record,
    run_level,
    write_outputs,
)
from chainfountain.headless.stepper import FOUNTAIN_SERIES, SceneRun, Stepper, seeded, simulate
from chainfountain.headless.stepping import (
    LOG_PROGRESS_EVERY,
    MAX_PROFILES,
    MAX_SAMPLES,
    Ending,
    Interrupted,
)
from chainfountain.headless.summary import SECTIONS, summarize

__all__ = [
    "DEFAULT_DURATION", "DEFAULT_OUTPUTS", "EXIT_STATUS", "FORMING_DURATION",
    "MACHINE_FORMING_DURATION", "LOG_PROGRESS_EVERY", "MAX_PROFILES", "MAX_SAMPLES",
    "MAX_TENSION_SAMPLES", "Ending", "Interrupted", "check_run", "default_duration",
    "default_out_dir", "describe_outputs", "exit_status",
    "json_safe", "prepare_out_dir", "run_and_record", "run_level", "simulate", "summarize",
    "write_reaction_figure", "write_snapshot", "FOUNTAIN_SERIES", "SceneRun", "Stepper",
    "seeded", "write_outputs", "OLD_NAMES", "RunSummary", "SECTIONS",
]
