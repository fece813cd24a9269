"""Which passes of a line's program are out of reach wherever the line carries the part, and
by how much (docs/model.md §24): the diagnosis behind the line's reach refusals, made once
when no shift keeps the program in reach, before any speed is searched.

Each pass alone, without the line's drift (a pass runs across the travel, so the drift only
slants it), is sampled at PASS_SAMPLES points and shifted along the line on a SCAN_STEP grid
over the shifts the planner may use, limited to where the tip can be at all (the ball of
:func:`reach_ball`); the workspace map's per-pose rules (``run``'s, docs/model.md §22) say
which samples are in reach. A pass with no shift at which all its samples are is out of
reach; its excess is its length less the longest stretch of it in reach at any shift.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...workspace.reach import evaluate

PASS_SAMPLES = 17  # points along each pass
SCAN_STEP = 0.02  # m between the shifts tried along the line
CHUNK = 50_000  # poses per call of the workspace rules
# Poses tried at most (≈ 30 µs each): a program of many passes gets a coarser shift grid.
MAX_POSES = 200_000


@dataclass(frozen=True)
class PassReach:
    """One pass out of reach: ``number`` (1 = the first painted, the leading end), the
    gun's ``length`` along it [m] (run-on included), at the shift that holds most of it in
    reach the longest stretch ``covered`` [m] and what is left out at each end, ``ends`` =
    (at its start, at its end) [m]; ``rise``: its end's height over its start's [m];
    ``middle``: where its middle is with the part at its t = 0 pose."""

    number: int
    length: float
    covered: float
    ends: tuple[float, float]
    rise: float
    middle: tuple[float, float, float]  # the tip at the pass's middle, the part at t = 0 [m]

    @property
    def excess(self) -> float:
        return self.length - self.covered

    @property
    def nowhere(self) -> bool:
        """No sample of the pass is in reach at any shift."""
        return self.ends == (self.length, self.length)

    @property
    def tall(self) -> bool:
        """The pass runs mostly along world z."""
        return abs(self.rise) > 0.5 * self.length

    def side(self) -> str:
        """Where it leaves the reach: 'top', 'bottom' (or 'start', 'end'), or 'both ends'."""
        a, b = self.ends
        if a > 0 and b > 0 and min(a, b) > 0.1 * self.excess:
            return "both ends"
        up = ("bottom", "top") if self.rise > 0 else ("top", "bottom")
        names = up if self.tall else ("start", "end")
        return names[0] if a >= b else names[1]


def reach_ball(params) -> tuple[np.ndarray, float]:
    """(centre, radius) of a ball holding every reachable tip, any orientation: the wrist
    centre within x32 + x65 + x1514 of chain 0's base joint, the tip x1918 beyond it
    (docs/model.md §2)."""
    return (np.array([0.0, 0.0, params.z10]),
            params.x32 + params.x65 + params.x1514 + params.x1918)


def ball_shift_range(params, points, e) -> tuple[float, float] | None:
    """(a, b): the shifts x along the unit ``e`` at which some of ``points`` + x·e can be in
    the reach ball (:func:`reach_ball`), from the first point to enter to the last to leave;
    None if no point's line meets the ball."""
    c, r = reach_ball(params)
    d = points - c
    along = d @ e
    perp2 = np.einsum("ij,ij->i", d, d) - along ** 2
    inside = perp2 < r * r
    if not inside.any():
        return None
    half = np.sqrt(r * r - perp2[inside])
    return float(np.min(-along[inside] - half)), float(np.max(-along[inside] + half))


def _ball_shifts(params, points, e, lo: float, hi: float, most: int) -> np.ndarray:
    """The grid of shifts in [lo, hi] at which some of ``points`` + x·e can be in the reach
    ball (empty if none), SCAN_STEP apart or wider to keep to ``most`` shifts."""
    span = ball_shift_range(params, points, e)
    if span is None:
        return np.empty(0)
    a, b = max(lo, span[0]), min(hi, span[1])
    if a > b:
        return np.empty(0)
    step = max(SCAN_STEP, (b - a) / max(most - 1, 1))
    return a + np.arange(0.0, b - a + step / 2, step)


def coarse_to_fine(n: int, coarsest: int = 16) -> list[np.ndarray]:
    """The indices 0..n−1 in rounds, every ``coarsest``-th first (a power of two), then the
    middles of the gaps left, halving: each index once. A scan that drops what an early
    round settles (a pass all in reach at some shift, a sample in reach somewhere) tries
    the rest in full."""
    out = [np.arange(0, n, coarsest)]
    s = coarsest
    while s > 1:
        out.append(np.arange(s // 2, n, s))
        s //= 2
    return [r for r in out if len(r)]


def _longest_run(ok: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The longest run of True along the last axis of ``ok``: its length and its start."""
    best = np.zeros(ok.shape[:-1], dtype=int)
    start = np.zeros(ok.shape[:-1], dtype=int)
    run = np.zeros(ok.shape[:-1], dtype=int)
    for k in range(ok.shape[-1]):
        run = np.where(ok[..., k], run + 1, 0)
        longer = run > best
        best = np.where(longer, run, best)
        start = np.where(longer, k + 1 - run, start)
    return best, start


def unreachable_passes(robot, rel, e, lo: float, hi: float) -> tuple[list[PassReach], int]:
    """The passes of the relative program ``rel`` (a :class:`.line.phases.Relative`) out of
    reach at every shift x ∈ [lo, hi] along the unit ``e``, and the number of passes."""
    e = np.asarray(e, dtype=float)
    pieces = [i for i, k in enumerate(rel.kind) if k == "pass"]
    u = np.linspace(0.0, 1.0, PASS_SAMPLES)
    tt = np.concatenate([rel.start[i] + rel.duration[i] * u for i in pieces])
    poses = rel.evaluate(tt)[0].reshape(len(pieces), PASS_SAMPLES, 6)
    xs = _ball_shifts(robot.params, poses[..., :3].reshape(-1, 3), e, lo, hi,
                      max(8, MAX_POSES // (len(pieces) * PASS_SAMPLES)))
    cum = np.concatenate([np.zeros((len(pieces), 1)), np.cumsum(np.linalg.norm(
        np.diff(poses[..., :3], axis=1), axis=2), axis=1)], axis=1)  # (P, K) arc length
    rise = poses[:, -1, 2] - poses[:, 0, 2]
    if len(xs):
        ok = np.zeros((len(pieces), len(xs), PASS_SAMPLES), dtype=bool)
        live = np.ones(len(pieces), dtype=bool)  # not yet all in reach at a shift tried
        for cols in coarse_to_fine(len(xs)):
            rows = np.flatnonzero(live)
            if not len(rows):
                break
            shifted = np.repeat(poses[rows, None], len(cols), axis=1)  # (P', X', K, 6)
            shifted[..., :3] += xs[cols][None, :, None, None] * e
            flat = shifted.reshape(-1, 6)
            got = np.concatenate([evaluate(robot, flat[i:i + CHUNK])["reachable"] > 0
                                  for i in range(0, len(flat), CHUNK)])
            ok[np.ix_(rows, cols)] = got.reshape(len(rows), len(cols), PASS_SAMPLES)
            live[rows] = ~ok[np.ix_(rows, cols)].all(axis=2).any(axis=1)
        # a pass all in reach at some shift is not reported, whatever its other shifts say;
        # every other pass was tried at every shift
        run, first = _longest_run(ok)
    else:
        run = first = np.zeros((len(pieces), 1), dtype=int)
    best = np.argmax(run, axis=1)
    out = []
    for k in range(len(pieces)):
        n, a = int(run[k, best[k]]), int(first[k, best[k]])
        if n == PASS_SAMPLES:
            continue
        c, total = cum[k], float(cum[k, -1])
        covered = float(c[a + n - 1] - c[a]) if n else 0.0
        ends = (float(c[a]), total - float(c[a + n - 1])) if n else (total, total)
        mid = poses[k, PASS_SAMPLES // 2, :3]
        out.append(PassReach(k + 1, total, covered, ends, float(rise[k]),
                             (float(mid[0]), float(mid[1]), float(mid[2]))))
    return out, len(pieces)


def numbers(passes: list[PassReach], most: int = 4) -> str:
    """'3–17, 20' for the passes' numbers, at most ``most`` ranges then '…'."""
    nums = [p.number for p in passes]
    ranges, first = [], nums[0]
    for a, b in zip(nums, nums[1:] + [None]):
        if b != a + 1:
            ranges.append(f"{first}" if first == a else f"{first}–{a}")
            first = b
    return ", ".join(ranges[:most]) + (", …" if len(ranges) > most else "")


def out_of_reach(passes: list[PassReach], total: int) -> str:
    """One clause: which passes are out of reach and why: one nowhere in reach and where it
    is, else the worst one's length, how much of it is in reach at best and where it leaves
    the reach, by how much [mm]."""
    which = (f"all {total} passes" if len(passes) == total else
             f"pass{'es' if len(passes) > 1 else ''} {numbers(passes)} of {total}")
    head = f"{which} out of reach at any place on the line: "
    nowhere = [p for p in passes if p.nowhere]
    if nowhere:
        p = nowhere[len(nowhere) // 2]
        x, y, z = p.middle
        return (head + f"no part of pass {p.number} ({p.length:.3f} m, its middle at "
                f"({x:.3f}, {y:.3f}, {z:.3f}) m at t = 0) is ever in reach")
    worst = max(passes, key=lambda p: p.excess)
    side = worst.side()
    where = (f"{1000 * worst.excess:.0f} mm too {'tall' if worst.tall else 'long'} for the "
             "reach" if side == "both ends" else
             f"its {side} {1000 * worst.excess:.0f} mm out")
    return (head + f"pass {worst.number} is {worst.length:.3f} m (run-on included), at most "
            f"{worst.covered:.3f} m of it in reach, {where}")


__all__ = ["CHUNK", "MAX_POSES", "PASS_SAMPLES", "PassReach", "SCAN_STEP", "ball_shift_range",
           "coarse_to_fine", "numbers", "out_of_reach", "reach_ball", "unreachable_passes"]
