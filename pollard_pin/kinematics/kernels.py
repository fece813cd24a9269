"""Compiled kernels of the batched pipeline: small dense linear algebra, one loop over the
samples of a stack, the GIL released (so the run's window threads use the cores).

The loops are C (the repository's ``csrc/``), compiled into ``_kernels`` when the package is
installed: no compile wait at the first run, nothing cached per user, nothing written at run
time. These functions are their typed front: they make the inputs C-contiguous float64 / int64
and allocate the outputs; the C side checks every size and index before it computes.

``tree_placements``, ``point_jacobians`` and ``point_drifts`` evaluate the joint placements,
K = [Jc; J_tool] and its drifts K̇v on Pinocchio's model tree (docs/model.md §11);
``block_inverse`` inverts K through its block-triangular structure (§11). For the closed-loop
simulation (§18), :class:`ClosedState` finds a control tick's state from the measured actuator
angles in one call and :func:`rk4_step` does RK4's stage arithmetic around the plant's
dynamics: one sample each, where numpy's fixed cost per call would dominate (these two keep
the GIL: a few µs of work).
``gram_extremes(A)`` gives λ_min and λ_max of AᵀA for every matrix of a stack (§12): the Gram
matrix, its Householder reduction to a symmetric tridiagonal T (the first step of LAPACK's
``dsyevd``), then Laguerre's iteration on det(T − λI), evaluated with its first two
derivatives by the LDLᵀ pivot recurrence, from the Gershgorin bounds inwards. For a polynomial
with only real roots Laguerre's iteration converges monotonically to the extreme root from
outside, cubically near a simple one, so a few steps reach it. The result is as accurate as
``numpy.linalg.eigvalsh``'s: both are backward stable, with absolute errors of a few ε·λ_max.
"""
from __future__ import annotations

import numpy as np

from ..compiled import extension, f64

_c = extension("pollard_pin.kinematics._kernels")


def _i64(x):
    return np.ascontiguousarray(x, dtype=np.int64)


def gram_extremes(A):
    """λ_min and λ_max (n,) of AᵀA for a stack A (n, m, k) of finite matrices."""
    A = f64(A)
    n, m, k = A.shape
    lo, hi = np.empty(n), np.empty(n)
    _c.gram_extremes(A, n, m, k, lo, hi)
    return lo, hi


def block_inverse(K, top, bottom, first, second):
    """K⁻¹ (n, N, N) of a stack K (n, N, N) whose block K[bottom, second] is zero, with
    K[bottom, first] (T) and K[top, second] (X) square: from K [x1; x2] = [r1; r2],
    x1 = T⁻¹ r2 and x2 = X⁻¹ (r1 − C x1), C = K[top, first]:

        K⁻¹[first, top] = 0,  K⁻¹[first, bottom] = T⁻¹,
        K⁻¹[second, top] = X⁻¹,  K⁻¹[second, bottom] = −X⁻¹ C T⁻¹.

    Two inverses of half the size (Gauss–Jordan with partial pivoting, an eighth of the work
    each). NaN where T or X is exactly singular (then so is K)."""
    K = f64(K)
    n, size = K.shape[0], K.shape[1]
    top, bottom, first, second = (_i64(x) for x in (top, bottom, first, second))
    out = np.empty((n, size, size))
    _c.block_inverse(K, n, size, top, bottom, first, second, len(top), out)
    return out


def tree_placements(C, S, parent, axis, idx_q, M_rot, M_trans):
    """World rotations (J + 1, n, 3, 3) and origins (J + 1, n, 3) of J revolute joints at n
    samples, slot 0 the base, from cos/sin of the configurations (n, nq): R_j =
    R_parent M_rot_j R_axis(q), o_j = o_parent + R_parent M_trans_j (docs/model.md §11).
    ``parent`` holds each joint's parent slot, listed before it."""
    C, S = f64(C), f64(S)
    n, nq = C.shape
    J = len(axis)
    R, o = np.empty((J + 1, n, 3, 3)), np.empty((J + 1, n, 3))
    _c.tree_placements(C, S, n, nq, _i64(parent), _i64(axis), _i64(idx_q), f64(M_rot),
                       f64(M_trans), J, R, o)
    return R, o


def point_jacobians(R, o, axis, col, pt_slot, pt_local, pt_support, pt_row, pt_sign,
                    ang_point, ang_row, nv):
    """K (n, ang_row + 3, nv) and point positions (n, P, 3) from the placements R, o of
    :func:`tree_placements` (docs/model.md §11). Point i, fixed in slot pt_slot[i] at
    pt_local[i], adds pt_sign[i] · z_c × (p − o_c) to rows pt_row[i] … + 2, column col[c], for
    each revolute joint (slot) c = pt_support[i, m] (−1 ends the list) that moves it; the rows
    ang_row … + 2 are the angular velocity of point ang_point's body: z_c per column."""
    R, o = f64(R), f64(o)
    S, n = R.shape[0], R.shape[1]
    pt_support = _i64(pt_support)
    P = len(pt_slot)
    K, pos = np.empty((n, ang_row + 3, nv)), np.empty((n, P, 3))
    _c.point_jacobians(R, o, S, n, _i64(axis), _i64(col), _i64(pt_slot), f64(pt_local),
                       pt_support, pt_support.shape[1] if pt_support.ndim == 2 else 0,
                       _i64(pt_row), f64(pt_sign), P, ang_point, ang_row, nv, K, pos)
    return K, pos


def point_drifts(R, o, parent, axis, col, V, pt_slot, pt_row, pt_sign, pos, ang_point,
                 ang_row):
    """The drifts K̇ v (n, ang_row + 3) at rates V (n, nv), with K as :func:`point_jacobians`
    builds it, and every body's angular velocity ω (slots, n, 3), world axes.

    Forward recursion at q̈ = 0 (docs/model.md §11), joint j in parent body p, r = o_j − o_p:
    ω_j = ω_p + z_j q̇_j, α_j = α_p + (ω_p × z_j) q̇_j, ö_j = ö_p + α_p × r + ω_p × (ω_p × r);
    a point fixed in body b at r = x − o_b accelerates by ö_b + α_b × r + ω_b × (ω_b × r)."""
    R, o, V = f64(R), f64(o), f64(V)
    S, n = R.shape[0], R.shape[1]
    P = len(pt_slot)
    drift, omega = np.empty((n, ang_row + 3)), np.empty((S, n, 3))
    _c.point_drifts(R, o, S, n, _i64(parent), _i64(axis), _i64(col), V, V.shape[1],
                    _i64(pt_slot), _i64(pt_row), f64(pt_sign), f64(pos), P, ang_point,
                    ang_row, drift, omega)
    return drift, omega


class ClosedState:
    """A control tick's closed-loop state for one tree layout (arrays of
    :class:`~.tree.TreeArrays`; closure points first, their rows the first ``len(ia)`` of K),
    compiled: ``(steps, q, v, Jc, N, a0, lohi) = kernel(theta, dtheta, guess, tol, max_iter)``.

    Newton on the passive angles ``ip`` with the actuated ones ``ia`` at ``theta``, from
    ``guess`` (the steps of :func:`~.closure.close_loops`: stop at max |r| ≤ tol, at most
    ``max_iter`` steps, none moving an angle by more than 0.5 rad), then at the solution
    Jc = K[:m], N (v = N θ̇: N[ia] = I, N[ip] = −Jc_p⁻¹ Jc_a), v = N·dtheta, a₀ (Jc a₀ = −J̇c v,
    a₀[ia] = 0) and λ_min, λ_max of Jc_pᵀJc_p (``lohi``, as :func:`gram_extremes`).
    ``steps`` < 0 where the state was not found: −1 no convergence (or not finite), −2 / −3
    Jc_p exactly singular on the way / at the solution (docs/model.md §4, §11, §12)."""

    def __init__(self, tree, ia, ip, nq: int, nv: int):
        ang_point, ang_row = tree.tool
        self.nq, self.nv, self.m = nq, nv, len(ia)
        self._head = (_i64(tree.parent), _i64(tree.axis), _i64(tree.idx_q), _i64(tree.col),
                      f64(tree.rot), f64(tree.trans), _i64(tree.pt_slot),
                      f64(tree.pt_local), _i64(tree.pt_support), _i64(tree.pt_row),
                      f64(tree.pt_sign), _i64(ia), _i64(ip), len(tree.parent),
                      len(tree.pt_slot), tree.pt_support.shape[1], ang_point, ang_row, nq, nv,
                      len(ia))

    def __call__(self, theta, dtheta, guess, tol: float, max_iter: int):
        nv, m = self.nv, self.m
        q, v, a0 = np.empty(self.nq), np.empty(nv), np.empty(nv)
        Jc, N, lohi = np.empty((m, nv)), np.empty((nv, m)), np.empty(2)
        steps = _c.closed_state(*self._head, f64(theta), f64(dtheta), f64(guess),
                                float(tol), int(max_iter), q, v, Jc, N, a0, lohi)
        return steps, q, v, Jc, N, a0, lohi


def rk4_step(f, q, v, a1, h: float, stage_q, stage_v):
    """(q, v) after one classical RK4 step of length ``h`` of q̈ = f(q, q̇) from (q, v) with
    a1 = f(q, v) already at hand: the stages' arithmetic compiled, bit for bit numpy's
    v + (h/2)·a1, …, q + (h/6)·(v + 2v₂ + 2v₃ + v₄) (docs/model.md §18). ``f`` is called
    with ``stage_q``, ``stage_v`` (float64 (n,) arrays it may not keep: overwritten by the
    next stage) and must return n float64 values."""
    q, v = f64(q), f64(v)
    n = len(q)
    q_out, v_out = np.empty(n), np.empty(n)
    _c.rk4_step(f, q, v, f64(a1), float(h), n, stage_q, stage_v, q_out, v_out)
    return q_out, v_out
