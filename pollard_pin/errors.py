"""The exception root and its families, and the one rule that sorts an error into a family.

Every error the package raises on purpose derives from :class:`PollardError` through exactly
one family, so a caller catches one class (the CLI prints any of them as one line and exits with
status 2). The rule:

- :class:`InputError`: the caller's value, file or option cannot be used as given: malformed,
  out of its stated range, inconsistent with another value, naming something that does not
  exist. It is decided from the input and its stated rules alone, before anything is solved;
  the fix is a different input.
- :class:`SolveError`: a valid request the computation could not carry out: the robot cannot
  do it (a pose out of reach, a singularity, a joint limit, a branch flip, a paint job no
  program meets) or a numerical method failed (no convergence, a simulation that left its
  tolerance). It is found by solving; the limit is the robot's or the method's.
- :class:`DestinationError`: an output destination that cannot be written.

So a pose asked for that is out of reach is a :class:`SolveError`, whichever solver finds it
(the closed form's ``UnreachableError`` and the kinematics' ``UnreachablePoseError`` alike):
reach is a property of the model, found by solving its kinematics, and the same pose is
reachable with other parameters; no rule of the value alone is broken. A parameter file whose
own home pose is out of reach is an :class:`InputError` (``ParameterError``): the file
contradicts itself. Malformed arguments of the kinematics (``KinematicsInputError``) are an
:class:`InputError` that says where as the kinematics' solve errors do.

Each family also derives from the builtin it always was (``ValueError`` for bad input,
``RuntimeError`` for a solve that failed, ``OSError`` for a destination), so code written
against those keeps working; an error that moved family keeps its old builtin as a second base
(the closed form's ``UnreachableError`` is still a ``ValueError``).
"""
from __future__ import annotations

import logging
import re

LONGEST_LINE = 250  # characters: the longest refusal; longer is said with less, never cut
# what a message has of it: the command line prefixes "pollard-pin <command>: error: "
MESSAGE_ROOM = LONGEST_LINE - len("pollard-pin workspace: error: ")


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


def without_asides(text: str) -> str:
    """``text`` without its asides in words (a parenthesis that starts with a letter and holds
    more than one word: '(run-on included)', '(or wider by 40 mm; …)'); figures such as
    '(0.1, 0.2, 0.3) m' and names such as '(part.facing)' stay."""
    return re.sub(r" \((?=[a-z])[^()]* [^()]*\)", "", text)


def say_less(*versions: str, width: int = MESSAGE_ROOM) -> str:
    """The first of ``versions`` (the full message first, then shorter ones: fewer clauses,
    never a cut word) of at most ``width`` characters (default :data:`MESSAGE_ROOM`: the
    line's room after the command line's prefix), else the last; when the full one is not
    it, the full one is logged (``-v`` shows it)."""
    full = " ".join(versions[0].split())
    for text in versions:
        text = " ".join(text.split())
        if len(text) <= width:
            break
    if text != full:
        logging.getLogger("pollard_pin").info("in full: %s", full)
    return text


__all__ = ["LONGEST_LINE", "MESSAGE_ROOM", "PollardError", "InputError", "SolveError",
           "DestinationError", "say_less", "without_asides"]
