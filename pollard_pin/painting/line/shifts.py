"""The shifts along the line at which a world program stays in reach (docs/model.md §24): the
scan of the window the line may carry the part through before the program starts, its ends
refined by bisection, and the window searched for a robot far down the line."""
from __future__ import annotations

import math

import numpy as np

from ..checks.motion import reach
from ..errors import ReachError

SHIFT_RANGE = 2.0  # m: the line may carry the part this far before the program starts
SHIFT_STEP = 0.005  # m: the scan of shifts along the line
SHIFT_BISECT = 10  # bisection steps refining each end of the feasible shifts


def _fits(robot, poses, e, x) -> bool:
    p = np.array(poses)
    p[:, :3] += x * e
    try:
        reach(robot, p)
    except ReachError:
        return False
    return True


def feasible_shifts(robot, poses, e, lo: float, span: float = SHIFT_RANGE,
                    anchor: float = 0.0):
    """The longest run of shifts x ∈ [lo, lo + span] along the line with every pose + x·e in
    reach (scan at the x with x + ``anchor`` a multiple of SHIFT_STEP, ends refined by
    bisection), or None. With ``anchor`` the poses' world place along e, the scanned places
    are fixed in the world, wherever the job puts the part at t = 0."""
    first = math.ceil((lo + anchor) / SHIFT_STEP - 1e-9)
    last = math.floor((lo + span + anchor) / SHIFT_STEP + 1e-9)
    xs = np.arange(first, last + 1) * SHIFT_STEP - anchor
    if not len(xs):
        return None
    ok = np.array([_fits(robot, poses, e, x) for x in xs])
    if not ok.any():
        return None
    # the longest run of True
    edges = np.diff(np.concatenate([[0], ok.astype(int), [0]]))
    starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    k = int(np.argmax(stops - starts))
    a, b = int(starts[k]), int(stops[k]) - 1

    def refine(good, bad):
        if bad < lo - 1e-15 or bad > lo + span + 1e-15:
            return good
        for _ in range(SHIFT_BISECT):
            mid = 0.5 * (good + bad)
            good, bad = (mid, bad) if _fits(robot, poses, e, mid) else (good, mid)
        return good

    return refine(xs[a], xs[a] - SHIFT_STEP), refine(xs[b], xs[b] + SHIFT_STEP)


def shift_window(lo: float, anchor: float) -> tuple[float, float]:
    """The shifts [start, start + SHIFT_RANGE] searched along the line when the first
    SHIFT_RANGE from ``lo`` (the part already riding the line) keep nothing in reach: for a
    part that reaches the robot only after more than half that range (a robot far down the
    line, ``anchor`` the program's world place along the line at shift 0), the range
    centred on the shift that brings it there, −anchor; else the first range again."""
    here = -float(anchor)
    start = lo if here <= lo + SHIFT_RANGE / 2 else here - SHIFT_RANGE / 2
    return start, start + SHIFT_RANGE


__all__ = ["SHIFT_BISECT", "SHIFT_RANGE", "SHIFT_STEP", "feasible_shifts", "shift_window"]
