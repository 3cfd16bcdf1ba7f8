"""The exit statuses of ``chainfountain run``, in one table (:data:`EXITS`):
:func:`chainfountain.headless.exit_status` computes them, the command's ``--help``
(:data:`EXIT_HELP`) and the README's table (:func:`markdown_table`, checked by
``tests/cli/test_headless.py``) describe them."""

from __future__ import annotations

from typing import NamedTuple


class Exit(NamedTuple):
    """One exit status: its number(s) as shown, and what it means."""

    status: str
    meaning: str


EXITS: tuple[Exit, ...] = (
    Exit("0", "the run completed"),
    Exit("2", "bad input: one line naming the flag or level field, the value and what is "
         "allowed (nothing is run)"),
    Exit("3", "the run ended early: an apparatus table used up, the fold collapsed, or the "
         "simulation diverged"),
    Exit("4", "an output could not be written (a full disk): named in `write_failed` or on "
         "the terminal"),
    Exit("130, 143", "interrupted by Ctrl-C (SIGINT) or SIGTERM"),
)
"""Every exit status of ``chainfountain run``."""

EXIT_STATUS = {None: 0, "machine": 3, "diverged": 3}
"""Exit status by :attr:`~chainfountain.headless.stepping.Ending.cause` (an interrupted
run's: 128 + the signal's number)."""
WRITE_FAILED = 4
"""Exit status when an output could not be written."""
ENDED_EARLY = 3
"""Exit status of a run that ended early for a cause not in :data:`EXIT_STATUS`."""

EXIT_HELP = ("Exit status: " + "; ".join(f"{e.status} {e.meaning.replace('`', '')}"
                                         for e in EXITS)
             + ". Whenever a run has started, its outputs cover the part simulated and "
             "summary.json says why it ended (ended_early).")
"""The exit statuses in one paragraph, for ``chainfountain run --help``."""


def markdown_table() -> str:
    """The exit statuses as the README's table."""
    rows = ["| status | meaning |", "|---|---|"]
    rows += [f"| {e.status} | {e.meaning} |" for e in EXITS]
    return "\n".join(rows)
