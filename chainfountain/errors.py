"""Errors that reach the user as one clear line instead of a traceback."""


class UserError(Exception):
    """Bad input from a user (flag, level file, GUI value).

    The message names the field, the value and what is allowed. The CLI prints
    it as one line and exits with status 2.
    """
