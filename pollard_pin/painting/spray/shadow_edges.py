"""Shadow edges in the film's time integral (docs/model.md §23).

Where a point sees the nozzle at one end of a time step and not at the other, the trapezoid
rule over the samples is first order in the step (the film jumps inside it). For each such
(point, step) the switch is located by bisection of the segment test (DEPTH halvings, the
gun's tip and axis interpolated linearly between the two samples, as the trigger) and the
lit part of the step is integrated by 3-point Gauss–Legendre. The trapezoid chain of lit steps
that ends at the step's lit sample t_j then misses its Euler–Maclaurin end term: it is added,
∓h²/12·f′(t_j), with f′ from the rate at t_j and the two samples beyond it on the chain's side
(the derivative of the interpolant through SLOPE_POINTS samples). What remains per switch:
the bisection's f·Δt·2^−DEPTH and the end term's error (estimated by the same term from one
sample fewer).
"""
from __future__ import annotations

import numpy as np

from ..workpiece.mesh import Part
from .deposition import Gun, pair_rate
from .occlusion import visible

DEPTH = 12  # halvings of a time step: the switch to 2.4e-4 of it
SLOPE_POINTS = 5  # samples for f′ at the chain's end: error ∝ h⁴
_GAUSS_X = np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)])
_GAUSS_W = np.array([5.0, 8.0, 5.0]) / 9.0


def _at(p, a, trig, k, lam):
    """Tip, unit axis (or rotation, its columns unit) and trigger at fraction ``lam`` of the
    steps k → k + 1 (linear)."""
    lam = np.asarray(lam, dtype=float)
    pos = p[k] + lam[:, None] * (p[k + 1] - p[k])
    ax = a[k] + lam.reshape((-1,) + (1,) * (a.ndim - 1)) * (a[k + 1] - a[k])
    ax /= np.linalg.norm(ax, axis=1, keepdims=True)
    return pos, ax, trig[k] + lam * (trig[k + 1] - trig[k])


def _derivative(x, f):
    """d/dx at x[0] of the polynomial through (x[m], f[m]), m < M (lists of arrays)."""
    out = np.zeros_like(f[0])
    with np.errstate(divide="ignore", invalid="ignore"):
        for i in range(len(x)):
            if i == 0:
                w = sum(1.0 / (x[0] - x[k]) for k in range(1, len(x)))
            else:
                w = 1.0 / (x[i] - x[0])
                for k in range(1, len(x)):
                    if k != i:
                        w = w * (x[0] - x[k]) / (x[i] - x[k])
            out = out + w * f[i]
    return np.nan_to_num(out)


def _slope(t, f, j, side):
    """df/dt at t_j from f (list, SLOPE_POINTS arrays) at samples j + m·side: the derivative
    of the interpolant through as many as lie inside, and through one fewer (its error
    estimate)."""
    x = [t[np.clip(j + m * side, 0, len(t) - 1)] for m in range(SLOPE_POINTS)]
    inside = sum(((j + m * side >= 0) & (j + m * side < len(t))).astype(int)
                 for m in range(SLOPE_POINTS))
    d = [np.zeros(len(j))] + [_derivative(x[:m], f[:m]) for m in range(2, SLOPE_POINTS + 1)]
    best = np.choose(np.clip(inside - 1, 0, SLOPE_POINTS - 1), d)
    less = np.choose(np.clip(inside - 2, 0, SLOPE_POINTS - 1), d)
    return best, less


SWITCH_BLOCK = 200_000  # switches per vectorised block: ~50 MB of temporaries


def is_dark(key, T: int, P: int, k, q) -> np.ndarray:
    """True where the pair (sample ``k``, point ``q``) is among the sorted pair keys ``key``
    (sample × P + point) of a film with T samples and P points (k outside [0, T): False)."""
    k, q = np.asarray(k, dtype=np.int64), np.asarray(q, dtype=np.int64)
    if not len(key):
        return np.zeros(k.shape, dtype=bool)
    want = np.clip(k, 0, T - 1) * P + q
    i = np.minimum(np.searchsorted(key, want), len(key) - 1)
    return (k >= 0) & (k < T) & (key[i] == want)


def shadow_edges(gun: Gun, t, p, a, trig, s, n, part: Part, shaded_sample, shaded_point,
                 intersector=None, cuts=None):
    """(correction (P,), bound (P,), switches, cuts): what to add to the trapezoid film at
    points ``s`` (P, 3), normals ``n``, given the pairs (``shaded_sample``, ``shaded_point``)
    the segment test found shaded (every other pair lit; samples with trigger 0 untested), a
    bound on what remains of the error at the shadow edges, and where in its step each
    switch lies (a fraction). ``cuts`` from an earlier call on the same pairs (a gun path
    moved by a deflection, docs/model.md §27.7) places the switches there without a ray; the
    switches are taken in blocks of SWITCH_BLOCK (bounded memory)."""
    T, P = len(t), len(s)
    correction, bound = np.zeros(P), np.zeros(P)
    key = np.asarray(shaded_sample, np.int64) * P + np.asarray(shaded_point, np.int64)
    if not np.all(key[1:] > key[:-1]):  # a film's pairs come sorted, sample by sample
        key = np.unique(key)
    if not len(key):
        return correction, bound, 0, np.zeros(0)
    ks, qs = key // P, key % P
    live = trig > 0

    def lit(k, q):  # tested (trigger open) and not found shaded
        ok = (k >= 0) & (k < T)
        return ok & live[np.clip(k, 0, T - 1)] & ~is_dark(key, T, P, k, q)

    up, down = lit(ks + 1, qs), lit(ks - 1, qs)
    k_all = np.r_[ks[up], ks[down] - 1]  # the step k → k + 1
    q_all = np.r_[qs[up], qs[down]]
    j_all = np.r_[ks[up] + 1, ks[down] - 1]  # its lit end
    del ks, qs, up, down
    if cuts is not None and len(cuts) != len(k_all):
        raise ValueError(f"{len(cuts)} switch cuts for {len(k_all)} switches")
    out = np.empty(len(k_all))
    for b in range(0, len(k_all), SWITCH_BLOCK):
        sl = slice(b, b + SWITCH_BLOCK)
        change, residual, out[sl] = _switches(
            gun, t, p, a, trig, s[q_all[sl]], n[q_all[sl]], part, k_all[sl], q_all[sl],
            j_all[sl], lit, intersector, None if cuts is None else cuts[sl])
        correction += np.bincount(q_all[sl], weights=change, minlength=P)
        bound += np.bincount(q_all[sl], weights=residual, minlength=P)
    return correction, bound, len(k_all), out


def _switches(gun, t, p, a, trig, sq, nq, part, k, q, j, lit, intersector, cut):
    """(the film change, the bound on what remains, the cut) of each switch (step k → k + 1
    at point q, lit at sample j) of :func:`shadow_edges`."""
    T = len(t)
    left = j == k  # lit at the step's start
    if cut is None:  # the switch by bisection: [lo, hi] holds it, lo with the start's state
        lo, hi = np.zeros(len(k)), np.ones(len(k))
        for _ in range(DEPTH):
            mid = 0.5 * (lo + hi)
            pm, am, _tr = _at(p, a, trig, k, mid)
            same = visible(part, pm, sq, nq, intersector) == left
            lo, hi = np.where(same, mid, lo), np.where(same, hi, mid)
        cut = 0.5 * (lo + hi)
    a0, a1 = np.where(left, 0.0, cut), np.where(left, cut, 1.0)
    dt = t[k + 1] - t[k]
    lit_part = np.zeros(len(k))
    for x, w in zip(_GAUSS_X, _GAUSS_W):
        pg, ag, tg = _at(p, a, trig, k, 0.5 * (a0 + a1) + 0.5 * (a1 - a0) * x)
        lit_part += w * tg * pair_rate(gun, pg, ag, sq, nq)
    lit_part *= 0.5 * (a1 - a0) * dt
    fj = trig[j] * pair_rate(gun, p[j], a[j], sq, nq)
    # the chain of lit steps beyond t_j (away from the switch) ends there
    side = np.where(left, -1, 1)
    chain = lit(j + side, q)
    fs = [fj]
    for m in range(1, SLOPE_POINTS):
        i = np.clip(j + m * side, 0, T - 1)
        fs.append(trig[i] * pair_rate(gun, p[i], a[i], sq, nq))
    d3, d2 = _slope(t, fs, j, side)
    h = np.abs(t[np.clip(j + side, 0, T - 1)] - t[j])
    end = np.where(chain, side * h ** 2 / 12.0 * d3, 0.0)
    residual = (np.abs(fj) * np.abs(dt) * 2.0 ** -DEPTH
                + np.where(chain, h ** 2 / 12.0 * np.abs(d3 - d2), 0.0))
    return lit_part - 0.5 * dt * fj + end, residual, cut


__all__ = ["DEPTH", "SWITCH_BLOCK", "is_dark", "shadow_edges"]
