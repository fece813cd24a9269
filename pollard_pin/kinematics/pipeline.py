"""Constrained inverse kinematics along a trajectory (docs/model.md §7, §11): positions,
velocities and accelerations of all tree joints from the tool pose, batched or per sample."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin

from ..model.build import TIP_FRAME, Robot, constraint_jacobian
from ..timing import Stopwatch
from . import closed_form
from .errors import KinematicsError, SingularityError, UnreachablePoseError
from .singularity import (BRANCH_TOL, SINGULARITY_MARGIN, WRIST_MARGIN, check_margins,
                          conditioning)
from .taskspace import rotation, twist, twist_dot

SPHERICAL = ("theta98_1", "theta109_1", "theta1110_1", "theta98_2", "theta109_2", "theta1110_2")
IK_TOL = 1e-12  # m / rad, closure residual and tool-pose error reached by Newton


def _zyz(M: np.ndarray) -> np.ndarray:
    """ZYZ angles (..., 3) of M = Rz(a) Ry(b) Rz(c) (..., 3, 3), b in [0, π] (docs/model.md §4)."""
    b = np.arccos(np.clip(M[..., 2, 2], -1.0, 1.0))
    return np.stack([np.arctan2(M[..., 1, 2], M[..., 0, 2]), b,
                     np.arctan2(M[..., 2, 1], -M[..., 2, 0])], axis=-1)


def _zyz_rates(ang: np.ndarray, w: np.ndarray) -> np.ndarray:
    """(ȧ, ḃ, ċ) from w, where Ṁ Mᵀ = ŵ and w = ȧ e_z + ḃ Rz(a) e_y + ċ Rz(a)Ry(b) e_z."""
    a, b = ang[..., 0], ang[..., 1]
    Z = np.zeros(ang.shape[:-1] + (3, 3))
    Z[..., 0, 1], Z[..., 0, 2] = -np.sin(a), np.cos(a) * np.sin(b)
    Z[..., 1, 1], Z[..., 1, 2] = np.cos(a), np.sin(a) * np.sin(b)
    Z[..., 2, 0], Z[..., 2, 2] = 1.0, np.cos(b)
    return np.linalg.solve(Z, w[..., None])[..., 0]


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
        step = np.linalg.solve(K, e)
        q = q - step * min(1.0, 0.5 / max(np.abs(step).max(), 1e-300))
        e = _pose_error(model, data, fr, q, p_des, R_des)
    return q, e, np.abs(e).max() <= tol


def _diagnose(robot: Robot, pose, k, tk, e, wrist_margin):
    """Why Newton failed at sample k: the closed form names the chain and the shortfall."""
    try:
        _closed_form(robot, np.asarray(pose)[None, :], np.array([tk]), wrist_margin)
    except KinematicsError as exc:
        return type(exc)(exc.detail, sample=k, time=tk, chain=exc.chain, amount=exc.amount)
    return UnreachablePoseError(
        f"Newton did not converge to pose {np.round(pose, 6).tolist()}: closure residual "
        f"{np.abs(e[:6]).max():.3g} m, tool error {np.abs(e[6:]).max():.3g} (m/rad)",
        sample=k, time=tk, amount=float(np.abs(e).max()))


def _task_inputs(poses, d_poses, dd_poses, t):
    """Validated (N, 6) poses, rates, accelerations (zeros when None) and times (N,)."""
    poses = np.atleast_2d(np.asarray(poses, dtype=float))
    n = len(poses)
    t = np.arange(n, dtype=float) if t is None else np.asarray(t, dtype=float).reshape(-1)
    arrays = [poses]
    for arr in (d_poses, dd_poses):
        arrays.append(np.zeros_like(poses) if arr is None
                      else np.atleast_2d(np.asarray(arr, dtype=float)))
    names = ("pose", "pose rate", "pose acceleration")
    for name, arr in zip(names, arrays):
        if arr.shape != (n, 6):
            raise KinematicsError(f"{name} array has shape {arr.shape}, expected ({n}, 6) "
                                  "(x, y, z, psi, theta, phi per sample)")
    if t.shape != (n,):
        raise KinematicsError(f"times have shape {t.shape}, expected ({n},)")
    for name, arr in zip(names, arrays):
        bad = np.argwhere(~np.isfinite(arr))
        if len(bad):
            k, c = bad[0]
            raise KinematicsError(f"{name} column {c} is {arr[k, c]}", sample=int(k), time=t[k])
    return (*arrays, t)


def _closed_form(robot: Robot, poses, t, wrist_margin=0.0) -> np.ndarray:
    """Closed-form tree angles (N, 12) on docs/model.md §9 branches, errors mapped to ours."""
    try:
        return closed_form.position_ik(robot.params, poses, wrist_margin=wrist_margin)[:, :12]
    except closed_form.UnreachableError as exc:
        k, tk = exc.sample, float(t[exc.sample])
        if exc.kind == "singular":
            raise SingularityError(
                f"wrist |sin θ1716| = {exc.ratio:.4g} is below the margin {wrist_margin:g} "
                "(near the wrist singularity: spray axis parallel to the platform arm)",
                sample=k, time=tk, chain="wrist",
                amount=wrist_margin - exc.ratio) from None
        msg = str(exc) if len(poses) > 1 else str(exc).replace(" at sample 0", "")
        raise UnreachablePoseError(msg, sample=k, time=tk, chain=exc.chain,
                                   amount=exc.shortfall) from None


def inverse_kinematics(robot: Robot, poses, d_poses=None, dd_poses=None, t=None,
                       q_start=None, *, method: str | None = None, progress=None,
                       **options) -> IKResult:
    """Constrained IK with Pinocchio: positions, velocities, accelerations of all 12 tree joints.

    ``method="batch"`` (the default without ``q_start``) stacks the work over samples (see
    :func:`inverse_kinematics_batch`); ``method="newton"`` (the default with ``q_start``)
    solves sample by sample (see :func:`inverse_kinematics_newton`). Both give the same result
    to round-off. ``options``: ``tol``, ``singularity_margin``, ``wrist_margin``, ``branch_tol``.
    """
    method = method or ("newton" if q_start is not None else "batch")
    if method == "newton":
        return inverse_kinematics_newton(robot, poses, d_poses, dd_poses, t, q_start,
                                         progress=progress, **options)
    if method != "batch":
        raise ValueError(f"method must be 'batch' or 'newton', got {method!r}")
    if q_start is not None:
        raise ValueError("q_start applies to method='newton' only")
    return inverse_kinematics_batch(robot, poses, d_poses, dd_poses, t, progress=progress,
                                    **options)


def inverse_kinematics_newton(robot: Robot, poses, d_poses=None, dd_poses=None, t=None,
                              q_start=None, *, tol: float = IK_TOL, max_iter: int = 30,
                              singularity_margin: float = SINGULARITY_MARGIN,
                              wrist_margin: float = WRIST_MARGIN, branch_tol: float = BRANCH_TOL,
                              progress=None) -> IKResult:
    """Sample-by-sample constrained IK.

    Positions: Newton on [closure residual; tool-pose error], warm-started from the previous
    sample (the first from ``q_start``, default the closed form on docs/model.md §9 branches).
    Velocities: ``[Jc; J_tool] v = [0; twist]``. Accelerations: the same matrix with the exact
    drifts from Pinocchio's classical accelerations. Raises a :class:`KinematicsError` subclass
    at the first unreachable, singular or branch-flipping sample.
    """
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
    stats = np.empty((n, 5))
    if q_start is None:  # docs/model.md §9 branches, through the closed form at the first pose
        q = _closed_form(robot, poses[:1], t[:1], wrist_margin)[0]
    else:
        q = np.asarray(q_start, dtype=float).copy()
    rhs_v = np.zeros(12)
    for k in range(n):
        if k > 0:  # predictor: second-order Taylor step from the previous sample
            dt = t[k] - t[k - 1]
            q = out["q"][k - 1] + dt * out["v"][k - 1] + 0.5 * dt * dt * out["a"][k - 1]
        q, e, ok = _newton(model, data, cms, cds, fr, q, poses[k, :3], Rs[k], tol, max_iter)
        if not ok:
            raise _diagnose(robot, poses[k], k, t[k], e, wrist_margin)
        K = _kinematic_matrix(model, data, cms, cds, fr, q)
        rhs_v[6:] = tw[k]
        v = np.linalg.solve(K, rhs_v)
        drift = _drifts(model, data, fr, q, v)
        rhs_a = -drift
        rhs_a[6:] += twd[k]
        a = np.linalg.solve(K, rhs_a)
        sph[k], dsph[k] = _spherical(data, fr)
        stats[k] = (np.abs(e[:6]).max(), np.abs(e[6:]).max(), abs(np.sin(q[fr.wrist_q])),
                    *conditioning(K, fr.actuated_v, fr.passive_v))
        out["q"][k], out["v"][k], out["a"][k] = q, v, a
        if progress is not None:
            progress(k + 1, n)
        if stats[k, 2] < wrist_margin or stats[k, 3:].min() < singularity_margin:
            n = k + 1  # stop here: the check below raises at the first offending sample
            break
    result = IKResult(t=t[:n], poses=poses[:n], q=out["q"][:n], v=out["v"][:n],
                      a=out["a"][:n], spherical=sph[:n], d_spherical=dsph[:n],
                      closure_residual=stats[:n, 0], tool_error=stats[:n, 1],
                      wrist_margin=stats[:n, 2], sigma_parallel=stats[:n, 3],
                      sigma_serial=stats[:n, 4], joint_names=robot.joint_names)
    check_margins(robot, result, singularity_margin, wrist_margin, branch_tol)
    return result


# --- batched path (issue: speed) -----------------------------------------------------------
# Per sample only the Pinocchio Jacobian calls run in Python; joint placements come from one
# forward pass over Pinocchio's model tree stacked over samples, and points, residuals,
# drifts and every 12 × 12 solve are stacked over samples in numpy.
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
    return _Layout(closures, tip, fr.platform_joint, fr.link_joints, fr.spherical_offset,
                   tuple(joints))


def _placements(model, Q: np.ndarray, joints) -> dict:
    """World rotation (N, 3, 3) and origin (N, 3) of each listed joint frame at every sample."""
    n = len(Q)
    out = {0: (np.broadcast_to(np.eye(3), (n, 3, 3)), np.zeros((n, 3)))}
    for j in joints:
        axis = _AXES.get(model.joints[j].shortname())
        if axis is None:
            raise NotImplementedError(f"batched kinematics: joint {model.names[j]} is a "
                                      f"{model.joints[j].shortname()}, not RX/RY/RZ")
        Rp, op = out[model.parents[j]]
        M = model.jointPlacements[j]
        B = Rp if np.array_equal(M.rotation, np.eye(3)) else Rp @ M.rotation
        qj = Q[:, model.joints[j].idx_q, None]
        c, s = np.cos(qj), np.sin(qj)
        i1, i2 = (axis + 1) % 3, (axis + 2) % 3
        R = np.empty((n, 3, 3))  # B · R_axis(q) by mixing two columns
        R[:, :, axis] = B[:, :, axis]
        R[:, :, i1] = B[:, :, i1] * c + B[:, :, i2] * s
        R[:, :, i2] = B[:, :, i2] * c - B[:, :, i1] * s
        out[j] = (R, op + Rp @ M.translation)
    return out


def _jacobians(robot: Robot, Q: np.ndarray, V: np.ndarray | None = None):
    """Stacked world joint Jacobians J (N, 6, nv) — or, if V is given, only their time
    variation dJ (J at the same q is the caller's already)."""
    model, data = robot.model, robot.data
    n = len(Q)
    J = np.empty((n, 6, model.nv))
    if V is None:
        jac = pin.computeJointJacobians
        for k in range(n):
            J[k] = jac(model, data, Q[k])
        return J, None
    dJ = np.empty_like(J)
    jac_dot = pin.computeJointJacobiansTimeVariation
    for k in range(n):
        jac_dot(model, data, Q[k], V[k])
        dJ[k] = data.dJ
    return None, dJ


def _position(pl, p: _Point) -> np.ndarray:
    R, o = pl[p.joint]
    return R @ p.local + o


def _cross(a, b):
    """Cross product along axis 1 (components), broadcasting the rest; cheaper than np.cross."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[:, 0] = a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1]
    out[:, 1] = a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2]
    out[:, 2] = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    return out


def _matvec(A, x):
    return (A @ x[:, :, None])[:, :, 0]


def _stack_K(J, pos, lay: _Layout) -> np.ndarray:
    """K = [Jc; J_tool] (N, 12, nv): point Jacobians J_lin + J_ang × p on their support."""
    n, _, nv = J.shape
    K = np.zeros((n, 12, nv))

    def add(rows, p: _Point, sign):
        c = p.cols
        jp = J[:, :3][:, :, c] + _cross(J[:, 3:][:, :, c], pos[p][:, :, None])
        K[:, rows.start:rows.stop, c] += sign * jp

    for i, (a, b) in enumerate(lay.closures):
        add(slice(3 * i, 3 * i + 3), a, 1.0)
        add(slice(3 * i, 3 * i + 3), b, -1.0)
    add(slice(6, 9), lay.tip, 1.0)
    K[:, 9:, lay.tip.cols] = J[:, 3:][:, :, lay.tip.cols]
    return K


def _log3(R):
    """Batched SO(3) logarithm (vector), exact away from π."""
    w = 0.5 * np.stack([R[:, 2, 1] - R[:, 1, 2], R[:, 0, 2] - R[:, 2, 0],
                        R[:, 1, 0] - R[:, 0, 1]], axis=1)
    s = np.linalg.norm(w, axis=1)
    c = 0.5 * (np.trace(R, axis1=1, axis2=2) - 1.0)
    th = np.arctan2(s, c)
    scale = np.where(s > 1e-8, th / np.where(s > 1e-8, s, 1.0), 1.0 + s * s / 6.0)
    return w * scale[:, None]


def _residuals(pl, pos, lay: _Layout, P_des, R_des) -> np.ndarray:
    """[closure p_A − p_B (6); tip position error (3); orientation error (3)], (N, 12)."""
    res = [pos[a] - pos[b] for a, b in lay.closures]
    R_tip = pl[lay.tip.joint][0]
    res += [pos[lay.tip] - P_des, _log3(R_tip @ np.swapaxes(R_des, 1, 2))]
    return np.concatenate(res, axis=1)


def _drift(J, dJ, v, pos, p: _Point) -> np.ndarray:
    """Classical acceleration of a point at a = 0: J̇_lin v + (J̇_ang v) × p + ω × ṗ."""
    c = p.cols
    vc = v[:, c]
    w = _matvec(J[:, 3:][:, :, c], vc)
    pdot = _matvec(J[:, :3][:, :, c], vc) + _cross(w, pos[p])
    return (_matvec(dJ[:, :3][:, :, c], vc) + _cross(_matvec(dJ[:, 3:][:, :, c], vc), pos[p])
            + _cross(w, pdot))


BATCH_CHUNK = 4096  # samples per stacked block: bounds memory (≈ 10 kB per sample)
POLISH_TOL = 1e-14  # m / rad: closed-form residual above which the Newton step is applied


def inverse_kinematics_batch(robot: Robot, poses, d_poses=None, dd_poses=None, t=None, *,
                             tol: float = IK_TOL,
                             singularity_margin: float = SINGULARITY_MARGIN,
                             wrist_margin: float = WRIST_MARGIN,
                             branch_tol: float = BRANCH_TOL, progress=None,
                             chunk: int = BATCH_CHUNK, timings: dict | None = None) -> IKResult:
    """Same result as :func:`inverse_kinematics`, stacked over samples.

    Positions start from the closed-form IK of docs/model.md §7 (vectorised) and take one Newton
    step on
    Pinocchio's [closure residual; tool-pose error]; velocities and accelerations solve Pinocchio's
    ``[Jc; J_tool]`` systems with drifts from ``computeJointJacobiansTimeVariation``. The
    closure residual and tool error reported are re-measured at the returned configuration.
    ``timings`` (a dict) accumulates seconds per stage: position (closed form, Jacobians,
    residual), velocity (the stacked solve shared with the Newton step), acceleration,
    analysis (spherical angles, singularity measures, margin checks).
    """
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
    check_margins(robot, result, singularity_margin, wrist_margin, branch_tol)
    clock.lap("analysis")
    return result


def _batch_block(robot: Robot, q0, poses, d_poses, dd_poses, t, tol, start, clock) -> IKResult:
    n = len(poses)
    model = robot.model
    lay = _layout(robot)
    points = [p for pair in lay.closures for p in pair] + [lay.tip]
    P_des, R_des = poses[:, :3], rotation(poses)
    # Newton polish at the closed form; velocities with the same matrix (one stacked solve).
    pl = _placements(model, q0, lay.joints)
    pos = {p: _position(pl, p) for p in points}
    J, _ = _jacobians(robot, q0)
    rhs = np.zeros((n, 12, 2))
    rhs[:, :, 0] = _residuals(pl, pos, lay, P_des, R_des)
    K = _stack_K(J, pos, lay)
    clock.lap("position")
    rhs[:, 6:, 1] = twist(poses, d_poses)
    sol = np.linalg.solve(K, rhs)
    v = sol[:, :, 1]
    # The closed form is exact to round-off: apply the Newton step only where the residual is
    # above POLISH_TOL, and re-evaluate just those samples, so K and the placements below are
    # those of the returned configuration.
    moved = np.flatnonzero(np.abs(rhs[:, :, 0]).max(axis=1) > POLISH_TOL)
    q = q0.copy()
    if len(moved):
        q[moved] -= sol[moved, :, 0]
        pl_m = _placements(model, q[moved], lay.joints)
        for j in pl:
            if j:
                pl[j][0][moved], pl[j][1][moved] = pl_m[j]
        for p in points:
            pos[p][moved] = _position(pl_m, p)
        J[moved] = _jacobians(robot, q[moved])[0]
        K[moved] = _stack_K(J[moved], {p: pos[p][moved] for p in points}, lay)
        v[moved] = np.linalg.solve(K[moved], rhs[moved, :, 1:])[:, :, 0]
    clock.lap("velocity")
    # Accelerations: K a = [−closure drift; tool acceleration − tool drift].
    _, dJ = _jacobians(robot, q, v)
    rhs_a = np.empty((n, 12))
    for i, (a_, b_) in enumerate(lay.closures):
        rhs_a[:, 3 * i:3 * i + 3] = _drift(J, dJ, v, pos, b_) - _drift(J, dJ, v, pos, a_)
    tc = lay.tip.cols
    rhs_a[:, 6:] = twist_dot(poses, d_poses, dd_poses)
    rhs_a[:, 6:9] -= _drift(J, dJ, v, pos, lay.tip)
    rhs_a[:, 9:] -= _matvec(dJ[:, 3:][:, :, tc], v[:, tc])
    a = np.linalg.solve(K, rhs_a[:, :, None])[:, :, 0]
    err = np.abs(_residuals(pl, pos, lay, P_des, R_des))
    if err.max() > tol:
        k = int(np.argmax(err.max(axis=1)))
        raise UnreachablePoseError(
            f"one Newton step from the closed form left a residual of {err[k].max():.3g} "
            f"(tolerance {tol:g})", sample=start + k, time=float(t[k]),
            amount=float(err[k].max()))
    clock.lap("acceleration")
    sph, dsph = _spherical_batch(robot, lay, pl, J, v)
    sigma_parallel, sigma_serial = conditioning(K, robot.actuated_v, robot.passive_v)
    result = IKResult(t=t, poses=poses, q=q, v=v, a=a, spherical=sph, d_spherical=dsph,
                      closure_residual=err[:, :6].max(axis=1), tool_error=err[:, 6:].max(axis=1),
                      wrist_margin=np.abs(np.sin(q[:, robot.idx_q("theta1716")])),
                      sigma_parallel=sigma_parallel, sigma_serial=sigma_serial,
                      joint_names=robot.joint_names, constraint_jacobian=K[:, :6])
    clock.lap("analysis")
    return result


def _spherical_batch(robot: Robot, lay: _Layout, pl, J, v):
    """ZYZ angles of R_linkᵀ R_platform Rz(−β1413i) and their rates (docs/model.md §4), (N, 6)
    each."""
    model = robot.model

    def omega(joint):
        c = _support_cols(model, joint)
        return _matvec(J[:, 3:][:, :, c], v[:, c])

    R_p, w_p = pl[lay.platform][0], omega(lay.platform)
    ang, rate = [], []
    for link, C in zip(lay.links, lay.spherical_offset):
        R_l = pl[link][0]
        ang.append(_zyz(np.swapaxes(R_l, 1, 2) @ R_p @ C))
        rate.append(_zyz_rates(ang[-1], _matvec(np.swapaxes(R_l, 1, 2), w_p - omega(link))))
    return np.concatenate(ang, axis=1), np.concatenate(rate, axis=1)
