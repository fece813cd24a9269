"""Raster spray paths over a flat panel (docs/model.md §21): geometry and motion.

The gun stays normal to the panel at the standoff; only its position in the panel plane
moves. In panel coordinates (U along the passes, V across them) the path is a chain of
polynomial segments in time, so positions, rates and accelerations are exact:

- ramp in: from rest to the pass speed v (velocity a cubic smoothstep, C² at both ends);
- pass: constant speed v wherever the spot (within 4σ) is over the panel;
- turnaround: U reverses (U̇ from ±v to ∓v, acceleration 0 at both ends) while V steps by
  the spacing (a quintic smoothstep), outside the panel;
- ramp out: from v to rest.

:mod:`.plan.panel` picks each turnaround's duration from the motors; this module only builds and
evaluates the path.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import Polynomial

from ...analytic.taskspace import angles_from_rotation
from ..spray.spots import STROKES
from ..workpiece.panel import PanelFrame

# σ: the spot's reach (docs/model.md §21): constant speed while within it of the panel
SPOT_RADIUS = 4.0
PROFILE_TOLERANCE = 0.01  # largest relative film deviation the pass layout allows
TURN_SHAPE = 1  # m of the turnaround's U acceleration −c·(1 − (2x − 1)^(2m)) (see _turn_u)
DEGREE = 7  # coefficients per segment polynomial (degree 6)


# --- pass layout -----------------------------------------------------------------------------
def spot_runon(sigma: float, spot=None, sigmas: float = SPOT_RADIUS) -> float:
    """How far [m] past a painted edge the passes run on (docs/model.md §21): ``sigmas``·σ,
    σ the spot's width, but never beyond the reach of a finite spot (the β spot's R at the
    standoff, c = 1: it deposits nothing beyond), since past it the gun paints nothing.

    Parameters
    ----------
    sigma : float
        The spot's width σ [m] (the job's ``sigma``).
    spot : Spot or None, optional
        The job's spot (:mod:`.spray.spots`); None: the round Gaussian of ``sigma``.
    sigmas : float, optional
        The run-on in σ (a panel's SPOT_RADIUS, a part's ``EXTENSION``).

    Returns
    -------
    float
        The run-on [m]: min(sigmas·σ, reach); the Gaussians' reach (10σ) never binds.
    """
    run = sigmas * sigma
    return run if spot is None else min(run, spot.reach)


def ripple_spacing(sigma: float, tolerance: float = PROFILE_TOLERANCE / 2) -> float:
    """Largest spacing whose interior ripple, 2·exp(−2π²σ²/Δ²) (Poisson summation of the
    passes' Gaussian profiles), stays within ``tolerance``."""
    return sigma * math.pi * math.sqrt(2.0 / math.log(2.0 / tolerance))


def job_spacing(job, tolerance: float = PROFILE_TOLERANCE / 2) -> float:
    """The widest spacing whose interior ripple stays within ``tolerance`` for the job's spot
    across its passes (docs/model.md §21): :func:`ripple_spacing` for the round Gaussian
    (``job.spot`` None), else the spot's own (:meth:`.spray.spots.Spot.spacing`)."""
    if job.spot is None:
        return ripple_spacing(job.sigma, tolerance)
    return job.spot.spacing(tolerance, STROKES[job.direction])


def cross_profile(offsets, spacing: float, sigma: float, y, spot=None,
                  direction: str = "across") -> np.ndarray:
    """Film across passes at ``offsets`` relative to the interior film flow/(speed·spacing):
    Σ_k Δ/(√(2π)σ)·exp(−(y − y_k)²/2σ²) (long passes, docs/model.md §21); with ``spot`` (a
    :class:`.spray.spots.Spot`, its strokes ``direction``), Σ_k Δ·stripe(y − y_k)."""
    d = np.asarray(y, dtype=float)[:, None] - np.asarray(offsets)[None, :]
    if spot is not None:
        return spacing * spot.stripe(d, direction).sum(1)
    return spacing / (math.sqrt(2 * math.pi) * sigma) * np.exp(-0.5 * (d / sigma) ** 2).sum(1)


def pass_offsets(extent: float, spacing: float, sigma: float,
                 tolerance: float = PROFILE_TOLERANCE, spot=None,
                 direction: str = "across") -> np.ndarray:
    """The fewest passes, centred and ``spacing`` apart, whose cross profile (of the round
    Gaussian of ``sigma``, or of ``spot`` in strokes ``direction``: :func:`cross_profile`)
    stays within ``tolerance`` of 1 across [−extent/2, extent/2], edges included."""
    y = np.linspace(-extent / 2, extent / 2, max(3, int(math.ceil(extent / (sigma / 20))) + 1))
    n = max(1, int(math.floor(extent / spacing)))
    while True:
        offsets = (np.arange(n) - (n - 1) / 2) * spacing
        if np.abs(cross_profile(offsets, spacing, sigma, y, spot, direction)
                  - 1.0).max() <= tolerance:
            return offsets
        n += 1
        if n * spacing > extent + 40 * sigma:  # the ripple alone breaks the tolerance
            raise ValueError(f"spacing {spacing:.4g} m is too wide for σ = {sigma:.4g} m: "
                             f"the film between passes varies by more than "
                             f"{100 * tolerance:g} %")


# --- segment polynomials ---------------------------------------------------------------------
def _turn_u(m: int = TURN_SHAPE) -> Polynomial:
    """f(x) on [0, 1] with f(0) = f(1) = 0, f'(0) = 1, f'(1) = −1, f''(0) = f''(1) = 0 and
    f'' = −c·(1 − (2x − 1)^(2m)), c = 2(2m + 1)/(2m): near-constant deceleration for large m
    (peak |f''| = c; m = 1 is the quintic x − 2x³ + x⁴)."""
    c = 2.0 * (2 * m + 1) / (2 * m)
    fdd = -c * (1 - Polynomial([-1.0, 2.0]) ** (2 * m))
    fd = fdd.integ(lbnd=0.0) + 1.0
    return fd.integ(lbnd=0.0)


SMOOTHSTEP = Polynomial([0, 0, 0, 10, -15, 6])  # 0 → 1, zero rate and acceleration at ends
RAMP_IN = Polynomial([0, 0, 0, 1, -0.5])  # rate 3x² − 2x³: 0 → 1; travels 1/2
RAMP_OUT = Polynomial([0, 1, 0, -1, 0.5])  # rate 1 − 3x² + 2x³: 1 → 0; travels 1/2


def _in_time(shape: Polynomial, scale: float, duration: float) -> np.ndarray:
    """Coefficients (DEGREE,) in local time t of scale·shape(t/duration)."""
    c = np.zeros(DEGREE)
    k = np.arange(len(shape.coef))
    c[:len(k)] = scale * shape.coef / duration ** k
    return c


@dataclass(frozen=True)
class Segments:
    """A path in panel coordinates as polynomial pieces: piece i covers
    [start[i], start[i] + duration[i]] with U(t) = Σ cu[i, k]·τ^k, V likewise (τ local)."""

    start: np.ndarray  # (S,)
    duration: np.ndarray  # (S,)
    cu: np.ndarray  # (S, DEGREE)
    cv: np.ndarray  # (S, DEGREE)
    kind: tuple[str, ...]  # "ramp", "pass", "turn" per piece

    @property
    def total(self) -> float:
        return float(self.start[-1] + self.duration[-1])

    def evaluate(self, t) -> tuple[np.ndarray, ...]:
        """(U, V, U̇, V̇, Ü, V̈) at times ``t`` (exact polynomial derivatives)."""
        t = np.asarray(t, dtype=float)
        i = np.clip(np.searchsorted(self.start, t, side="right") - 1, 0, len(self.start) - 1)
        tau = np.clip(t - self.start[i], 0.0, self.duration[i])
        k = np.arange(DEGREE)
        out = []
        for c in (self.cu[i], self.cv[i]):
            p0 = (c * tau[:, None] ** k).sum(1)
            p1 = (c[:, 1:] * k[1:] * tau[:, None] ** (k[1:] - 1)).sum(1)
            p2 = (c[:, 2:] * (k[2:] * (k[2:] - 1)) * tau[:, None] ** (k[2:] - 2)).sum(1)
            out.append((p0, p1, p2))
        (u0, u1, u2), (v0, v1, v2) = out
        return u0, v0, u1, v1, u2, v2


def raster_segments(offsets, half_length: float, speed: float, turn_durations,
                    ramp_durations, coats: int = 1, shape: int = TURN_SHAPE) -> Segments:
    """The serpentine over passes at V = ``offsets`` (each coat back over them in reverse
    order), constant ``speed`` for |U| ≤ ``half_length``; one turnaround duration per turn
    ((passes·coats − 1,)) and the two ramp durations."""
    vs = list(offsets)
    order = []
    for c in range(coats):
        order += vs if c % 2 == 0 else vs[::-1]
    turn_durations = np.broadcast_to(np.asarray(turn_durations, float), (len(order) - 1,))
    f_turn = _turn_u(shape)
    pieces = []  # (kind, duration, cu, cv)
    direction = 1.0
    r_in, r_out = ramp_durations
    u0 = -half_length - speed * r_in / 2
    pieces.append(("ramp", r_in, _in_time(RAMP_IN, speed * r_in, r_in) + _const(u0),
                   _const(order[0])))
    for k, v in enumerate(order):
        length = 2 * half_length / speed
        u_start = -direction * half_length
        pieces.append(("pass", length, _const(u_start) + _linear(direction * speed),
                       _const(v)))
        if k + 1 < len(order):
            tau = float(turn_durations[k])
            pieces.append(("turn", tau,
                           _in_time(f_turn, direction * speed * tau, tau)
                           + _const(direction * half_length),
                           _in_time(SMOOTHSTEP, order[k + 1] - v, tau) + _const(v)))
            direction = -direction
    pieces.append(("ramp", r_out, _in_time(RAMP_OUT, direction * speed * r_out, r_out)
                   + _const(direction * half_length), _const(order[-1])))
    durations = np.array([p[1] for p in pieces])
    starts = np.concatenate([[0.0], np.cumsum(durations)[:-1]])
    return Segments(starts, durations, np.array([p[2] for p in pieces]),
                    np.array([p[3] for p in pieces]), tuple(p[0] for p in pieces))


def _const(x: float) -> np.ndarray:
    c = np.zeros(DEGREE)
    c[0] = x
    return c


def _linear(x: float) -> np.ndarray:
    c = np.zeros(DEGREE)
    c[1] = x
    return c


def task_motion(frame: PanelFrame, standoff: float, U, V, dU, dV, ddU, ddV,
                horizontal: bool = True):
    """Tool poses, rates, accelerations (N, 6) of panel-coordinate motion: the tip at the
    standoff along n from c + U·e_p + V·e_s (e_p = u, e_s = v for horizontal passes, swapped
    for vertical), orientation constant (:attr:`PanelFrame.rotation`)."""
    ep, es = (frame.u, frame.v) if horizontal else (frame.v, frame.u)
    U, V = np.asarray(U, dtype=float), np.asarray(V, dtype=float)
    n = len(U)
    poses = np.empty((n, 6))
    poses[:, :3] = (frame.c + standoff * frame.n + U[:, None] * ep + V[:, None] * es)
    poses[:, 3:] = angles_from_rotation(frame.rotation)
    d, dd = np.zeros((n, 6)), np.zeros((n, 6))
    d[:, :3] = np.asarray(dU)[:, None] * ep + np.asarray(dV)[:, None] * es
    dd[:, :3] = np.asarray(ddU)[:, None] * ep + np.asarray(ddV)[:, None] * es
    return poses, d, dd


def raster_motion(frame: PanelFrame, standoff: float, seg: Segments, t,
                  horizontal: bool = True):
    """Tool poses, rates, accelerations (N, 6) of the raster ``seg`` at times ``t``
    (:func:`task_motion`); at its two ends (rest) rates and accelerations are exactly 0, not
    the polynomials' round-off."""
    poses, d, dd = task_motion(frame, standoff, *seg.evaluate(t), horizontal=horizontal)
    ends = (np.asarray(t) <= 0.0) | (np.asarray(t) >= seg.total)
    d[ends], dd[ends] = 0.0, 0.0
    return poses, d, dd


__all__ = ["PROFILE_TOLERANCE", "SPOT_RADIUS", "Segments", "cross_profile", "job_spacing",
           "pass_offsets", "spot_runon",
           "raster_motion", "raster_segments", "ripple_spacing", "task_motion"]
