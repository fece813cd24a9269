"""The motors along a line's world path (docs/model.md §24): the check's :class:`Motion`, a
too slow line's screen at the path's own samples, and the refusal of a path over the motors'
ratings.

A slow line's path is mostly its wait at the start pose, every row the same, which
:func:`.checks.motion.motion` solves once and spreads over them all. :func:`wait_motion`
leaves out all but the last LEADING_RUN + 1 of those rows: the rows kept are solved as in the
whole path's check, to the bit, at a fraction of the spreading (a search's slowest tries).
"""
from __future__ import annotations

import numpy as np

from ...dynamics.motors import Actuators
from ...errors import PollardError
from ..checks.motion import LEADING_RUN, Motion, motion
from ..errors import LineSpeedError, ReachError


def first_kept(t, leave: float) -> int:
    """The first row of the increasing times ``t`` a check needs: of the rows before
    ``leave`` − 1e-12 [s] (the robot held at its start pose, the same row each,
    :func:`.line.phases.world_motion`; none in the repeating cycle, from ``leave`` − 1e-12),
    the last LEADING_RUN + 1 (0 if there are no more)."""
    held = int(np.searchsorted(np.asarray(t, dtype=float), leave - 1e-12))
    return max(0, held - 1 - LEADING_RUN)


def wait_motion(robot, act: Actuators, path, j: int, whole) -> Motion:
    """:func:`.checks.motion.motion` of ``path`` = (poses, rates, accelerations), the rows
    from ``j`` (:func:`first_kept`) of the path ``whole()`` gives. The rows kept still start
    with more than LEADING_RUN of the wait's, so ``motion`` solves from the same row as for
    the whole path, in the same blocks: each kept row's figures are the whole path's to the
    bit, the rows left out the same as the kept wait's. Anything raised (its samples
    numbered from row j) is the whole path's check's, raised in its own words."""
    try:
        return motion(robot, act, *path)
    except PollardError:
        if not j:
            raise
    return motion(robot, act, *whole())  # named from row j: the whole path's check names it


def screen_motors(robot, act: Actuators, path, speed: float, j: int = 0) -> None:
    """The motors along ``path`` (poses, rates, accelerations at the path's own samples, its
    rows before ``j`` the wait's: :func:`first_kept`), a too slow line's
    :class:`LineSpeedError` where they are over their ratings (a path out of reach there is
    left to the check)."""
    try:
        m = wait_motion(robot, act, [a[j:] for a in path], j, lambda: path)
    except ReachError:
        return
    motors_within(float(m.utilisation.max()), speed, False, "at least ")


def motors_within(worst: float, speed: float, too_fast: bool, least: str = "") -> None:
    """The :class:`LineSpeedError` of a path whose motors' ``worst`` use is over 1 (``least``:
    "at least " where only some samples were checked)."""
    if worst > 1.0:
        raise LineSpeedError(f"at line speed {speed:.4g} m/s a motor needs {least}"
                             f"{100 * worst:.0f} % of its peak torque or speed", too_fast,
                             f"a motor at {100 * worst:.0f} % of its rating")


__all__ = ["first_kept", "motors_within", "screen_motors", "wait_motion"]
