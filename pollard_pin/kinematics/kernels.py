"""Compiled kernels (numba) of the batched pipeline: small dense linear algebra, one loop over
the samples of a stack, the GIL released (so the run's window threads use the cores).

``tree_placements``, ``point_jacobians`` and ``point_drifts`` evaluate the joint placements,
K = [Jc; J_tool] and its drifts K̇v on Pinocchio's model tree (docs/model.md §11);
``block_inverse`` inverts K through its block-triangular structure (§11).
``gram_extremes(A)`` gives λ_min and λ_max of AᵀA for every matrix of a stack (§12): the Gram
matrix, its Householder reduction to a
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
def _laguerre(d, e2, x, upward, tol):
    """The eigenvalue of the tridiagonal (d, e² = e2) next to x, x outside the spectrum on the
    low side (``upward``) or the high side. Pivots q_i(x) of T − xI, their x-derivatives and
    Σ q_i'/q_i = p'/p (G), −(p'/p)' (H) give Laguerre's step n / (G ∓ √((n−1)(nH − G²)))."""
    k = d.shape[0]
    for _ in range(MAX_STEPS):
        q = d[0] - x
        if q == 0.0:
            q = EPS  # x is an eigenvalue of a leading block: the usual Sturm shift
        iq = 1.0 / q  # one division per row: they dominate the cost
        dq, ddq = -1.0, 0.0
        g = -iq
        h = g * g
        for i in range(1, k):
            r = e2[i - 1] * iq
            q, dq, ddq = d[i] - x - r, -1.0 + r * dq * iq, r * (ddq - 2.0 * dq * dq * iq) * iq
            if q == 0.0:
                q = EPS
            iq = 1.0 / q
            u = dq * iq
            g += u
            h += u * u - ddq * iq
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
        inv = 1.0 / scale
        for i in range(k):
            for j in range(k):
                G[i, j] *= inv
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
        lo[s] = scale * _laguerre(d, e2, start, True, tol)
        hi[s] = scale * _laguerre(d, e2, high + tol, False, tol)
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


@njit(cache=True, nogil=True)
def tree_placements(C, S, parent, axis, idx_q, M_rot, M_trans):
    """World rotations (J + 1, n, 3, 3) and origins (J + 1, n, 3) of J revolute joints at n
    samples, slot 0 the base, from cos/sin of the configurations (n, nq): R_j =
    R_parent M_rot_j R_axis(q), o_j = o_parent + R_parent M_trans_j (docs/model.md §11).
    ``parent`` holds each joint's parent slot, listed before it."""
    n, J = C.shape[0], axis.shape[0]
    R = np.empty((J + 1, n, 3, 3))
    o = np.empty((J + 1, n, 3))
    B = np.empty((3, 3))
    for s in range(n):
        for a in range(3):
            o[0, s, a] = 0.0
            for b in range(3):
                R[0, s, a, b] = 1.0 if a == b else 0.0
    for j in range(J):  # joint by joint: each pass streams through its parent's arrays
        p, ax = parent[j], axis[j]
        i1, i2 = (ax + 1) % 3, (ax + 2) % 3
        for s in range(n):
            c, sn = C[s, idx_q[j]], S[s, idx_q[j]]
            for a in range(3):
                acc = 0.0
                for b in range(3):
                    B[a, b] = (R[p, s, a, 0] * M_rot[j, 0, b] + R[p, s, a, 1] * M_rot[j, 1, b]
                               + R[p, s, a, 2] * M_rot[j, 2, b])
                    acc += R[p, s, a, b] * M_trans[j, b]
                o[j + 1, s, a] = o[p, s, a] + acc
                # B · R_axis(q): the axis column stays, the other two turn by q
                R[j + 1, s, a, ax] = B[a, ax]
                R[j + 1, s, a, i1] = B[a, i1] * c + B[a, i2] * sn
                R[j + 1, s, a, i2] = B[a, i2] * c - B[a, i1] * sn
    return R, o


@njit(cache=True, nogil=True)
def point_jacobians(R, o, axis, col, pt_slot, pt_local, pt_support, pt_row, pt_sign,
                    ang_point, ang_row, nv):
    """K (n, ang_row + 3, nv) and point positions (n, P, 3) from the placements R, o of
    :func:`tree_placements` (docs/model.md §11). Point i, fixed in slot pt_slot[i] at
    pt_local[i], adds pt_sign[i] · z_c × (p − o_c) to rows pt_row[i] … + 2, column col[c], for
    each revolute joint (slot) c = pt_support[i, m] (−1 ends the list) that moves it; the rows
    ang_row … + 2 are the angular velocity of point ang_point's body: z_c per column."""
    n, P = R.shape[1], pt_slot.shape[0]
    K = np.zeros((n, ang_row + 3, nv))
    pos = np.empty((n, P, 3))
    for s in range(n):
        for i in range(P):
            b, row, sign = pt_slot[i], pt_row[i], pt_sign[i]
            for a in range(3):
                pos[s, i, a] = (R[b, s, a, 0] * pt_local[i, 0] + R[b, s, a, 1] * pt_local[i, 1]
                                + R[b, s, a, 2] * pt_local[i, 2] + o[b, s, a])
            for m in range(pt_support.shape[1]):
                c = pt_support[i, m]
                if c < 0:
                    break
                ax, v = axis[c], col[c]
                z0, z1, z2 = R[c, s, 0, ax], R[c, s, 1, ax], R[c, s, 2, ax]
                d0, d1, d2 = (pos[s, i, 0] - o[c, s, 0], pos[s, i, 1] - o[c, s, 1],
                              pos[s, i, 2] - o[c, s, 2])
                K[s, row, v] += sign * (z1 * d2 - z2 * d1)
                K[s, row + 1, v] += sign * (z2 * d0 - z0 * d2)
                K[s, row + 2, v] += sign * (z0 * d1 - z1 * d0)
                if i == ang_point:
                    for a in range(3):
                        K[s, ang_row + a, v] = R[c, s, a, ax]
    return K, pos


@njit(cache=True, nogil=True, inline="always")
def _cross3(a, b, out):
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]


@njit(cache=True, nogil=True)
def point_drifts(R, o, parent, axis, col, V, pt_slot, pt_row, pt_sign, pos, ang_point,
                 ang_row):
    """The drifts K̇ v (n, ang_row + 3) at rates V (n, nv), with K as :func:`point_jacobians`
    builds it, and every body's angular velocity ω (slots, n, 3), world axes.

    Forward recursion at q̈ = 0 (docs/model.md §11), joint j in parent body p, r = o_j − o_p:
    ω_j = ω_p + z_j q̇_j, α_j = α_p + (ω_p × z_j) q̇_j, ö_j = ö_p + α_p × r + ω_p × (ω_p × r);
    a point fixed in body b at r = x − o_b accelerates by ö_b + α_b × r + ω_b × (ω_b × r)."""
    S, n = R.shape[0], R.shape[1]
    drift = np.zeros((n, ang_row + 3))
    omega = np.empty((S, n, 3))
    w, al, acc = np.zeros((S, 3)), np.zeros((S, 3)), np.zeros((S, 3))
    r, t1, t2 = np.empty(3), np.empty(3), np.empty(3)
    for s in range(n):
        for a in range(3):
            omega[0, s, a] = 0.0
        for j in range(1, S):
            p = parent[j]
            for a in range(3):
                r[a] = o[j, s, a] - o[p, s, a]
            _cross3(al[p], r, t1)
            _cross3(w[p], r, t2)
            _cross3(w[p], t2, r)  # ω_p × (ω_p × r), r no longer needed
            qd = V[s, col[j]]
            ax = axis[j]
            for a in range(3):
                acc[j, a] = acc[p, a] + t1[a] + r[a]
                t1[a] = R[j, s, a, ax]  # z_j
            _cross3(w[p], t1, t2)
            for a in range(3):
                al[j, a] = al[p, a] + t2[a] * qd
                w[j, a] = w[p, a] + t1[a] * qd
                omega[j, s, a] = w[j, a]
        for i in range(pt_slot.shape[0]):
            b, row, sign = pt_slot[i], pt_row[i], pt_sign[i]
            for a in range(3):
                r[a] = pos[s, i, a] - o[b, s, a]
            _cross3(al[b], r, t1)
            _cross3(w[b], r, t2)
            _cross3(w[b], t2, r)
            for a in range(3):
                drift[s, row + a] += sign * (acc[b, a] + t1[a] + r[a])
        for a in range(3):
            drift[s, ang_row + a] = al[pt_slot[ang_point], a]
    return drift, omega
