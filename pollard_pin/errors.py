"""The exception root and its families.

Every error the package raises on purpose derives from :class:`PollardError`, so a caller (and
the CLI, which prints it as one line) catches one class. Each family also derives from the
builtin it always was (``ValueError`` for bad input, ``RuntimeError`` for a solve that failed,
``OSError`` for a destination), so code written against those keeps working.
"""
from __future__ import annotations


class PollardError(Exception):
    """The root of the package's own errors: one line for the user, never a traceback."""


class InputError(PollardError, ValueError):
    """A value, file or option the package cannot use: names what, where and how far off."""


class SolveError(PollardError, RuntimeError):
    """A computation that could not be carried out for valid input (a pose out of reach, a
    singular system, a simulation that left its stated tolerance)."""


class DestinationError(PollardError, OSError):
    """An output destination that cannot be written."""

    def __str__(self) -> str:
        return self.args[0] if self.args else "cannot write the output"
