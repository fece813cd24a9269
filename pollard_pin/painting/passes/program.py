"""A part's program (docs/model.md §23): its passes and the turnarounds and ramps between
them, each a polynomial in time or a polynomial of one, so positions, rates and accelerations
are exact at any time (the trajectory's ``curve``).

- pass: the gun pose (tip, angles) as a quintic interpolating B-spline P(s) of the surface arc
  s through the pass samples, run at ṡ = ±v: rate P'(s)·ṡ, acceleration P''(s)·v²;
- turnaround, ramp: the quintic in time matching pose, rate and acceleration at both ends
  (from rest, or to rest: a ramp starts v·τ/2 before its pass, as the panel's).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import make_interp_spline

from ...analytic.taskspace import angles_from_rotation
from ..errors import PlanError
from .surface import SurfaceLayout, reference_axis


def gun_frame(axis: np.ndarray, reference=(0.0, 0.0, 1.0)) -> np.ndarray:
    """Tool rotations (K, 3, 3) spraying along unit ``axis`` (K, 3): R = [a, c × a, c], c the
    unit ``reference`` (world z: the panel's [−n, u, v] for a = −n) projected off a;
    :class:`PlanError` where an axis runs along the reference."""
    ref = np.asarray(reference, dtype=float)
    c = ref - (axis @ ref)[:, None] * axis
    norm = np.linalg.norm(c, axis=1)
    if not norm.min() > 1e-6:
        k = int(np.argmin(norm))
        raise PlanError(f"the spray axis {tuple(round(float(x), 3) for x in axis[k])} runs "
                        f"along the gun frame's reference axis {tuple(ref)}: the part's "
                        "surface turns more than 45° off its facing")
    c /= norm[:, None]
    return np.stack([axis, np.cross(c, axis), c], axis=-1)


class PassPiece:
    """A pass run at surface speed ``v``, forwards (s from 0) or backwards."""

    kind = "pass"

    def __init__(self, s, poses, v: float, forward: bool, index: int):
        self.spline = make_interp_spline(s, poses, k=5)
        self.d1, self.d2 = self.spline.derivative(1), self.spline.derivative(2)
        self.length, self.v, self.forward, self.index = float(s[-1]), v, forward, index
        self.duration = self.length / v

    def evaluate(self, tau):
        rate = self.v if self.forward else -self.v
        s = tau * self.v if self.forward else self.length - tau * self.v
        s = np.clip(s, 0.0, self.length)
        return self.spline(s), self.d1(s) * rate, self.d2(s) * self.v ** 2

    def state(self, end: bool):
        """(pose, rate, acceleration) at the pass's start or ``end``: evaluated once (a
        turnaround search builds the program ~30 times from the same passes)."""
        states = self.__dict__.setdefault("_states", {})
        if end not in states:
            x = tuple(a[0] for a in self.evaluate(np.array([self.duration if end else 0.0])))
            for a in x:
                a.flags.writeable = False  # shared by every build
            states[end] = x
        return states[end]


class Quintic:
    """The quintic in time from (p0, v0, a0) to (p1, v1, a1) over ``duration``."""

    def __init__(self, kind: str, start, end, duration: float):
        (p0, v0, a0), (p1, v1, a1) = start, end
        T = duration
        dp = p1 - p0
        self.c = np.array([
            p0, v0, a0 / 2,
            (20 * dp - (8 * v1 + 12 * v0) * T - (3 * a0 - a1) * T ** 2) / (2 * T ** 3),
            (-30 * dp + (14 * v1 + 16 * v0) * T + (3 * a0 - 2 * a1) * T ** 2) / (2 * T ** 4),
            (12 * dp - 6 * (v1 + v0) * T - (a0 - a1) * T ** 2) / (2 * T ** 5)])
        self.kind, self.duration = kind, T

    def evaluate(self, tau):
        tau = np.clip(tau, 0.0, self.duration)[:, None]
        c = self.c
        p = c[0] + tau * (c[1] + tau * (c[2] + tau * (c[3] + tau * (c[4] + tau * c[5]))))
        d = c[1] + tau * (2 * c[2] + tau * (3 * c[3] + tau * (4 * c[4] + tau * 5 * c[5])))
        dd = 2 * c[2] + tau * (6 * c[3] + tau * (12 * c[4] + tau * 20 * c[5]))
        return p, d, dd


def ramp(kind: str, state, duration: float, into: bool) -> Quintic:
    """From rest to a pass's start ``state`` (``into``), or from its end to rest: the rest
    pose lies v·τ/2 back (or on) along the pass's rate, as the panel's ramps travel."""
    p, v, a = state
    z = np.zeros_like(p)
    if into:
        return Quintic(kind, (p - v * duration / 2, z, z), state, duration)
    return Quintic(kind, state, (p + v * duration / 2, z, z), duration)


@dataclass(frozen=True, eq=False)
class Program:
    """Pieces back to back from t = 0."""

    pieces: tuple

    @property
    def start(self) -> np.ndarray:
        d = np.array([p.duration for p in self.pieces])
        return np.concatenate([[0.0], np.cumsum(d)[:-1]])

    @property
    def total(self) -> float:
        return float(sum(p.duration for p in self.pieces))

    def piece_at(self, t) -> np.ndarray:
        return np.clip(np.searchsorted(self.start, t, side="right") - 1, 0,
                       len(self.pieces) - 1)

    def evaluate(self, t):
        """(poses, rates, accelerations) (N, 6) at times ``t``; exactly at rest at both
        ends."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        start, idx = self.start, self.piece_at(t)
        out = [np.empty((len(t), 6)) for _ in range(3)]
        # each piece's times in their order, as idx == i selects them: a slice where t
        # increases (a path), else a stable sort's run (a mask per piece costs P passes)
        order = None if (np.diff(idx) >= 0).all() else np.argsort(idx, kind="stable")
        ks = idx if order is None else idx[order]
        cuts = np.flatnonzero(np.diff(ks)) + 1
        for a, b in zip(np.r_[0, cuts], np.r_[cuts, len(ks)]) if len(ks) else ():
            rows = slice(a, b) if order is None else order[a:b]
            i = int(ks[a])
            for o, x in zip(out, self.pieces[i].evaluate(t[rows] - start[i])):
                o[rows] = x
        ends = (t <= 0.0) | (t >= self.total)
        out[1][ends], out[2][ends] = 0.0, 0.0
        return tuple(out)

    def spray(self, t) -> np.ndarray:
        """The trigger at times ``t``: 1 on the passes, 0 elsewhere."""
        kinds = np.array([p.kind == "pass" for p in self.pieces], dtype=float)
        return kinds[self.piece_at(np.atleast_1d(np.asarray(t, dtype=float)))]


def pass_poses(layout: SurfaceLayout):
    out = []
    ref, first = reference_axis(layout.frame.n), None
    for p in layout.passes:
        ang = np.unwrap(angles_from_rotation(gun_frame(p.axis, ref)), axis=0)
        if first is None:
            first = ang[0]
        ang -= 2 * math.pi * np.round((ang[0] - first) / (2 * math.pi))
        out.append(np.column_stack([p.tip, ang]))
    return out


def pass_pieces(layout: SurfaceLayout, v: float, coats: int) -> list:
    """The passes of every coat in serpentine order (a coat runs back over the last)."""
    poses = pass_poses(layout)
    order = []
    for c in range(coats):
        order += list(range(len(poses)) if c % 2 == 0 else range(len(poses) - 1, -1, -1))
    return [PassPiece(layout.passes[k].s, poses[k], v, i % 2 == 0, k)
            for i, k in enumerate(order)]


def build_program(passes, taus) -> Program:
    """Ramp, pass, turn, pass, ..., ramp with the given turn/ramp durations (P + 1,)."""
    pieces = [ramp("ramp", passes[0].state(False), taus[0], True)]
    for k, p in enumerate(passes):
        pieces.append(p)
        if k + 1 < len(passes):
            pieces.append(Quintic("turn", p.state(True), passes[k + 1].state(False),
                                  taus[k + 1]))
    pieces.append(ramp("ramp", passes[-1].state(True), taus[-1], False))
    return Program(tuple(pieces))


__all__ = ["PassPiece", "Program", "Quintic", "build_program", "gun_frame", "pass_pieces",
           "pass_poses", "ramp"]
