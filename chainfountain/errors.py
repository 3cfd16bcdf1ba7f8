"""Errors that reach the user as one clear line instead of a traceback."""

from typing import NoReturn


class UserError(Exception):
    """Bad input from a user (flag, level file, GUI value).

    The message names the field, the value and what is allowed. The CLI prints
    it as one line and exits with status 2.
    """


class LevelError(UserError):
    """A level file or level value is not acceptable."""


def fail(where: str, field: str, msg: str) -> NoReturn:
    """Raise the one-line :class:`LevelError` ``"<where>: <field>: <msg>"`` (``msg`` names
    the value and what is allowed)."""
    raise LevelError(f"{where}: {field}: {msg}")


class RunEnded(UserError):
    """The simulated machine cannot go on (a machine's table used up, the fold
    collapsed). Not bad input: ``chainfountain run`` writes its outputs for the part
    that was simulated, marks ``summary.json`` ``ended_early`` and exits with status 3;
    the window pauses and shows the message.

    A message longer than a sentence (the fold's collapse explains its cause at length)
    comes with ``plain``: one sentence of what happened and what to change, which the
    window shows while the full message goes to the terminal. Without it ``plain`` is the
    message itself."""

    def __init__(self, message: str, plain: str | None = None) -> None:
        super().__init__(message)
        self.plain = plain or message


class OutputError(UserError):
    """An output file could not be written (a full disk, a folder made read-only). The
    CLI prints it as one line and exits with status 4; outputs already written stay."""
