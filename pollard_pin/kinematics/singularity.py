"""Distance to singularities (docs/model.md §12): wrist, parallel (passive-joint constraint
Jacobian) and serial (actuator-rate → tool-twist map) conditioning, the numerical floors, the
assembly-branch signs (docs/model.md §7) and the margin checks."""
from __future__ import annotations

import functools
import math

import numpy as np

from . import kernels
from .errors import BranchFlipError, SingularityError
from .margins import (  # noqa: F401  (re-exported: the defaults, floors and the rule's home)
    CHECKS,
    FLOORS,
    SERIAL_FLOOR,
    SIGMA_FLOOR,
    SINGULARITY_MARGIN,
    WRIST_MARGIN,
    Margins,
)

# σ_min from the Gram matrix's eigenvalues errs by ≈ 3 ε (σ_max/σ_min)² relatively: below this
# ratio (error ≳ 1e-7) it is recomputed by SVD.
GRAM_TRUSTED = 1e-4
# A branch sign within round-off of 0 is no sign (the sample is then singular: see floors).
BRANCH_ZERO = 64 * np.finfo(float).eps

# Branch-defining signs (docs/model.md §7), in branch_quantities() order: the chain, what
# changes sign, and the boundary the motion crosses when it does. The closed form's values are
# (branches[0], +, +, branches[1], +, branches[2], +).
BRANCH_SIGNS = (
    ("chain 0", "sin θ43·cos θ54 (the branch term of chain 0's circle equation)",
     "chain 0's reach boundary"),
    ("chain 0", "cos θ54", "θ54 = ±90° (platform arm along the θ43 axis)"),
    ("wrist", "sin θ1716", "the wrist singularity θ1716 = 0 (spray axis along the platform arm)"),
    ("leg 1", "the link's component along arm_1's swing (sin θ76_1 when β54 = 0)",
     "leg 1's reach boundary"),
    ("leg 1", "cos θ76_1", "θ76_1 = ±90°"),
    ("leg 2", "the link's component along arm_2's swing (sin θ76_2 when β54 = 0)",
     "leg 2's reach boundary"),
    ("leg 2", "cos θ76_2", "θ76_2 = ±90°"),
)


def _batched(A):
    A = np.asarray(A, dtype=float)
    return A.reshape((-1,) + A.shape[-2:]), A.shape[:-2]


def all_finite(a) -> bool:
    """True when the sum of ``a`` is finite, so every entry is (one reduction, the common
    case): False where an entry is NaN or ±inf, or finite ones overflow (a caller then looks
    at each)."""
    with np.errstate(over="ignore", invalid="ignore"):
        return math.isfinite(np.sum(a))


def finite_rows(r) -> np.ndarray:
    """(n,) True where a sample of the IK result ``r`` has every joint position, rate,
    acceleration and spherical angle and rate finite (:func:`all_finite` first: the common
    case is one reduction per array)."""
    finite = np.ones(len(r.q), bool)
    for arr in (r.q, r.v, r.a, r.spherical, r.d_spherical):
        if not all_finite(arr):
            finite &= np.isfinite(arr).all(axis=1)
    return finite


def sigma_range(A):
    """(σ_min, σ_max) of each matrix of a stack (..., m, n), m ≥ n; NaN for non-finite ones.

    From the Gram matrix's extreme eigenvalues (compiled, :mod:`.kernels`); where
    σ_min < GRAM_TRUSTED σ_max the Gram value is round-off, so those few are recomputed by SVD.
    A single matrix goes straight to SVD."""
    A = np.asarray(A, dtype=float)
    if A.ndim == 2:
        if not np.isfinite(A).all():
            return np.float64(np.nan), np.float64(np.nan)
        s = _singular_values(A)
        return s[-1], s[0]
    A, shape = _batched(A)
    ok = np.ones(len(A), bool) if all_finite(A) else np.isfinite(A).all(axis=(1, 2))
    if not ok.all():
        A = np.where(ok[:, None, None], A, 0.0)
    lo, hi = kernels.gram_extremes(A)
    smin, smax = np.sqrt(np.maximum(lo, 0.0)), np.sqrt(np.maximum(hi, 0.0))
    low = ok & ~(smin > GRAM_TRUSTED * smax)
    if low.any():
        s = np.linalg.svd(A[low], compute_uv=False)
        smin[low], smax[low] = s[:, -1], s[:, 0]
    smin[~ok] = smax[~ok] = np.nan
    return smin.reshape(shape), smax.reshape(shape)


def sigma_min(A):
    """Smallest singular value of each matrix of a stack (see :func:`sigma_range`)."""
    return sigma_range(A)[0]


def _singular_values(A) -> np.ndarray:
    """``np.linalg.svd(A, compute_uv=False)`` of one finite matrix by LAPACK's ``dgesdd``
    itself (≈ 4 µs; numpy's wrapper ≈ 7 µs, run on every control tick)."""
    global _dgesdd
    if _dgesdd is None:
        from scipy.linalg.lapack import dgesdd as _dgesdd
    s, info = _dgesdd(A, compute_uv=0)[1::2]
    if info != 0:
        raise np.linalg.LinAlgError("SVD did not converge")
    return s


_dgesdd = None


def solve_small(A, B):
    """``np.linalg.solve`` of one small system (n × n, (n,) or (n, k)) by LAPACK's ``dgesv``
    itself: ≈ 1 µs, numpy's wrapper ≈ 4 µs (the same LU; a control tick solves three).
    Raises ``np.linalg.LinAlgError`` where A is exactly singular, as numpy does."""
    global _dgesv
    if _dgesv is None:  # scipy.linalg on first use: not at import (the CLI's start-up)
        from scipy.linalg.lapack import dgesv as _dgesv
    _, _, x, info = _dgesv(A, B)
    if info != 0:
        raise np.linalg.LinAlgError(f"singular matrix (dgesv info {info})")
    return x


_dgesv = None


def solve_stack(A, B):
    """``np.linalg.solve`` over a stack (..., n, n), (..., n, k), except that a singular member
    gives NaN instead of failing the whole stack. Returns (X, singular mask or None)."""
    try:
        return np.linalg.solve(A, B), None
    except np.linalg.LinAlgError:
        pass
    A2, shape = _batched(A)
    B2 = np.broadcast_to(B, shape + B.shape[-2:]).reshape((-1,) + B.shape[-2:])
    bad = np.linalg.slogdet(A2)[0] == 0  # the same LU as solve: an exactly zero pivot
    A2 = np.where(bad[:, None, None], np.eye(A2.shape[-1]), A2)
    try:
        X = np.linalg.solve(A2, B2)
    except np.linalg.LinAlgError:  # pivots judged differently: go one by one
        X = np.empty(B2.shape)
        for k in range(len(A2)):
            try:
                X[k] = np.linalg.solve(A2[k], B2[k])
            except np.linalg.LinAlgError:
                bad[k] = True
    X[bad] = np.nan
    return X.reshape(shape + B.shape[-2:]), bad.reshape(shape)


def inverse_stack(A):
    """``np.linalg.inv`` over a stack (..., n, n), NaN for a singular member (never raises)."""
    try:
        return np.linalg.inv(A)
    except np.linalg.LinAlgError:
        n = A.shape[-1]
        X, _ = solve_stack(A, np.broadcast_to(np.eye(n), A.shape))
        return X


def _velocity_map(Jc, actuated_v, passive_v):
    """N of :func:`actuator_velocity_map`, NaN where Jc_p is exactly singular; and that mask."""
    N = np.zeros(Jc.shape[:-2] + (Jc.shape[-1], len(actuated_v)))
    N[..., actuated_v, :] = _identity(len(actuated_v))
    if Jc.ndim == 2:  # one matrix (a control tick): no stack bookkeeping
        try:
            N[passive_v] = -solve_small(Jc[:, passive_v], Jc[:, actuated_v])
            return N, None
        except np.linalg.LinAlgError:
            pass
    X, bad = solve_stack(Jc[..., passive_v], Jc[..., actuated_v])
    N[..., passive_v, :] = -X
    return N, bad


@functools.cache
def _identity(n: int) -> np.ndarray:
    eye = np.eye(n)
    eye.flags.writeable = False
    return eye


def actuator_velocity_map(Jc: np.ndarray, actuated_v, passive_v, t=None) -> np.ndarray:
    """N (..., nv, 6) with v = N q̇_act on the closed loops: Jc_p q̇_p = −Jc_a q̇_act.

    Raises :class:`SingularityError` (chain "parallel", the sample index of a stack, its time
    from ``t``, σ) where Jc_p is singular and N would not be finite. (Cheap: σ is measured only
    then; :func:`check_margins` applies the numerical floor along IK results.)"""
    Jc = np.asarray(Jc, dtype=float)
    N, _ = _velocity_map(Jc, actuated_v, passive_v)
    if math.isfinite(N.sum()):  # every entry finite: one reduction, the common case
        return N
    bad = ~np.isfinite(N).all(axis=(-2, -1))
    if bad.any():
        k = int(np.argmax(bad.reshape(-1)))
        smin, smax = (float(x) for x in sigma_range(
            Jc.reshape((-1,) + Jc.shape[-2:])[k][:, passive_v]))
        raise SingularityError(
            f"the passive-joint constraint Jacobian Jc_p is singular (smallest singular value "
            f"{smin:.3g}, largest {smax:.3g}): the actuator-velocity map is not finite "
            "(parallel singularity, docs/model.md §12)", sigma=smin, chain="parallel",
            sample=None if Jc.ndim == 2 else k,
            time=None if t is None else float(np.atleast_1d(t)[k]))
    return N


def conditioning(K: np.ndarray, actuated_v, passive_v, full: bool = False, K_inv=None):
    """σ_min of the passive-joint constraint Jacobian (parallel singularity) and of the
    actuator-rate → tool-twist map (serial singularity), from K = [Jc; J_tool] (..., 12, nv);
    with ``full`` also their σ_max (the scale of the numerical floors). Never raises: where
    Jc_p is exactly singular the serial values are NaN.

    With ``K_inv`` (K⁻¹, already at hand in the batched IK) the serial map is not formed: since
    K v = [0; twist] gives q̇_act = K⁻¹[act, 6:] twist, (J_tool N)⁻¹ = K⁻¹[act, 6:], so its
    singular values are the reciprocals of that block's (docs/model.md §12)."""
    Jc, Jt = K[..., :6, :], K[..., 6:, :]
    sp, sp_max = sigma_range(Jc[..., passive_v])
    if K_inv is None:
        ss, ss_max = sigma_range(Jt @ _velocity_map(Jc, actuated_v, passive_v)[0])
    else:
        with np.errstate(divide="ignore"):
            lo, hi = sigma_range(K_inv[..., actuated_v, 6:])
            ss, ss_max = np.atleast_1d(1.0 / hi), np.atleast_1d(1.0 / lo)
        bad = ~np.isfinite(ss)
        if bad.any():  # K singular: its inverse says nothing, the map itself is still defined
            ss[bad], ss_max[bad] = sigma_range(
                Jt[bad] @ _velocity_map(Jc[bad], actuated_v, passive_v)[0])
    return (sp, ss, sp_max, ss_max) if full else (sp, ss)


class BranchQuantities:
    """The joint indices and U-joint twists of :func:`branch_quantities`, looked up once."""

    NAMES = ("theta43", "theta54", "theta1716", "theta65_1", "theta76_1", "theta65_2",
             "theta76_2")

    def __init__(self, robot):
        self.idx = [robot.idx_q(n) for n in self.NAMES]
        self.beta = [(np.cos(leg.beta54), np.sin(leg.beta54)) for leg in robot.params.legs]

    def __call__(self, q) -> np.ndarray:
        q = np.asarray(q, dtype=float)
        if q.ndim == 1:  # one configuration (per-sample Newton): scalar math is 10x faster
            t43, t54, t1716, t65a, t76a, t65b, t76b = (float(q[i]) for i in self.idx)
            c54 = math.cos(t54)
            out = [math.sin(t43) * c54, c54, math.sin(t1716)]
            for (cb, sb), t65, t76 in zip(self.beta, (t65a, t65b), (t76a, t76b)):
                c76 = math.cos(t76)
                out += [cb * math.sin(t76) + sb * math.sin(t65) * c76, c76]
            return np.array(out)
        t43, t54, t1716, t65a, t76a, t65b, t76b = (q[..., i] for i in self.idx)
        c54 = np.cos(t54)
        out = [np.sin(t43) * c54, c54, np.sin(t1716)]
        for (cb, sb), t65, t76 in zip(self.beta, (t65a, t65b), (t76a, t76b)):
            # Component of the link direction along the elbow's swing Rz(θ21) e_y in the
            # cross frame Rx(β54): ∝ the circle equation's derivative, whose sign is the branch.
            c76 = np.cos(t76)
            out += [cb * np.sin(t76) + sb * np.sin(t65) * c76, c76]
        return np.stack(out, axis=-1)

    def signs(self, q) -> np.ndarray:
        v = self(q)
        return np.where(np.abs(v) <= BRANCH_ZERO, 0.0, np.sign(v))

    def signs_list(self, q) -> list:
        """:meth:`signs` of one configuration as a list of floats (cheap per-sample path)."""
        return [0.0 if abs(x) <= BRANCH_ZERO else math.copysign(1.0, x)
                for x in self(q).tolist()]


def branch_quantities(robot, q) -> np.ndarray:
    """(..., 7) values whose signs define the assembly mode (:data:`BRANCH_SIGNS` order), from
    tree configurations q (..., nq). Each is a geometric quantity, unchanged by the equivalent
    joint-angle representation (θ ↦ π − θ with its partner + π)."""
    return BranchQuantities(robot)(q)


def branch_signs(robot, q) -> np.ndarray:
    """Signs (−1, 0, +1) of :func:`branch_quantities`, 0 within BRANCH_ZERO of 0."""
    return BranchQuantities(robot).signs(q)


def same_branch(signs, reference) -> bool:
    """No sign of ``signs`` opposes ``reference`` (zeros, i.e. boundaries, match anything)."""
    return not any(a * b < 0 for a, b in zip(signs, reference))


def flip_error(k0: int, k: int, j: int, v0: float, v1: float, t,
               near: float | None = None) -> BranchFlipError:
    """The :class:`BranchFlipError` for sign ``j`` of :data:`BRANCH_SIGNS` going from v0
    (sample k0) to v1 (sample k, time t; crossing near time ``near`` when known)."""
    chain, what, boundary = BRANCH_SIGNS[j]
    where = "" if near is None else f" near t = {near:.6g} s"
    return BranchFlipError(
        f"assembly branch flip between samples {k0} and {k}: {what} changed sign "
        f"({v0:+.3g} → {v1:+.3g}), so the motion crossed {boundary}{where}; the IK keeps one "
        "assembly mode (docs/model.md §7, §9): split the trajectory there",
        sample=k, time=None if t is None else float(t), chain=chain, amount=abs(float(v1)))


def _first_flip(robot, q):
    """(k0, k, column, v0, v1) of the first branch-sign change along q (N, nq), or None."""
    if len(q) < 2:
        return None
    v = BranchQuantities(robot)(q)
    s = np.where(np.abs(v) <= BRANCH_ZERO, 0.0, np.sign(v))
    best = None
    for j in range(s.shape[1]):
        nz = np.flatnonzero(s[:, j])
        ch = np.flatnonzero(s[nz[1:], j] != s[nz[:-1], j])
        if len(ch) and (best is None or nz[ch[0] + 1] < best[1]):
            k0, k = int(nz[ch[0]]), int(nz[ch[0] + 1])
            best = (k0, k, j, float(v[k0, j]), float(v[k, j]))
    return best


# How check_margins names each check of CHECKS: the quantity, and why it matters.
_LABELS = {"wrist": ("wrist |sin θ1716| =", " (spray axis nearly parallel to the platform arm)"),
           "parallel": ("parallel (passive-joint constraint Jacobian) smallest singular value",
                        ""),
           "serial": ("serial (actuator-rate to tool-twist map) smallest singular value", ""),
           **{f"spherical joint {i}": (f"|sin θ109_{i}| =",
                                       f" (θ98_{i}, θ1110_{i} and their rates are undefined "
                                       "there)") for i in (1, 2)}}


def floor_message(label, v, margin, limit, floor) -> str:
    """'<label> v is below the margin m', or, when the floor (``limit``) is the larger, that v
    is at round-off level."""
    if margin >= limit:
        return f"{label} {v:.4g} is below the margin {margin:g}"
    return (f"{label} {v:.4g} is at round-off level: below the numerical floor {limit:.3g} "
            f"({floor:g} relative, docs/model.md §12)")


def check_margins(robot, r, margins: Margins):
    """Raise at the first sample that violates :meth:`Margins.violations` (the margins raised
    to the numerical floors SIGMA_FLOOR, SERIAL_FLOOR: even with margins 0), with non-finite
    results, or whose assembly-branch signs differ from the previous sample's (a real branch
    flip)."""
    n = len(r)
    sp_max = getattr(r, "sigma_parallel_max", None)
    ss_max = getattr(r, "sigma_serial_max", None)
    sp_max, ss_max = (np.ones(n) if m is None else m for m in (sp_max, ss_max))
    values = {"wrist": r.wrist_margin, "parallel": r.sigma_parallel,
              "serial": r.sigma_serial}
    # The cut spherical joints' ZYZ angles: rates undefined at sin θ109 = 0.
    sph = [np.abs(np.sin(r.spherical[:, 3 * i - 2])) for i in (1, 2)]
    values["spherical joint 1"], values["spherical joint 2"] = sph
    bad = margins.violations(wrist=values["wrist"], parallel=values["parallel"],
                             serial=values["serial"], parallel_max=sp_max,
                             serial_max=ss_max, spherical=sph)
    limits = margins.limits(sp_max, ss_max)
    first = None
    for check in CHECKS:
        k = np.flatnonzero(bad[check])
        if len(k) and (first is None or k[0] < first[0]):
            k = int(k[0])
            v = float(values[check][k])
            lim = float(np.broadcast_to(limits[check], (n,))[k])
            label, why = _LABELS[check]
            first = (k, SingularityError(
                floor_message(label, v, margins.margin(check), lim, FLOORS[check]) + why,
                sigma=v,
                sample=k, time=float(r.t[k]), chain=check,
                amount=lim - v if np.isfinite(v) else None))
    bad = np.flatnonzero(~finite_rows(r))
    if len(bad) and (first is None or bad[0] < first[0]):
        k = int(bad[0])
        first = (k, SingularityError(
            "joint positions, rates or accelerations are not finite (a singular linear "
            "system, docs/model.md §12)", sample=k, time=float(r.t[k]), chain="kinematics"))
    flip = _first_flip(robot, r.q[:first[0] + 1] if first is not None else r.q)
    if flip is not None and (first is None or flip[1] < first[0]):
        k0, k, j, v0, v1 = flip
        first = (k, flip_error(k0, k, j, v0, v1, r.t[k]))
    if first is not None:
        raise first[1]
