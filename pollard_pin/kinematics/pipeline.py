"""Constrained inverse kinematics along a trajectory (docs/model.md §7, §11): positions,
velocities and accelerations of all tree joints from the tool pose, batched or per sample."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin

from ..analytic import closed_form
from ..analytic.taskspace import TaskInputError, check_task_array, rotation, twist, twist_dot
from ..model.build import TIP_FRAME, Robot, constraint_jacobian
from ..timing import Stopwatch
from .errors import KinematicsError, KinematicsInputError, SingularityError, UnreachablePoseError
from .singularity import (
    SERIAL_FLOOR,
    SIGMA_FLOOR,
    SINGULARITY_MARGIN,
    WRIST_MARGIN,
    BranchQuantities,
    check_margins,
    conditioning,
    flip_error,
    floor_message,
    inverse_stack,
    same_branch,
)

IK_TOL = 1e-12  # m / rad, closure residual and tool-pose error reached by Newton


def _zyz(M: np.ndarray) -> np.ndarray:
    """ZYZ angles (..., 3) of M = Rz(a) Ry(b) Rz(c) (..., 3, 3), b in [0, π] (docs/model.md §4).
    b from atan2(sin b, cos b): accurate to round-off near 0 and π, where arccos is not."""
    b = np.arctan2(np.hypot(M[..., 0, 2], M[..., 1, 2]), M[..., 2, 2])
    return np.stack([np.arctan2(M[..., 1, 2], M[..., 0, 2]), b,
                     np.arctan2(M[..., 2, 1], -M[..., 2, 0])], axis=-1)


def _zyz_rates(ang: np.ndarray, w: np.ndarray) -> np.ndarray:
    """(ȧ, ḃ, ċ) from w, where Ṁ Mᵀ = ŵ and w = ȧ e_z + ḃ Rz(a) e_y + ċ Rz(a)Ry(b) e_z.

    Solved in closed form: Rz(−a) w = (ċ sin b, ḃ, ȧ + ċ cos b). At sin b = 0 (θ109 = 0 or π)
    the system is singular and the rates are not finite; :func:`check_margins` rejects such
    samples (|sin θ109| below SIGMA_FLOOR, docs/model.md §12)."""
    if ang.ndim == 1:  # one sample (per-sample Newton): scalar math
        a, b = float(ang[0]), float(ang[1])
        wx, wy, wz = w.tolist()
        ca, sa, sb = math.cos(a), math.sin(a), math.sin(b)
        cdot = (ca * wx + sa * wy) / sb if sb else math.copysign(math.inf, ca * wx + sa * wy)
        return np.array([wz - cdot * math.cos(b), ca * wy - sa * wx, cdot])
    a, b = ang[..., 0], ang[..., 1]
    ca, sa = np.cos(a), np.sin(a)
    wx = ca * w[..., 0] + sa * w[..., 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        cdot = wx / np.sin(b)
    return np.stack([w[..., 2] - cdot * np.cos(b), ca * w[..., 1] - sa * w[..., 0], cdot],
                    axis=-1)


@dataclass
class KinematicFrames:
    """Frame and joint ids used on the hot path, looked up once."""

    tip: int
    closure_a: tuple[int, ...]
    closure_b: tuple[int, ...]
    link_joints: tuple[int, ...]
    platform_joint: int
    spherical_offset: tuple[np.ndarray, ...]  # Rz(−β1413i)
    actuated_v: np.ndarray
    passive_v: np.ndarray
    wrist_q: int

    @classmethod
    def of(cls, robot: Robot) -> "KinematicFrames":
        def rz(a):
            c, s = np.cos(a), np.sin(a)
            return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])

        return cls(tip=robot.tip_frame,
                   closure_a=tuple(robot.frame_id(c.frame_a) for c in robot.closures),
                   closure_b=tuple(robot.frame_id(c.frame_b) for c in robot.closures),
                   link_joints=tuple(robot.joint_id(f"theta76_{i}") for i in (1, 2)),
                   platform_joint=robot.joint_id("theta54"),
                   spherical_offset=tuple(rz(-leg.beta1413) for leg in robot.params.legs),
                   actuated_v=robot.actuated_v, passive_v=robot.passive_v,
                   wrist_q=robot.idx_q("theta1716"))


def _pose_error(model, data, fr: KinematicFrames, q, p_des, R_des):
    """[closure residual (6); tip position error (3); tip orientation error (3)], world axes."""
    pin.forwardKinematics(model, data, q)
    for f in fr.closure_a + fr.closure_b + (fr.tip,):
        pin.updateFramePlacement(model, data, f)
    res = [data.oMf[a].translation - data.oMf[b].translation
           for a, b in zip(fr.closure_a, fr.closure_b)]
    tip = data.oMf[fr.tip]
    res.append(tip.translation - p_des)
    res.append(pin.log3(tip.rotation @ R_des.T))
    return np.concatenate(res)


def _kinematic_matrix(model, data, cms, cds, fr: KinematicFrames, q):
    """K = [Jc; J_tool] (12 × 12), world axes: K v = [closure velocity; tool twist]."""
    Jc = constraint_jacobian(model, data, cms, cds, q)
    Jt = pin.getFrameJacobian(model, data, fr.tip, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    return np.vstack([Jc, Jt])


def _drifts(model, data, fr: KinematicFrames, q, v):
    """[closure acceleration drift; tool drift] at a = 0: K̇ v from classical accelerations."""
    pin.forwardKinematics(model, data, q, v, np.zeros(model.nv))
    LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
    out = [pin.getFrameClassicalAcceleration(model, data, a, LWA).linear
           - pin.getFrameClassicalAcceleration(model, data, b, LWA).linear
           for a, b in zip(fr.closure_a, fr.closure_b)]
    acc = pin.getFrameClassicalAcceleration(model, data, fr.tip, LWA)
    out += [acc.linear, acc.angular]
    return np.concatenate(out)


def _spherical(data, fr: KinematicFrames):
    """Cut spherical-joint angles (6,) and rates (6,) after forwardKinematics(q, v)."""
    oMp = data.oMi[fr.platform_joint]
    w_p = oMp.rotation @ data.v[fr.platform_joint].angular
    ang, rate = [], []
    for jl, C in zip(fr.link_joints, fr.spherical_offset):
        oMl = data.oMi[jl]
        a = _zyz(oMl.rotation.T @ oMp.rotation @ C)
        ang.append(a)
        rate.append(_zyz_rates(a, oMl.rotation.T @ (w_p - oMl.rotation @ data.v[jl].angular)))
    return np.concatenate(ang), np.concatenate(rate)


@dataclass
class IKResult:
    """Joint motion along a trajectory. Arrays have one row per sample; tree joints in
    :attr:`Robot.joint_names` order, spherical angles in :data:`SPHERICAL` order."""

    t: np.ndarray
    poses: np.ndarray
    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    spherical: np.ndarray
    d_spherical: np.ndarray
    closure_residual: np.ndarray  # max |p_A − p_B| component [m]
    tool_error: np.ndarray  # max |pose error| component [m, rad]
    wrist_margin: np.ndarray  # |sin θ1716|
    sigma_parallel: np.ndarray  # σ_min of Jc over the passive joints
    sigma_serial: np.ndarray  # σ_min of the actuator-rate → tool-twist map
    joint_names: tuple[str, ...] = field(default=())
    constraint_jacobian: np.ndarray | None = None  # (N, 6, nv) at q, reused by dynamics
    sigma_parallel_max: np.ndarray | None = None  # σ_max of the same maps: the scale of the
    sigma_serial_max: np.ndarray | None = None  # numerical floors (docs/model.md §12)

    def __len__(self) -> int:
        return len(self.t)


def _newton(model, data, cms, cds, fr, q, p_des, R_des, tol, max_iter):
    e = _pose_error(model, data, fr, q, p_des, R_des)
    polished = False
    for _ in range(max_iter):
        if np.abs(e).max() <= tol:
            if polished:
                return q, e, True
            polished = True  # one more step past tol: quadratic convergence to round-off
        K = _kinematic_matrix(model, data, cms, cds, fr, q)
        try:
            step = np.linalg.solve(K, e)
        except np.linalg.LinAlgError:  # exactly singular K on the way: least-squares step
            step = np.linalg.lstsq(K, e, rcond=None)[0]
        q = q - step * min(1.0, 0.5 / max(np.abs(step).max(), 1e-300))
        e = _pose_error(model, data, fr, q, p_des, R_des)
    return q, e, np.abs(e).max() <= tol


MIN_SUBSTEP = 2.0 ** -10  # finest continuation step, as a fraction of one sample interval


def _follow(solve, signs_of, q0, pose_a, pose_b, ref):
    """Newton continuation from q0 (solution at pose_a) along the straight pose segment to
    pose_b, halving the step until Newton converges on the branch signs ``ref``.

    Returns (q, e, ok, flip): flip = (s, q_before, q_after) when a step of MIN_SUBSTEP from a
    solution on ``ref`` (q_before) still converges on other signs (q_after) at the fraction s:
    the segment crosses the boundary of the assembly mode (docs/model.md §7), a real flip."""
    s, h, q, q_old, s_old, e = 0.0, 1.0, q0, None, 0.0, None
    while s < 1.0:
        s1 = min(1.0, s + h)
        guess = q if q_old is None else q + (s1 - s) / (s - s_old) * (q - q_old)
        qn, e, ok = solve(guess, pose_a + s1 * (pose_b - pose_a))
        if ok and same_branch(signs_of(qn), ref):
            q_old, s_old, q, s, h = q, s, qn, s1, 2.0 * h
            continue
        if h <= MIN_SUBSTEP:
            return qn, e, False, ((s1, q, qn) if ok else None)
        h *= 0.5
    return q, e, True, None


def _diagnose(robot: Robot, pose, k, tk, e, wrist_margin):
    """Why Newton failed at sample k: the closed form names the chain and the shortfall."""
    try:
        _closed_form(robot, np.asarray(pose)[None, :], np.array([tk]), wrist_margin)
    except KinematicsError as exc:
        extra = {"sigma": exc.sigma} if isinstance(exc, SingularityError) else {}
        return type(exc)(exc.detail, sample=k, time=tk, chain=exc.chain, amount=exc.amount,
                         **extra)
    return UnreachablePoseError(
        f"Newton did not converge to pose {np.round(pose, 6).tolist()}: closure residual "
        f"{np.abs(e[:6]).max():.3g} m, tool error {np.abs(e[6:]).max():.3g} (m/rad)",
        sample=k, time=tk, amount=float(np.abs(e).max()))


MIN_TIME_STEP = 1e-9  # s: closer samples are duplicated or mis-scaled times (a 1 GHz rate)


def _task_inputs(poses, d_poses, dd_poses, t):
    """Validated (N, 6) poses, rates, accelerations (zeros when None) and times (N,).

    Raises :class:`KinematicsInputError` naming the cause: an empty or mis-shaped array,
    times that are not finite or not increasing by at least MIN_TIME_STEP (sample k), or a
    non-finite or absurd entry (column x … phi, d_x … d_phi, dd_x … dd_phi; sample, value)."""
    poses = np.atleast_2d(np.asarray(poses, dtype=float))
    n = len(poses)
    if poses.size == 0:
        raise KinematicsInputError(f"no samples: the pose array is empty (shape "
                                   f"{poses.shape}); give at least one pose (x, y, z, psi, "
                                   "theta, phi)")
    t = np.arange(n, dtype=float) if t is None else np.asarray(t, dtype=float).reshape(-1)
    arrays = [poses]
    for arr in (d_poses, dd_poses):
        arrays.append(np.zeros_like(poses) if arr is None
                      else np.atleast_2d(np.asarray(arr, dtype=float)))
    names = ("pose", "pose rate", "pose acceleration")
    for name, arr in zip(names, arrays):
        if arr.shape != (n, 6):
            raise KinematicsInputError(f"{name} array has shape {arr.shape}, expected ({n}, 6) "
                                       "(x, y, z, psi, theta, phi per sample)")
    if t.shape != (n,):
        raise KinematicsInputError(f"times have shape {t.shape}, expected ({n},)")
    bad = np.flatnonzero(~np.isfinite(t))
    if len(bad):
        k = int(bad[0])
        raise KinematicsInputError(f"time t = {t[k]} is not a finite number", sample=k,
                                   chain="t")
    if n > 1:
        dt = np.diff(t)
        bad = np.flatnonzero(~(dt >= MIN_TIME_STEP))
        if len(bad):
            k = int(bad[0]) + 1
            what = ("times are not increasing" if dt[k - 1] <= 0 else
                    f"time step too small (below {MIN_TIME_STEP:g} s)")
            raise KinematicsInputError(
                f"{what}: t = {t[k]:.17g} s follows t = {t[k - 1]:.17g} s at sample {k - 1} "
                f"(step {dt[k - 1]:.3g} s)", sample=k, time=float(t[k]), chain="t",
                amount=float(dt[k - 1]))
    try:
        for prefix, arr in zip(("", "d_", "dd_"), arrays):
            check_task_array(arr, prefix)
    except TaskInputError as exc:
        raise KinematicsInputError(exc.detail, sample=exc.sample, time=float(t[exc.sample]),
                                   chain=exc.column, amount=abs(exc.value)) from None
    return (*arrays, t)


def _check_options(tol, singularity_margin, wrist_margin, **counts) -> None:
    """Reject a non-finite, negative (or, for wrist_margin, > 1) margin, a tolerance that is not
    a positive number and counts below 1, before any work (:class:`KinematicsInputError`)."""
    rules = (("singularity_margin", singularity_margin, 0.0, np.inf, "a finite number >= 0"),
             ("wrist_margin", wrist_margin, 0.0, 1.0,
              "a number in [0, 1] (the smallest |sin θ1716| allowed)"),
             ("tol", tol, np.finfo(float).tiny, np.inf, "a finite number > 0"))
    for name, value, lo, hi, rule in rules:
        try:
            x = float(value)
        except (TypeError, ValueError):
            x = np.nan
        if not (lo <= x <= hi and np.isfinite(x)):
            raise KinematicsInputError(f"{name} = {value!r}: must be {rule}", chain=name)
    for name, value in counts.items():
        if not (isinstance(value, (int, np.integer)) and value >= 1):
            raise KinematicsInputError(f"{name} = {value!r}: must be an integer >= 1",
                                       chain=name)


def _closed_form(robot: Robot, poses, t, wrist_margin=0.0) -> np.ndarray:
    """Closed-form tree angles (N, 12) on docs/model.md §9 branches, errors mapped to ours."""
    try:
        # The wrist's numerical floor applies even with margin 0 (docs/model.md §12).
        limit = max(wrist_margin, SERIAL_FLOOR)
        return closed_form.position_ik(robot.params, poses, wrist_margin=limit)[:, :12]
    except closed_form.UnreachableError as exc:
        k, tk = exc.sample, float(t[exc.sample])
        if exc.kind == "singular" and exc.chain == "wrist":
            raise SingularityError(
                floor_message("wrist |sin θ1716| =", exc.ratio, wrist_margin, limit,
                              SERIAL_FLOOR)
                + " (near the wrist singularity: spray axis parallel to the platform arm)",
                sample=k, time=tk, chain="wrist", sigma=exc.ratio,
                amount=limit - exc.ratio) from None
        msg = str(exc).replace(f" at sample {exc.sample}", "")  # the prefix says where
        cls = SingularityError if exc.kind == "singular" else UnreachablePoseError
        raise cls(msg, sample=k, time=tk, chain=exc.chain, amount=exc.shortfall) from None


def inverse_kinematics(robot: Robot, poses, d_poses=None, dd_poses=None, t=None,
                       q_start=None, *, method: str | None = None, progress=None,
                       **options) -> IKResult:
    """Constrained IK with Pinocchio: positions, velocities, accelerations of all 12 tree joints.

    ``method="batch"`` (the default without ``q_start``) stacks the work over samples (see
    :func:`inverse_kinematics_batch`); ``method="newton"`` (the default with ``q_start``)
    solves sample by sample (see :func:`inverse_kinematics_newton`). Both give the same result
    to round-off. ``options``: ``tol``, ``singularity_margin``, ``wrist_margin`` (and
    ``max_iter`` for Newton). Invalid arguments (a negative or NaN margin, empty or non-finite
    poses, times that do not increase) raise :class:`KinematicsInputError`, a ValueError.
    """
    method = method or ("newton" if q_start is not None else "batch")
    if method == "newton":
        return inverse_kinematics_newton(robot, poses, d_poses, dd_poses, t, q_start,
                                         progress=progress, **options)
    if method != "batch":
        raise KinematicsInputError(f"method must be 'batch' or 'newton', got {method!r}")
    if q_start is not None:
        raise KinematicsInputError("q_start applies to method='newton' only")
    return inverse_kinematics_batch(robot, poses, d_poses, dd_poses, t, progress=progress,
                                    **options)


def _start_configuration(robot: Robot, q_start) -> np.ndarray:
    q = np.asarray(q_start, dtype=float).reshape(-1)
    if q.shape != (robot.model.nq,) or not np.isfinite(q).all():
        raise KinematicsInputError(f"q_start must be {robot.model.nq} finite joint angles "
                                   f"({', '.join(robot.joint_names)}), got {q_start!r}",
                                   chain="q_start")
    return q.copy()


def _stop(stats_row, singularity_margin, wrist_margin) -> bool:
    """A margin or numerical floor is crossed at this sample (check_margins names it)."""
    _, _, wrist, sp, ss, sp_max, ss_max = stats_row
    return not (wrist >= max(wrist_margin, SERIAL_FLOOR)
                and sp >= max(singularity_margin, SIGMA_FLOOR * sp_max)
                and ss >= max(singularity_margin, SERIAL_FLOOR * ss_max))


def inverse_kinematics_newton(robot: Robot, poses, d_poses=None, dd_poses=None, t=None,
                              q_start=None, *, tol: float = IK_TOL, max_iter: int = 30,
                              singularity_margin: float = SINGULARITY_MARGIN,
                              wrist_margin: float = WRIST_MARGIN, progress=None) -> IKResult:
    """Sample-by-sample constrained IK.

    Positions: Newton on [closure residual; tool-pose error], warm-started from the previous
    sample (the first from ``q_start``, default the closed form on docs/model.md §9 branches)
    by a second-order Taylor predictor. The solution must keep the previous sample's
    assembly-branch signs (:data:`~.singularity.BRANCH_SIGNS`); when the predictor lands
    elsewhere (sparse samples), the motion is followed by continuation along the straight
    pose segment between the samples, so any sampling density gives the same branch. If even
    the finest continuation step changes a sign, the motion really crosses the boundary of the
    assembly mode: :class:`BranchFlipError`.
    Velocities: ``[Jc; J_tool] v = [0; twist]``. Accelerations: the same matrix with the exact
    drifts from Pinocchio's classical accelerations. Raises a :class:`KinematicsError` subclass
    at the first unreachable, singular or branch-flipping sample.
    """
    _check_options(tol, singularity_margin, wrist_margin, max_iter=max_iter)
    model, data = robot.model, robot.data
    cms, cds = robot.constraint_models, robot.constraint_datas
    fr = KinematicFrames.of(robot)
    poses, d_poses, dd_poses, t = _task_inputs(poses, d_poses, dd_poses, t)
    n = len(poses)
    Rs = rotation(poses)
    tw, twd = twist(poses, d_poses), twist_dot(poses, d_poses, dd_poses)
    nv = model.nv
    out = {k: np.empty((n, nv)) for k in ("q", "v", "a")}
    sph, dsph = np.empty((n, 6)), np.empty((n, 6))
    stats = np.empty((n, 7))
    if q_start is None:  # docs/model.md §9 branches, through the closed form at the first pose
        q = _closed_form(robot, poses[:1], t[:1], wrist_margin)[0]
    else:
        q = _start_configuration(robot, q_start)

    def solve(guess, pose, R=None):
        return _newton(model, data, cms, cds, fr, guess, pose[:3],
                       rotation(pose) if R is None else R, tol, max_iter)

    branch = BranchQuantities(robot)
    rhs_v = np.zeros(12)
    ref = None
    for k in range(n):
        if k == 0:
            q, e, ok = solve(q, poses[0], Rs[0])
            signs = branch.signs_list(q)
        else:  # predictor: second-order Taylor step from the previous sample
            dt = t[k] - t[k - 1]
            q_prev = out["q"][k - 1]
            q = q_prev + dt * out["v"][k - 1] + 0.5 * dt * dt * out["a"][k - 1]
            q, e, ok = solve(q if np.isfinite(q).all() else q_prev, poses[k], Rs[k])
            signs = branch.signs_list(q)
            if not (ok and same_branch(signs, ref)):
                q, e, ok, flip = _follow(solve, branch.signs_list, q_prev, poses[k - 1],
                                         poses[k], ref)
                if flip is not None:
                    s_, q_a, q_b = flip
                    va, vb = branch(q_a), branch(q_b)
                    j = next(i for i, (a_, b_) in enumerate(zip(branch.signs_list(q_b), ref))
                             if a_ * b_ < 0)
                    raise flip_error(k - 1, k, j, float(va[j]), float(vb[j]), t[k],
                                     near=float(t[k - 1] + s_ * dt))
                signs = branch.signs_list(q)
        if not ok:
            raise _diagnose(robot, poses[k], k, t[k], e, wrist_margin)
        # The reference keeps the last non-zero sign (a zero is a boundary: no information).
        ref = signs if ref is None else [s if s else r for s, r in zip(signs, ref)]
        K = _kinematic_matrix(model, data, cms, cds, fr, q)
        stats[k] = (np.abs(e[:6]).max(), np.abs(e[6:]).max(), abs(np.sin(q[fr.wrist_q])),
                    *conditioning(K, fr.actuated_v, fr.passive_v, full=True))
        rhs_v[6:] = tw[k]
        try:
            v = np.linalg.solve(K, rhs_v)
            drift = _drifts(model, data, fr, q, v)
            rhs_a = -drift
            rhs_a[6:] += twd[k]
            a = np.linalg.solve(K, rhs_a)
        except np.linalg.LinAlgError:  # singular K: check_margins names the singularity
            v = a = np.full(nv, np.nan)
            pin.forwardKinematics(model, data, q, np.zeros(nv))
        sph[k], dsph[k] = _spherical(data, fr)
        out["q"][k], out["v"][k], out["a"][k] = q, v, a
        if progress is not None:
            progress(k + 1, n)
        if (_stop(stats[k], singularity_margin, wrist_margin)
                or not math.isfinite(float(v.sum() + a.sum()))):  # NaN or inf anywhere
            n = k + 1  # stop here: the check below raises at the first offending sample
            break
    result = IKResult(t=t[:n], poses=poses[:n], q=out["q"][:n], v=out["v"][:n],
                      a=out["a"][:n], spherical=sph[:n], d_spherical=dsph[:n],
                      closure_residual=stats[:n, 0], tool_error=stats[:n, 1],
                      wrist_margin=stats[:n, 2], sigma_parallel=stats[:n, 3],
                      sigma_serial=stats[:n, 4], joint_names=robot.joint_names,
                      sigma_parallel_max=stats[:n, 5], sigma_serial_max=stats[:n, 6])
    check_margins(robot, result, singularity_margin, wrist_margin)
    return result


# --- batched path ------------------------------------------------------------------------------
# No Python loop over samples: joint placements, Jacobians and their time variation come from
# passes over Pinocchio's model tree stacked over samples (docs/model.md §11), and points,
# residuals, drifts and every 12 × 12 system are stacked over samples in numpy.
_AXES = {"JointModelRX": 0, "JointModelRY": 1, "JointModelRZ": 2}


@dataclass(frozen=True, eq=False)  # hashed by identity: a key for its world position
class _Point:
    """A point fixed in joint ``joint``'s frame (``local``), moved by the v-columns ``cols``."""

    joint: int
    local: np.ndarray
    cols: np.ndarray


@dataclass(frozen=True)
class _Layout:
    closures: tuple[tuple[_Point, _Point], ...]
    tip: _Point
    platform: int
    links: tuple[int, ...]
    spherical_offset: tuple[np.ndarray, ...]  # Rz(−β1413i), docs/model.md §4
    joints: tuple[int, ...]  # every joint whose placement is needed, parents first
    # K's block-triangular partition (closure rows, tool rows, tool-support columns, the
    # others), when the tool is moved by exactly as many joints as it has rows; else None.
    blocks: tuple[np.ndarray, ...] | None = None
    tree: "_TreeArrays | None" = None  # the same, as arrays for the compiled kernels


@dataclass(frozen=True, eq=False)
class _TreeArrays:
    """The layout as flat arrays (slot 0 = the base, then ``joints`` in order) for
    :mod:`.kernels`: placements, K rows of the points, drifts."""

    slot: dict  # joint id → slot
    parent: np.ndarray  # (S,) parent slot
    axis: np.ndarray  # (S,) revolute axis 0/1/2
    idx_q: np.ndarray  # (S,) configuration index
    col: np.ndarray  # (S,) velocity index
    rot: np.ndarray  # (S, 3, 3) joint placement rotation in the parent
    trans: np.ndarray  # (S, 3) joint placement translation in the parent
    pt_slot: np.ndarray  # (P,) points: closure A/B pairs, then the tip
    pt_local: np.ndarray  # (P, 3)
    pt_support: np.ndarray  # (P, depth) slots of the joints moving each point, −1 padded
    pt_row: np.ndarray  # (P,) first row of the point's block of K
    pt_sign: np.ndarray  # (P,) +1 for A and the tip, −1 for B

    @property
    def tool(self) -> tuple[int, int]:
        """The tip (the last point) and the first of the tool's angular rows (after its
        linear ones): K's last three rows."""
        return len(self.pt_slot) - 1, int(self.pt_row[-1]) + 3

    def placements(self, Q: np.ndarray):
        """World rotations (S, N, 3, 3) and origins (S, N, 3) at configurations Q (N, nq)."""
        from .kernels import tree_placements  # compiled on first use (numba)

        Q = np.ascontiguousarray(Q, dtype=float)
        return tree_placements(np.cos(Q), np.sin(Q), self.parent[1:], self.axis[1:],
                               self.idx_q[1:], self.rot[1:], self.trans[1:])


def _tree_arrays(model, joints, points, rows, signs) -> _TreeArrays:
    joints = tuple(joints)
    slot = {0: 0, **{j: i + 1 for i, j in enumerate(joints)}}
    for j in joints:
        if model.joints[j].shortname() not in _AXES:
            raise NotImplementedError(f"batched kinematics: joint {model.names[j]} is a "
                                      f"{model.joints[j].shortname()}, not RX/RY/RZ")
        if slot.get(model.parents[j], len(slot)) > slot[j]:
            raise ValueError(f"batched kinematics: the parent of {model.names[j]} must be "
                             "listed before it")
    every = (0,) + joints
    ints = lambda xs: np.array(xs, dtype=np.int64)  # noqa: E731
    support = [[slot[j] for j in model.supports[p.joint][1:]] for p in points]
    depth = max((len(x) for x in support), default=1)
    return _TreeArrays(
        slot=slot, parent=ints([0] + [slot[model.parents[j]] for j in joints]),
        axis=ints([0] + [_AXES[model.joints[j].shortname()] for j in joints]),
        idx_q=ints([0] + [model.joints[j].idx_q for j in joints]),
        col=ints([0] + [model.joints[j].idx_v for j in joints]),
        rot=np.array([np.eye(3) if j == 0 else model.jointPlacements[j].rotation
                      for j in every]).reshape(-1, 3, 3),
        trans=np.array([np.zeros(3) if j == 0 else model.jointPlacements[j].translation
                        for j in every]).reshape(-1, 3),
        pt_slot=ints([slot[p.joint] for p in points]),
        pt_local=np.array([p.local for p in points]).reshape(-1, 3),
        pt_support=ints([x + [-1] * (depth - len(x)) for x in support]),
        pt_row=ints(rows), pt_sign=np.array(signs, dtype=float))


def _support_cols(model, joint: int) -> np.ndarray:
    return np.array([model.joints[j].idx_v for j in model.supports[joint][1:]])


def _layout(robot: Robot) -> _Layout:
    model = robot.model

    def point(frame_name):
        f = model.frames[robot.frame_id(frame_name)]
        local = np.array(f.placement.translation)
        return _Point(int(f.parentJoint), local, _support_cols(model, f.parentJoint))

    fr = KinematicFrames.of(robot)
    tip = point(TIP_FRAME)
    closures = tuple((point(c.frame_a), point(c.frame_b)) for c in robot.closures)
    ends = {tip.joint, fr.platform_joint, *fr.link_joints,
            *(p.joint for pair in closures for p in pair)}
    joints = sorted({j for e in ends for j in model.supports[e][1:]})
    rows = 3 * len(closures)
    blocks = None
    if len(tip.cols) == 6 and rows + 6 == model.nv:
        others = np.setdiff1d(np.arange(model.nv), tip.cols)
        blocks = (np.arange(rows), np.arange(rows, rows + 6), np.sort(tip.cols), others)
    points = [p for pair in closures for p in pair] + [tip]
    tree = _tree_arrays(model, joints, points,
                        [3 * i for i in range(len(closures)) for _ in range(2)] + [rows],
                        [1.0, -1.0] * len(closures) + [1.0])
    return _Layout(closures, tip, fr.platform_joint, fr.link_joints, fr.spherical_offset,
                   tuple(joints), blocks, tree)


def _inverse(K: np.ndarray, lay: _Layout) -> np.ndarray:
    """K⁻¹ of the stacked [Jc; J_tool] (NaN where singular). The tool rows involve only the
    tool's supporting joints, so K is block-triangular (docs/model.md §11) and two inverses of
    half the size give K⁻¹ (compiled, :func:`.kernels.block_inverse`)."""
    if lay.blocks is None:
        return inverse_stack(K)
    from .kernels import block_inverse  # compiled on first use (numba): keeps start-up fast

    return block_inverse(np.ascontiguousarray(K), *lay.blocks)


def joint_placements(model, Q: np.ndarray, joints) -> dict:
    """World rotation (N, 3, 3) and origin (N, 3) of each listed joint frame at every sample
    (dict by joint, 0 = the base); the parent of each listed joint must be listed before it.
    One compiled pass over the tree (:func:`.kernels.tree_placements`)."""
    tree = _tree_arrays(model, joints, (), (), ())
    R, o = tree.placements(Q)
    return {j: (R[i], o[i]) for j, i in tree.slot.items()}


def joint_velocities(model, pl, joints, V: np.ndarray):
    """Angular velocity ω_j of each listed joint's body and linear velocity ȯ_j of its origin
    (world axes, dicts by joint, 0 = the base) at rates V (N, nv), from the placements ``pl``:
    ȯ_j = ȯ_parent + ω_parent × (o_j − o_parent), ω_j = ω_parent + z_j q̇_j."""
    n = len(pl[0][1])
    w, vo = {0: np.zeros((n, 3))}, {0: np.zeros((n, 3))}
    for j in joints:
        p = model.parents[j]
        R, o = pl[j]
        vo[j] = vo[p] + _cross(w[p], o - pl[p][1])
        w[j] = w[p] + R[:, :, _AXES[model.joints[j].shortname()]] * V[
            :, model.joints[j].idx_v, None]
    return w, vo


def _cross(a, b):
    """Cross product along axis 1 (components), broadcasting the rest; cheaper than np.cross."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[:, 0] = a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1]
    out[:, 1] = a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2]
    out[:, 2] = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    return out


def _matvec(A, x):
    return (A @ x[:, :, None])[:, :, 0]


def _log3(R):
    """Batched SO(3) logarithm (vector), exact away from π."""
    w = 0.5 * np.stack([R[:, 2, 1] - R[:, 1, 2], R[:, 0, 2] - R[:, 2, 0],
                        R[:, 1, 0] - R[:, 0, 1]], axis=1)
    s = np.linalg.norm(w, axis=1)
    c = 0.5 * (np.trace(R, axis1=1, axis2=2) - 1.0)
    th = np.arctan2(s, c)
    scale = np.where(s > 1e-8, th / np.where(s > 1e-8, s, 1.0), 1.0 + s * s / 6.0)
    return w * scale[:, None]


def _residuals(R, pos, lay: _Layout, P_des, R_des) -> np.ndarray:
    """[closure p_A − p_B (6); tip position error (3); orientation error (3)], (N, 12), from
    the placements R and point positions of :func:`_point_rows`."""
    nc = len(lay.closures)
    res = [pos[:, 2 * i] - pos[:, 2 * i + 1] for i in range(nc)]
    R_tip = R[lay.tree.slot[lay.tip.joint]]
    res += [pos[:, 2 * nc] - P_des, _log3(R_tip @ np.swapaxes(R_des, 1, 2))]
    return np.concatenate(res, axis=1)


def _point_rows(lay: _Layout, R, o, nv: int):
    """K = [Jc; J_tool] (N, 12, nv) and the points' positions (N, P, 3): point Jacobians
    z_c × (p − o_c) summed over the joints moving each point, compiled
    (:func:`.kernels.point_jacobians`)."""
    from .kernels import point_jacobians  # compiled on first use (numba)

    t = lay.tree
    return point_jacobians(R, o, t.axis, t.col, t.pt_slot, t.pt_local, t.pt_support, t.pt_row,
                           t.pt_sign, *t.tool, nv)


def _point_drifts(lay: _Layout, R, o, v, pos):
    """K̇ v (N, 12) and every body's angular velocity (S, N, 3), compiled
    (:func:`.kernels.point_drifts`)."""
    from .kernels import point_drifts  # compiled on first use (numba)

    t = lay.tree
    return point_drifts(R, o, t.parent, t.axis, t.col, np.ascontiguousarray(v), t.pt_slot,
                        t.pt_row, t.pt_sign, pos, *t.tool)


BATCH_CHUNK = 4096  # samples per stacked block: bounds memory (≈ 10 kB per sample)
POLISH_TOL = 1e-14  # m / rad: closed-form residual above which the Newton step is applied


def inverse_kinematics_batch(robot: Robot, poses, d_poses=None, dd_poses=None, t=None, *,
                             tol: float = IK_TOL,
                             singularity_margin: float = SINGULARITY_MARGIN,
                             wrist_margin: float = WRIST_MARGIN, progress=None,
                             chunk: int = BATCH_CHUNK, timings: dict | None = None) -> IKResult:
    """Same result as :func:`inverse_kinematics`, stacked over samples.

    Positions start from the closed-form IK of docs/model.md §7 (vectorised) and take one Newton
    step on the [closure residual; tool-pose error]; velocities and accelerations solve the
    ``[Jc; J_tool]`` systems (one K⁻¹ per sample) with drifts from the Jacobians' time
    variation, all evaluated on Pinocchio's model tree stacked over samples (docs/model.md
    §11). The
    closure residual and tool error reported are re-measured at the returned configuration.
    ``timings`` (a dict) accumulates seconds per stage: position (closed form, Jacobians,
    residual), velocity (the stacked solve shared with the Newton step), acceleration,
    analysis (spherical angles, singularity measures, margin checks).

    Every sample is solved on the same assembly branches (the closed form's signs), whatever
    the sampling density. A singular stacked system fails no other sample: its samples get NaN
    and :func:`~.singularity.check_margins` raises :class:`SingularityError` at the first
    singular (or margin-violating) sample, naming its time, chain and σ.
    """
    _check_options(tol, singularity_margin, wrist_margin, chunk=chunk)
    clock = Stopwatch(timings)
    poses, d_poses, dd_poses, t = _task_inputs(poses, d_poses, dd_poses, t)
    n = len(poses)
    q0 = _closed_form(robot, poses, t, wrist_margin)
    clock.lap("position")
    parts = []
    for start in range(0, n, chunk):
        sl = slice(start, min(start + chunk, n))
        parts.append(_batch_block(robot, q0[sl], poses[sl], d_poses[sl], dd_poses[sl], t[sl],
                                  tol, start, clock))
        if progress is not None:
            progress(sl.stop, n)
    if len(parts) == 1:
        result = parts[0]
    else:
        result = IKResult(**{f: (np.concatenate([getattr(p, f) for p in parts])
                                 if f != "joint_names" else parts[0].joint_names)
                             for f in IKResult.__dataclass_fields__})
    check_margins(robot, result, singularity_margin, wrist_margin)
    clock.lap("analysis")
    return result


def _batch_block(robot: Robot, q0, poses, d_poses, dd_poses, t, tol, start, clock) -> IKResult:
    n = len(poses)
    model = robot.model
    lay = _layout(robot)
    P_des, R_des = poses[:, :3], rotation(poses)
    # Newton polish at the closed form; velocities with the same matrix (one stacked solve).
    R, o = lay.tree.placements(q0)
    K, pos = _point_rows(lay, R, o, model.nv)
    rhs = np.zeros((n, 12, 2))
    rhs[:, :, 0] = _residuals(R, pos, lay, P_des, R_des)
    clock.lap("position")
    rhs[:, 6:, 1] = twist(poses, d_poses)
    # One K⁻¹ per sample serves the Newton step, the velocities, the accelerations and the
    # serial conditioning (conditioning(K_inv=...)). NaN where K is singular (checked below).
    K_inv = _inverse(K, lay)
    sol = K_inv @ rhs
    v = sol[:, :, 1]
    # The closed form is exact to round-off: apply the Newton step only where the residual is
    # above POLISH_TOL, and re-evaluate just those samples, so K and the placements below are
    # those of the returned configuration.
    moved = np.flatnonzero((np.abs(rhs[:, :, 0]).max(axis=1) > POLISH_TOL)
                           & np.isfinite(sol[:, :, 0]).all(axis=1))
    q = q0.copy()
    if len(moved):
        q[moved] -= sol[moved, :, 0]
        R_m, o_m = lay.tree.placements(q[moved])
        R[:, moved], o[:, moved] = R_m, o_m
        K[moved], pos[moved] = _point_rows(lay, R_m, o_m, model.nv)
        K_inv[moved] = _inverse(K[moved], lay)
        v[moved] = _matvec(K_inv[moved], rhs[moved, :, 1])
    clock.lap("velocity")
    # Accelerations: K a = [−closure drift; tool acceleration − tool drift].
    singular = ~np.isfinite(v).all(axis=1)
    if singular.any():  # keep NaN out of the drifts; those samples stay NaN
        v = np.where(singular[:, None], 0.0, v)
    drift, omega = _point_drifts(lay, R, o, v, pos)
    rhs_a = -drift
    rhs_a[:, 6:] += twist_dot(poses, d_poses, dd_poses)
    a = _matvec(K_inv, rhs_a)
    if singular.any():
        v[singular] = a[singular] = np.nan
    err = np.abs(_residuals(R, pos, lay, P_des, R_des))
    if not err.max() <= tol:
        k = int(np.argmax(err.max(axis=1)))
        raise UnreachablePoseError(
            f"one Newton step from the closed form left a residual of {err[k].max():.3g} "
            f"(tolerance {tol:g})", sample=start + k, time=float(t[k]),
            amount=float(err[k].max()))
    clock.lap("acceleration")
    sph, dsph = _spherical_batch(lay, R, omega)
    sp, ss, sp_max, ss_max = conditioning(K, robot.actuated_v, robot.passive_v, full=True,
                                          K_inv=K_inv)
    result = IKResult(t=t, poses=poses, q=q, v=v, a=a, spherical=sph, d_spherical=dsph,
                      closure_residual=err[:, :6].max(axis=1), tool_error=err[:, 6:].max(axis=1),
                      wrist_margin=np.abs(np.sin(q[:, robot.idx_q("theta1716")])),
                      sigma_parallel=sp, sigma_serial=ss, sigma_parallel_max=sp_max,
                      sigma_serial_max=ss_max, joint_names=robot.joint_names,
                      constraint_jacobian=K[:, :6])
    clock.lap("analysis")
    return result


def _spherical_batch(lay: _Layout, R, omega):
    """ZYZ angles of R_linkᵀ R_platform Rz(−β1413i) and their rates (docs/model.md §4), (N, 6)
    each, from the placements R and body angular velocities ω (slots first)."""
    slot = lay.tree.slot
    R_p, w_p = R[slot[lay.platform]], omega[slot[lay.platform]]
    ang, rate = [], []
    for link, C in zip(lay.links, lay.spherical_offset):
        R_l = R[slot[link]]
        ang.append(_zyz(np.swapaxes(R_l, 1, 2) @ R_p @ C))
        rate.append(_zyz_rates(ang[-1], _matvec(np.swapaxes(R_l, 1, 2),
                                                w_p - omega[slot[link]])))
    return np.concatenate(ang, axis=1), np.concatenate(rate, axis=1)
