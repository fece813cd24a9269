"""The shifts along the line at which a world program stays in reach (docs/model.md §24): the
scan of the window the line may carry the part through before the program starts, its ends
refined by bisection, and the window searched for a robot far down the line."""
from __future__ import annotations

import math

import numpy as np

from ...analytic.taskspace import MAX_ABS_TASK
from ...kinematics.ik_batch import reachable_sequences

SHIFT_RANGE = 2.0  # m: the line may carry the part this far before the program starts
SHIFT_STEP = 0.005  # m: the scan of shifts along the line
SHIFT_BISECT = 10  # bisection steps refining each end of the feasible shifts
SCAN_COARSE = 8  # the scan's first pass: every 8th shift (scan)


def fits(robot, poses, e, xs) -> np.ndarray:
    """Whether the poses shifted by x·e are in reach (:func:`.checks.motion.reach`), for every
    x of ``xs``: (X,) booleans, the shifts stacked into one batch
    (:func:`~pollard_pin.kinematics.ik_batch.reachable_sequences`), each judged as alone."""
    p = np.repeat(np.asarray(poses, dtype=float)[None], len(xs), axis=0)
    p[..., :3] += np.asarray(xs, dtype=float)[:, None, None] * np.asarray(e, dtype=float)
    return reachable_sequences(robot, p)


def longest_run(ok) -> tuple[int, int]:
    """The first and last index of the first longest run of True in ``ok`` (one True at
    least)."""
    edges = np.diff(np.concatenate([[0], np.asarray(ok).astype(int), [0]]))
    starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    k = int(np.argmax(stops - starts))
    return int(starts[k]), int(stops[k]) - 1


def scan(robot, poses, e, xs, known: dict | None = None) -> np.ndarray:
    """:func:`fits` at the shifts ``xs`` where it decides :func:`longest_run`, False elsewhere
    (docs/model.md §24): every SCAN_COARSE-th shift (and the last) first, then every shift
    between two of them of which one fits, so that each run holding a shift tried is known
    whole with its ends; a run not met lies between two misses, at most SCAN_COARSE − 1
    long, so when a run met is SCAN_COARSE long or more, it is the longest and the first of
    the longest, as a scan of every shift finds it. Else every shift left is tried. Each
    shift is judged as alone (:func:`fits`), so the ones tried are the full scan's to the
    bit; a shift that puts a pose out of bounds (an input error, the first such shift's)
    sends the whole scan to :func:`fits` at once. ``known`` (a dict, shift → fits) holds the
    shifts of these poses judged before (another window's scan) and gains those judged
    here: a shift is judged once, its answer the same."""
    xs = np.asarray(xs, dtype=float)
    n = len(xs)
    p = np.asarray(poses, dtype=float)
    far = np.abs(p).max(initial=0.0) + np.abs(xs).max(initial=0.0)  # |e| = 1
    if n <= 2 * SCAN_COARSE or not far < MAX_ABS_TASK / 2:  # NaN too
        return fits(robot, poses, e, xs)
    ok, tried = np.zeros(n, dtype=bool), np.zeros(n, dtype=bool)
    known = {} if known is None else known

    def judge(i):
        new = [k for k in i if float(xs[k]) not in known]
        if new:
            known.update(zip(xs[new].tolist(), fits(robot, poses, e, xs[new]).tolist()))
        ok[i] = [known[float(xs[k])] for k in i]
        tried[i] = True

    coarse = np.unique(np.append(np.arange(0, n, SCAN_COARSE), n - 1))
    judge(coarse)
    near = np.zeros(n, dtype=bool)
    for i, j in zip(coarse[:-1], coarse[1:]):
        if ok[i] or ok[j]:
            near[i + 1:j] = True
    if near.any():
        judge(np.flatnonzero(near))
    a, b = longest_run(ok) if ok.any() else (0, -1)
    rest = np.flatnonzero(~tried)
    if b - a + 1 < SCAN_COARSE and len(rest):
        judge(rest)
    return ok


def feasible_shifts(robot, poses, e, lo: float, span: float = SHIFT_RANGE,
                    anchor: float = 0.0, known: dict | None = None):
    """The longest run of shifts x ∈ [lo, lo + span] along the line with every pose + x·e in
    reach (scan at the x with x + ``anchor`` a multiple of SHIFT_STEP, ends refined by
    bisection), or None. With ``anchor`` the poses' world place along e, the scanned places
    are fixed in the world, wherever the job puts the part at t = 0. ``known``: the scan's
    shifts of the same poses already judged (:func:`scan`), for a second window."""
    first = math.ceil((lo + anchor) / SHIFT_STEP - 1e-9)
    last = math.floor((lo + span + anchor) / SHIFT_STEP + 1e-9)
    xs = np.arange(first, last + 1) * SHIFT_STEP - anchor
    if not len(xs):
        return None
    ok = scan(robot, poses, e, xs, known)
    if not ok.any():
        return None
    a, b = longest_run(ok)

    # each end bisected between its last good and first bad shift, both ends in one batch
    ends = [[xs[a], xs[a] - SHIFT_STEP], [xs[b], xs[b] + SHIFT_STEP]]
    live = [lo - 1e-15 <= bad <= lo + span + 1e-15 for _, bad in ends]
    for _ in range(SHIFT_BISECT if any(live) else 0):
        mids = [0.5 * (good + bad) for good, bad in ends]
        ok = fits(robot, poses, e, mids)
        ends = [([m, bad] if fine else [good, m]) if on else [good, bad]
                for (good, bad), m, fine, on in zip(ends, mids, ok, live)]
    return ends[0][0], ends[1][0]


def shift_window(lo: float, anchor: float) -> tuple[float, float]:
    """The shifts [start, start + SHIFT_RANGE] searched along the line when the first
    SHIFT_RANGE from ``lo`` (the part already riding the line) keep nothing in reach: for a
    part that reaches the robot only after more than half that range (a robot far down the
    line, ``anchor`` the program's world place along the line at shift 0), the range
    centred on the shift that brings it there, −anchor; else the first range again."""
    here = -float(anchor)
    start = lo if here <= lo + SHIFT_RANGE / 2 else here - SHIFT_RANGE / 2
    return start, start + SHIFT_RANGE


__all__ = ["SCAN_COARSE", "SHIFT_BISECT", "SHIFT_RANGE", "SHIFT_STEP", "feasible_shifts", "fits",
           "longest_run", "scan", "shift_window"]
