"""The least distance between two robots' capsules over their samples (docs/model.md §26.4):
every capsule pair at coarse samples first, a ceiling; then only the pairs and samples that
the boxes, or the way travelled between samples (:func:`.clearance.may_come_within`), cannot
prove farther than the least so far. The same least, and the same sample named, as measuring
every pair at every sample, to the bit. Used by :mod:`.cell_clearance`.
"""
from __future__ import annotations

import math

import numpy as np

from ...kinematics.capsules import segment_distance
from .clearance import SLACK, may_come_within, travelled

CHUNK = 4096  # samples a block of the pairwise distances (≈ 40 MB at 25 capsules)
COARSE = 16  # every this many samples, every capsule pair sets the ceiling (and wins a tie)
FIRST = 64  # with steps: every this many samples measured first, every capsule pair
LEVELS = (32, 16, 8, 4, 2, 1)  # the spacings measured in turn between those
PAIRS = 1 << 18  # capsule pairs measured at a time between the coarse samples (≈ 60 MB)


def pair_distance(a1, b1, a2, b2, r1, r2, steps=None,
                  below: float = math.inf) -> tuple[float, int]:
    """The least distance [m] between two robots' capsules over the samples (ends (N, L, 3)
    each, radii (L,)) and its sample. Every pair at every COARSE-th sample sets a ceiling;
    then only the pairs of capsules whose bounding boxes come within it of the other robot's
    (the union of its capsules' boxes) are measured. ``steps`` (N − 1,): how far the two
    robots' points may move apart or together in each step (the sum of both robots' largest
    step, the chords of :mod:`.cell_clearance`), to measure every pair at every FIRST-th
    sample only and the samples between at halving spacings (LEVELS), only those the way
    travelled from the samples measured cannot prove beyond the least so far (or
    ``below``), there only the capsule pairs it cannot prove so (:func:`pairs_least`,
    instead of the boxes), and not a sample the same as the one before
    (:func:`skipping_least`; default None: every sample); the answer is the same either way
    (docs/model.md §26.4).
    ``below``: only a least under it is sought (default inf); with none, a distance found,
    at least ``below``, and its sample."""
    rr = r1[:, None] + r2[None, :]
    ends = (a1, b1, a2, b2, r1, r2, rr)
    if steps is None:
        best, where, known = coarse_least(a1[::COARSE], b1[::COARSE], a2[::COARSE], b2[::COARSE],
                                     r1, r2)
        ceiling, where = best, where * COARSE
        least = row_least(ends, np.arange(len(a1)), max(best, 0.0))
        if least.min() < ceiling:  # else the coarse samples' first least
            best = float(least.min())
            where = int(np.flatnonzero(least == least.min()).min())
        return best, where
    return skipping_least(ends, steps, below)


def skipping_least(ends, steps, below: float) -> tuple[float, int]:
    """:func:`pair_distance` with ``steps`` (docs/model.md §26.4). Named: the first COARSE-th
    sample at the least, else the first sample there, as with every sample measured."""
    a1, b1, a2, b2, r1, r2, _ = ends
    best, _, known = coarse_least(a1[::FIRST], b1[::FIRST], a2[::FIRST], b2[::FIRST], r1, r2)
    way = travelled(steps)
    # a sample the same as the one before measures the same: not the first least (a COARSE-th
    # is measured all the same: it wins a tie)
    fresh = np.concatenate([[True], np.asarray(steps) > 0])
    fresh[::COARSE] = True
    at, low = np.arange(0, len(a1), FIRST), known.min(axis=(1, 2))
    # `low` is a FIRST-th sample's exact least where that is the least (a pair not measured
    # lies farther than one measured)
    done = [(at, low)]
    for spacing in LEVELS:
        rows = np.arange(spacing, len(a1), 2 * spacing)
        rows = rows[fresh[rows]]
        # a sample left out is further than the least so far: not the least
        limit = min(best, below)
        rows = rows[may_come_within(low, at, way, limit, rows)]
        if len(rows) == 0:
            continue
        least = pairs_least(ends, rows, known, way, limit)
        best = min(best, float(least.min()))
        done.append((rows, least))
        # a pair not measured is further than the limit
        order = np.argsort(np.concatenate([at, rows]), kind="stable")
        at = np.concatenate([at, rows])[order]
        low = np.concatenate([low, np.minimum(least, limit)])[order]
    rows = np.concatenate([r for r, _ in done])
    held = rows[np.concatenate([d for _, d in done]) == best]
    grid = held[held % COARSE == 0]
    return best, int(grid.min() if len(grid) else held.min())


def pairs_least(ends, rows, known, way, limit: float) -> np.ndarray:
    """The least distance between the two robots at each sample of ``rows`` (R,), none a
    coarse sample, over the capsule pairs that may come within ``limit`` there (inf where
    none may): a pair's distance falls by at most the way between the coarse samples around
    it, so a pair whose lower bounds ``known`` (M, L1, L2) at both, less that way, are past
    the limit is not measured in between (docs/model.md §26.4). Exact where under the
    limit; ``ends`` (a1, b1, a2, b2, r1, r2, r1 + r2 of each pair). Taken about PAIRS
    capsule pairs at a time."""
    a1, b1, a2, b2, _, _, rr = ends
    start = np.arange(len(known)) * FIRST
    stop = np.minimum(start + FIRST, len(way) - 1)  # the next coarse sample, or the last
    bound = known.copy()  # a pair's least lower bound at the two coarse samples
    bound[:-1] = np.maximum(known[:-1], known[1:])
    may = bound - (way[stop] - way[start])[:, None, None] <= limit + SLACK
    p, i, j = np.nonzero(may)  # the pairs of each interval, in its order
    counts = np.bincount(p, minlength=len(known))
    first = np.cumsum(counts) - counts
    per = counts[rows // FIRST]  # each row's pairs
    out = np.full(len(rows), np.inf)
    cuts = np.searchsorted(np.cumsum(per), np.arange(PAIRS, per.sum(), PAIRS))
    for lo, hi in zip(np.r_[0, cuts], np.r_[cuts, len(rows)]):
        c = per[lo:hi]
        row = np.repeat(np.arange(lo, hi), c)
        k = ranges(first[rows[lo:hi] // FIRST], c)
        n, ii, jj = rows[row], i[k], j[k]
        np.minimum.at(out, row, segment_distance(a1[n, ii], b1[n, ii], a2[n, jj], b2[n, jj])
                      - rr[ii, jj])
    return out


def row_least(ends, rows, cut: float) -> np.ndarray:
    """The least distance between the two robots at each sample of ``rows`` (R,) over the
    capsule pairs whose bounding boxes come within ``cut`` of the other robot's (inf where
    none does); ``ends`` (a1, b1, a2, b2, r1, r2, r1 + r2 of each pair). Taken CHUNK samples
    at a time."""
    a1, b1, a2, b2, r1, r2, rr = ends
    out = np.full(len(rows), np.inf)
    for lo in range(0, len(rows), CHUNK):
        k = rows[lo:lo + CHUNK]
        e1, f1, e2, f2 = a1[k], b1[k], a2[k], b2[k]
        (lo1, hi1), (lo2, hi2) = boxes(e1, f1, r1), boxes(e2, f2, r2)
        # boxes apart by g hold capsules at least g apart; capsules that cut into each
        # other (best < 0) have touching boxes (g = 0)
        near1 = box_gap(lo1, hi1, *box_union(lo2, hi2)) <= cut
        near2 = box_gap(lo2, hi2, *box_union(lo1, hi1)) <= cut
        n, i, j = pairs_of(near1, near2)
        if len(n):
            np.minimum.at(out, lo + n, segment_distance(e1[n, i], f1[n, i], e2[n, j],
                                                        f2[n, j]) - rr[i, j])
    return out


def pairs_of(near1, near2) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(n, i, j): every capsule i of near1 (N, L1) with every j of near2 (N, L2) at each
    sample n, in the order of ``np.nonzero(near1[:, :, None] & near2[:, None, :])``, built
    from the two lists alone (not the N × L1 × L2 array)."""
    n1, i1 = np.nonzero(near1)
    n2, j2 = np.nonzero(near2)
    counts = np.bincount(n2, minlength=len(near2))
    rep = counts[n1]  # each (n, i) with every j of its sample
    start = np.cumsum(counts) - counts  # where each sample's j's begin in j2
    return np.repeat(n1, rep), np.repeat(i1, rep), j2[ranges(start[n1], rep)]


def ranges(starts, counts) -> np.ndarray:
    """The ranges starts[m] … starts[m] + counts[m] − 1 one after another (integers)."""
    return np.repeat(starts, counts) + np.arange(counts.sum()) - np.repeat(
        np.cumsum(counts) - counts, counts)


def coarse_least(a1, b1, a2, b2, r1, r2) -> tuple[float, int, np.ndarray]:
    """(the least distance between two robots' capsules over the samples (ends (M, L, 3)
    each), the first sample where it lies, a lower bound (M, L1, L2) of each pair's). Only the
    capsule pairs whose bounding spheres (the segment's midpoint, half its length plus r)
    may come within the best of each sample's closest pair of spheres are measured: a pair
    left out lies farther apart than one measured, so neither the least nor its first sample
    changes; its spheres' gap bounds its distance below."""
    rr = r1[:, None] + r2[None, :]
    c1, c2 = (a1 + b1) / 2, (a2 + b2) / 2
    h1 = norm3(b1 - a1) / 2 + r1
    h2 = norm3(b2 - a2) / 2 + r2
    gap = norm3(c1[:, :, None] - c2[:, None]) - h1[:, :, None] - h2[:, None]
    # the closest spheres' capsules of each sample: an achieved distance, a ceiling
    m = np.arange(len(gap))
    i, j = np.unravel_index(gap.reshape(len(gap), -1).argmin(axis=1), gap.shape[1:])
    ceiling = float((segment_distance(a1[m, i], b1[m, i], a2[m, j], b2[m, j])
                     - rr[i, j]).min())
    # round-off (~1e-16 m) kept far below the margin; a pair cutting in (gap ≤ 0) kept
    measured = gap <= max(ceiling, 0.0) + 1e-9
    n, i, j = np.nonzero(measured)
    d = segment_distance(a1[n, i], b1[n, i], a2[n, j], b2[n, j]) - rr[i, j]
    k = int(np.argmin(d))  # n ascends: the first sample of the least
    known = np.where(measured, np.inf, gap)
    known[n, i, j] = d
    return float(d[k]), int(n[k]), known


def boxes(a, b, r) -> tuple[np.ndarray, np.ndarray]:
    """Each capsule's bounding box: its lower and upper corners (N, L, 3) each."""
    return np.minimum(a, b) - r[:, None], np.maximum(a, b) + r[:, None]


def box_gap(lower, upper, lo, hi) -> np.ndarray:
    """The distance (N, L) of each box (corners ``lower``, ``upper``) from the box lo–hi of
    its sample (each (N, 3))."""
    out = np.maximum(np.maximum(lo[:, None] - upper, lower - hi[:, None]), 0)
    return norm3(out)


def box_union(lower, upper) -> tuple[np.ndarray, np.ndarray]:
    """The box (N, 3) corners holding every box (N, L, 3) of a sample: min and max over L,
    taken capsule by capsule (exact, and faster than a reduction over the middle axis)."""
    lo, hi = lower[:, 0].copy(), upper[:, 0].copy()
    for k in range(1, lower.shape[1]):
        np.minimum(lo, lower[:, k], out=lo)
        np.maximum(hi, upper[:, k], out=hi)
    return lo, hi


def norm3(x) -> np.ndarray:
    """|x| over the last axis (of 3): numpy's norm, summed as it sums, (x₀² + x₁²) + x₂², to
    the bit, without a reduction over an axis of three."""
    s = x * x
    return np.sqrt((s[..., 0] + s[..., 1]) + s[..., 2])


__all__ = ["CHUNK", "COARSE", "FIRST", "LEVELS", "PAIRS", "box_gap", "box_union", "boxes",
           "coarse_least", "norm3", "pair_distance", "pairs_least", "pairs_of", "ranges",
           "row_least", "skipping_least"]
