"""Compiled kernels (numba) of the batched pipeline: small dense linear algebra, one loop over
the samples of a stack, the GIL released (so the run's window threads use the cores).

``block_inverse`` inverts the stacked [Jc; J_tool] systems through their block-triangular
structure (docs/model.md §11). ``gram_extremes(A)`` gives λ_min and λ_max of AᵀA for every matrix of a stack, in one
compiled loop that releases the GIL: the Gram matrix, its Householder reduction to a
symmetric tridiagonal T (the first step of LAPACK's ``dsyevd``), then Laguerre's iteration on
det(T − λI), evaluated with its first two derivatives by the LDLᵀ pivot recurrence, from the
Gershgorin bounds inwards. For a polynomial with only real roots Laguerre's iteration
converges monotonically to the extreme root from outside, cubically near a simple one, so a
few steps reach it. The result is as accurate as ``numpy.linalg.eigvalsh``'s: both are
backward stable, with absolute errors of a few ε·λ_max.
"""
from __future__ import annotations

import numpy as np
from numba import njit

EPS = np.finfo(float).eps
PSD_SLACK = 1e-12  # relative: round-off may push λ_min(T) of a singular Gram below 0
MAX_STEPS = 100  # Laguerre steps: a handful for a simple root, linear at a multiple one


@njit(cache=True, nogil=True)
def _gram(A, G):
    """G = AᵀA (k × k) of one matrix A (m × k)."""
    m, k = A.shape
    for i in range(k):
        for j in range(i, k):
            acc = 0.0
            for r in range(m):
                acc += A[r, i] * A[r, j]
            G[i, j] = acc
            G[j, i] = acc


@njit(cache=True, nogil=True)
def _tridiagonalize(G, d, e, v, p):
    """Householder reduction of the symmetric G (overwritten) to diagonal d and off-diagonal
    e of a tridiagonal matrix with the same eigenvalues."""
    k = G.shape[0]
    for j in range(k - 2):
        alpha = 0.0
        for i in range(j + 1, k):
            alpha += G[i, j] * G[i, j]
        alpha = np.sqrt(alpha)
        if G[j + 1, j] > 0.0:
            alpha = -alpha
        e[j] = alpha
        if alpha == 0.0:  # column already reduced
            continue
        norm2 = 0.0
        for i in range(j + 1, k):
            v[i] = G[i, j]
        v[j + 1] -= alpha
        for i in range(j + 1, k):
            norm2 += v[i] * v[i]
        beta = 2.0 / norm2
        # G ← H G H with H = I − β v vᵀ: G −= v wᵀ + w vᵀ, w = β G v − (β² vᵀGv / 2) v
        for i in range(j + 1, k):
            acc = 0.0
            for r in range(j + 1, k):
                acc += G[i, r] * v[r]
            p[i] = beta * acc
        half = 0.0
        for i in range(j + 1, k):
            half += v[i] * p[i]
        half *= 0.5 * beta
        for i in range(j + 1, k):
            p[i] -= half * v[i]
        for i in range(j + 1, k):
            for r in range(j + 1, k):
                G[i, r] -= v[i] * p[r] + p[i] * v[r]
    for j in range(k):
        d[j] = G[j, j]
    if k > 1:
        e[k - 2] = G[k - 1, k - 2]


@njit(cache=True, nogil=True)
def _laguerre(d, e2, x, upward, tiny, tol):
    """The eigenvalue of the tridiagonal (d, e² = e2) next to x, x outside the spectrum on the
    low side (``upward``) or the high side. Pivots q_i(x) of T − xI, their x-derivatives and
    Σ q_i'/q_i = p'/p (G), −(p'/p)' (H) give Laguerre's step n / (G ∓ √((n−1)(nH − G²)))."""
    k = d.shape[0]
    for _ in range(MAX_STEPS):
        q = d[0] - x
        if q == 0.0:
            q = tiny  # x is an eigenvalue of a leading block: the usual Sturm shift
        dq, ddq = -1.0, 0.0
        g = dq / q
        h = g * g
        for i in range(1, k):
            r = e2[i - 1] / q
            q, dq, ddq = d[i] - x - r, -1.0 + r * dq / q, r * (ddq - 2.0 * dq * dq / q) / q
            if q == 0.0:
                q = tiny
            u = dq / q
            g += u
            h += u * u - ddq / q
        disc = (k - 1) * (k * h - g * g)
        root = np.sqrt(disc) if disc > 0.0 else 0.0
        den = g - root if upward else g + root
        if den == 0.0 or (g >= 0.0 if upward else g <= 0.0):
            break  # at (or, by round-off, past) the eigenvalue
        step = k / den
        x_new = x - step
        if (x_new <= x) if upward else (x_new >= x):
            break  # no more progress: converged to round-off
        x = x_new
        if abs(step) <= tol:
            break
    return x


@njit(cache=True, nogil=True)
def _below(d, e2, x):
    """Sturm count: the number of eigenvalues of the tridiagonal (d, e2) below x."""
    count, q = 0, 1.0
    for i in range(d.shape[0]):
        q = d[i] - x - (e2[i - 1] / q if i > 0 else 0.0)
        if q == 0.0:
            q = -EPS
        if q < 0.0:
            count += 1
    return count


@njit(cache=True, nogil=True)
def gram_extremes(A):
    """λ_min and λ_max (n,) of AᵀA for a stack A (n, m, k) of finite matrices."""
    n, m, k = A.shape
    lo, hi = np.empty(n), np.empty(n)
    G = np.empty((k, k))
    d, e, e2 = np.empty(k), np.zeros(max(k - 1, 1)), np.empty(max(k - 1, 1))
    v, p = np.empty(k), np.empty(k)
    for s in range(n):
        _gram(A[s], G)
        scale = 0.0
        for i in range(k):
            scale = max(scale, G[i, i])  # = max |G_ij|: work at unit scale, no overflow
        if scale == 0.0:  # the zero matrix
            lo[s] = hi[s] = 0.0
            continue
        for i in range(k):
            for j in range(k):
                G[i, j] /= scale
        _tridiagonalize(G, d, e, v, p)
        low, high = np.inf, -np.inf
        for i in range(k):
            radius = (abs(e[i - 1]) if i > 0 else 0.0) + (abs(e[i]) if i < k - 1 else 0.0)
            low = min(low, d[i] - radius)
            high = max(high, d[i] + radius)
        for i in range(k - 1):
            e2[i] = e[i] * e[i]
        tol = 4.0 * EPS * max(abs(low), abs(high))
        # AᵀA is positive semi-definite: start just below 0 when no eigenvalue of T is
        # lower (round-off), which is much nearer λ_min than Gershgorin's bound.
        start = max(low - tol, -PSD_SLACK)
        if _below(d, e2, start) > 0:
            start = low - tol
        lo[s] = scale * _laguerre(d, e2, start, True, EPS, tol)
        hi[s] = scale * _laguerre(d, e2, high + tol, False, EPS, tol)
    return lo, hi


@njit(cache=True, nogil=True)
def _invert(M, out, work):
    """out = M⁻¹ (k × k) by Gauss–Jordan with partial pivoting; False at an exactly zero pivot
    (singular M), as LAPACK's LU."""
    k = M.shape[0]
    for i in range(k):
        for j in range(k):
            work[i, j] = M[i, j]
            work[i, k + j] = 1.0 if i == j else 0.0
    for c in range(k):
        pivot, best = c, abs(work[c, c])
        for r in range(c + 1, k):
            if abs(work[r, c]) > best:
                pivot, best = r, abs(work[r, c])
        if best == 0.0:
            return False
        if pivot != c:
            for j in range(c, 2 * k):
                work[c, j], work[pivot, j] = work[pivot, j], work[c, j]
        inv = 1.0 / work[c, c]
        for j in range(c, 2 * k):
            work[c, j] *= inv
        for r in range(k):
            f = work[r, c]
            if r != c and f != 0.0:
                for j in range(c, 2 * k):
                    work[r, j] -= f * work[c, j]
    for i in range(k):
        for j in range(k):
            out[i, j] = work[i, k + j]
    return True


@njit(cache=True, nogil=True)
def block_inverse(K, top, bottom, first, second):
    """K⁻¹ (n, N, N) of a stack K (n, N, N) whose block K[bottom, second] is zero, with
    K[bottom, first] (T) and K[top, second] (X) square: from K [x1; x2] = [r1; r2],
    x1 = T⁻¹ r2 and x2 = X⁻¹ (r1 − C x1), C = K[top, first]:

        K⁻¹[first, top] = 0,  K⁻¹[first, bottom] = T⁻¹,
        K⁻¹[second, top] = X⁻¹,  K⁻¹[second, bottom] = −X⁻¹ C T⁻¹.

    Two inverses of half the size (an eighth of the work each). NaN where T or X is exactly
    singular (then so is K)."""
    n, size = K.shape[0], K.shape[1]
    h = top.shape[0]
    out = np.zeros((n, size, size))
    T, X, Ti, Xi, CTi = (np.empty((h, h)), np.empty((h, h)), np.empty((h, h)),
                         np.empty((h, h)), np.empty((h, h)))
    work = np.empty((h, 2 * h))
    for s in range(n):
        for i in range(h):
            for j in range(h):
                T[i, j] = K[s, bottom[i], first[j]]
                X[i, j] = K[s, top[i], second[j]]
        if not (_invert(T, Ti, work) and _invert(X, Xi, work)):
            out[s] = np.nan
            continue
        for i in range(h):  # C T⁻¹
            for j in range(h):
                acc = 0.0
                for r in range(h):
                    acc += K[s, top[i], first[r]] * Ti[r, j]
                CTi[i, j] = acc
        for i in range(h):
            for j in range(h):
                out[s, first[i], bottom[j]] = Ti[i, j]
                out[s, second[i], top[j]] = Xi[i, j]
                acc = 0.0
                for r in range(h):
                    acc += Xi[i, r] * CTi[r, j]
                out[s, second[i], bottom[j]] = -acc
    return out
