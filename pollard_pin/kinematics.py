"""Constrained kinematics with Pinocchio: closure solve / forward kinematics (spec §4)."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin

from .model import Robot, constraint_jacobian, constraint_residual

CLOSURE_TOL = 1e-12  # m, closure residual reached by Newton
MAX_ITER = 50


class ClosureError(RuntimeError):
    """The loops cannot be closed for the given actuator angles."""

    def __init__(self, message: str, leg: int | None = None, residual: float | None = None):
        super().__init__(message)
        self.leg = leg
        self.residual = residual


def _leg_residuals(r: np.ndarray) -> np.ndarray:
    return np.linalg.norm(r.reshape(2, 3), axis=1)


def solve_closure(robot: Robot, actuated: np.ndarray, q_guess: np.ndarray | None = None,
                  tol: float = CLOSURE_TOL, max_iter: int = MAX_ITER) -> np.ndarray:
    """Full configuration (12,) with the six actuator angles fixed and the loops closed.

    Newton on the passive angles with the constraint Jacobian, warm-started at ``q_guess``
    (default: the home posture). Raises :class:`ClosureError` naming the leg and the residual
    reached when the actuator set cannot be assembled.
    """
    model, data = robot.model, robot.data
    cms, cds = robot.constraint_models, robot.constraint_datas
    act = np.asarray(actuated, dtype=float).reshape(-1)
    if act.shape != (6,) or not np.all(np.isfinite(act)):
        raise ValueError(f"actuator angles must be 6 finite numbers "
                         f"({', '.join(robot.actuated)}), got {act!r}")
    q = (robot.q_reference if q_guess is None else np.asarray(q_guess, dtype=float)).copy()
    ia, ip = robot.actuated_v, robot.passive_v
    q[ia] = act
    r = constraint_residual(model, data, cms, cds, q)
    best = np.inf
    for _ in range(max_iter):
        err = np.abs(r).max()
        best = min(best, err)
        if err <= tol:
            return q
        Jp = constraint_jacobian(model, data, cms, cds, q)[:, ip]
        step = np.linalg.lstsq(Jp, r, rcond=None)[0]
        # Damped step: never move a passive angle by more than 0.5 rad at once.
        scale = min(1.0, 0.5 / max(np.abs(step).max(), 1e-300))
        q_new = q.copy()
        q_new[ip] -= scale * step
        r_new = constraint_residual(model, data, cms, cds, q_new)
        q, r = q_new, r_new
    legs = _leg_residuals(r)
    leg = int(np.argmax(legs)) + 1
    angles = dict(zip(robot.actuated, act.round(6).tolist()))
    raise ClosureError(
        f"cannot close the loops for actuator angles {angles} "
        f"(rad): after {max_iter} Newton steps the residual is {legs[0]*1e3:.4g} mm on leg 1 and "
        f"{legs[1]*1e3:.4g} mm on leg 2 (tolerance {tol:g} m); leg {leg} cannot reach its "
        f"attachment point", leg=leg, residual=float(legs.max()))


def tool_pose(robot: Robot, q: np.ndarray) -> pin.SE3:
    """World placement of the ``tip`` frame."""
    pin.framesForwardKinematics(robot.model, robot.data, q)
    return pin.SE3(robot.data.oMf[robot.tip_frame])


def forward_kinematics(robot: Robot, actuated: np.ndarray, q_guess: np.ndarray | None = None
                       ) -> tuple[np.ndarray, np.ndarray]:
    """Actuator angles (N, 6) → full configurations (N, 12) and task poses (N, 6).

    Each sample warm-starts from the previous one, so a trajectory stays on one branch.
    """
    from .taskspace import pose_from_se3

    act = np.atleast_2d(np.asarray(actuated, dtype=float))
    qs = np.empty((len(act), robot.model.nq))
    poses = np.empty((len(act), 6))
    q = q_guess
    for k, a in enumerate(act):
        try:
            q = solve_closure(robot, a, q_guess=q)
        except ClosureError as exc:
            raise ClosureError(f"sample {k}: {exc}", exc.leg, exc.residual) from None
        qs[k] = q
        poses[k] = pose_from_se3(tool_pose(robot, q))
    return qs, poses


# --- inverse kinematics along a trajectory (issue: constrained kinematics) -------------------
SPHERICAL = ("theta98_1", "theta109_1", "theta1110_1", "theta98_2", "theta109_2", "theta1110_2")
IK_TOL = 1e-12  # m / rad, closure residual and tool-pose error reached by Newton
SINGULARITY_MARGIN = 1e-3  # default smallest singular value allowed (parallel and serial)
WRIST_MARGIN = 0.05  # default smallest |sin θ1716| allowed (≈ 2.9°)
BRANCH_TOL = 0.05  # rad, largest departure from the trapezoid prediction between samples


class KinematicsError(RuntimeError):
    """IK failed at a sample: ``chain``, ``sample``, ``time`` and ``amount`` say where and how far."""

    def __init__(self, message: str, *, sample: int | None = None, time: float | None = None,
                 chain: str | None = None, amount: float | None = None):
        where = "" if sample is None else f"sample {sample}" + (
            "" if time is None else f" (t = {time:.6g} s)")
        super().__init__(f"{where}: {message}" if where else message)
        self.sample, self.time, self.chain, self.amount = sample, time, chain, amount


class UnreachablePoseError(KinematicsError):
    """A chain cannot reach the requested tool pose."""


class SingularityError(KinematicsError):
    """The trajectory passes closer to a singularity than the configured margin."""


class BranchFlipError(KinematicsError):
    """The solution jumped to another assembly branch between consecutive samples."""


def _zyz(M: np.ndarray) -> np.ndarray:
    """ZYZ angles of M = Rz(a) Ry(b) Rz(c), b in [0, π] (spec §4)."""
    b = np.arccos(np.clip(M[2, 2], -1.0, 1.0))
    return np.array([np.arctan2(M[1, 2], M[0, 2]), b, np.arctan2(M[2, 1], -M[2, 0])])


def _zyz_rate_matrix(ang: np.ndarray) -> np.ndarray:
    """w = Z(a, b) · (ȧ, ḃ, ċ) for M = Rz(a) Ry(b) Rz(c), Ṁ Mᵀ = ŵ."""
    a, b = ang[0], ang[1]
    return np.array([[0.0, -np.sin(a), np.cos(a) * np.sin(b)],
                     [0.0, np.cos(a), np.sin(a) * np.sin(b)],
                     [1.0, 0.0, np.cos(b)]])


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
        w_rel = oMl.rotation.T @ (w_p - oMl.rotation @ data.v[jl].angular)
        ang.append(a)
        rate.append(np.linalg.solve(_zyz_rate_matrix(a), w_rel))
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
    from .thesis.ik import UnreachableError, position_ik

    try:
        position_ik(robot.params, np.asarray(pose)[None, :])
    except UnreachableError as exc:
        return UnreachablePoseError(str(exc).replace("sample 0", "this pose"), sample=k, time=tk,
                                    chain=exc.chain, amount=exc.shortfall)
    return UnreachablePoseError(
        f"Newton did not converge to pose {np.round(pose, 6).tolist()}: closure residual "
        f"{np.abs(e[:6]).max():.3g} m, tool error {np.abs(e[6:]).max():.3g} (m/rad)",
        sample=k, time=tk, amount=float(np.abs(e).max()))


def _closed_form_start(robot: Robot, pose, time, wrist_margin=0.0):
    import importlib

    cf = importlib.import_module(".thesis.ik", __package__)
    try:
        return cf.position_ik(robot.params, np.asarray(pose)[None, :],
                              wrist_margin=wrist_margin)[0, :12]
    except cf.UnreachableError as exc:
        cls = SingularityError if exc.kind == "singular" else UnreachablePoseError
        raise cls(str(exc).replace("sample 0", "this pose"), sample=0, time=float(time),
                  chain=exc.chain, amount=exc.shortfall) from None


def inverse_kinematics(robot: Robot, poses, d_poses=None, dd_poses=None, t=None,
                       q_start=None, *, tol: float = IK_TOL, max_iter: int = 30,
                       singularity_margin: float = SINGULARITY_MARGIN,
                       wrist_margin: float = WRIST_MARGIN, branch_tol: float = BRANCH_TOL,
                       progress=None) -> IKResult:
    """Constrained IK with Pinocchio: positions, velocities, accelerations of all 12 tree joints.

    Positions: Newton on [closure residual; tool-pose error], warm-started from the previous
    sample (the first from ``q_start``, default the closed form on the spec §9 branches).
    Velocities: ``[Jc; J_tool] v = [0; twist]``. Accelerations: the same matrix with the exact
    drifts from Pinocchio's classical accelerations. Raises a :class:`KinematicsError` subclass
    at the first unreachable, singular or branch-flipping sample.
    """
    from .taskspace import rotation, twist, twist_dot

    model, data = robot.model, robot.data
    cms, cds = robot.constraint_models, robot.constraint_datas
    fr = KinematicFrames.of(robot)
    poses = np.atleast_2d(np.asarray(poses, dtype=float))
    n = len(poses)
    d_poses = np.zeros_like(poses) if d_poses is None else np.atleast_2d(d_poses)
    dd_poses = np.zeros_like(poses) if dd_poses is None else np.atleast_2d(dd_poses)
    t = np.arange(n, dtype=float) if t is None else np.asarray(t, dtype=float)
    for name, arr in (("pose", poses), ("pose rate", d_poses), ("pose acceleration", dd_poses)):
        bad = np.argwhere(~np.isfinite(arr))
        if len(bad):
            k, c = bad[0]
            raise KinematicsError(f"{name} column {c} is {arr[k, c]}", sample=int(k), time=t[k])
    Rs = rotation(poses)
    tw, twd = twist(poses, d_poses), twist_dot(poses, d_poses, dd_poses)
    nv = model.nv
    out = {k: np.empty((n, nv)) for k in ("q", "v", "a")}
    sph, dsph = np.empty((n, 6)), np.empty((n, 6))
    stats = np.empty((n, 5))
    if q_start is None:  # the spec §9 branches, through the closed form at the first pose
        q = _closed_form_start(robot, poses[0], t[0], wrist_margin)
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
        Jc, Jt = K[:6], K[6:]
        Jp = Jc[:, fr.passive_v]
        fwd = Jt[:, fr.actuated_v] - Jt[:, fr.passive_v] @ np.linalg.solve(
            Jp, Jc[:, fr.actuated_v])  # actuator rates → tool twist
        stats[k] = (np.abs(e[:6]).max(), np.abs(e[6:]).max(), abs(np.sin(q[fr.wrist_q])),
                    np.linalg.svd(Jp, compute_uv=False)[-1],
                    np.linalg.svd(fwd, compute_uv=False)[-1])
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
    _check_margins(robot, result, singularity_margin, wrist_margin, branch_tol)
    return result


# --- batched path (issue: speed) -----------------------------------------------------------
# Per sample only the unavoidable Pinocchio calls run in Python (joint Jacobians, their time
# variation, joint placements); points, residuals, drifts and all 12 × 12 solves are stacked
# over samples in numpy.
@dataclass(frozen=True)
class _Point:
    """A point fixed on joint ``joint`` (local coordinates ``local``), with its support mask."""

    slot: int  # index into the gathered joint placements
    local: np.ndarray
    mask: np.ndarray  # (nv,) 1.0 on the joints that move it


def _batch_layout(robot: Robot):
    model = robot.model
    joints = (robot.joint_id("theta54"), robot.joint_id("theta1817"),
              robot.joint_id("theta76_1"), robot.joint_id("theta76_2"))

    def point(frame_name):
        f = model.frames[robot.frame_id(frame_name)]
        mask = np.zeros(model.nv)
        for j in model.supports[f.parentJoint][1:]:
            mask[model.joints[j].idx_v] = 1.0
        return _Point(joints.index(f.parentJoint), np.array(f.placement.translation), mask)

    pts = [(point(c.frame_a), point(c.frame_b)) for c in robot.closures]
    return joints, pts, point(TIP_FRAME_NAME)


TIP_FRAME_NAME = "tip"


def _gather(robot: Robot, joints, Q, V=None):
    """Stacked world joint Jacobians J (N, 6, nv), dJ if V is given, and placements (N, m, 4, 4)."""
    model, data = robot.model, robot.data
    n = len(Q)
    J = np.empty((n, 6, model.nv))
    dJ = np.empty((n, 6, model.nv)) if V is not None else None
    H = np.empty((n, len(joints), 4, 4))
    oMi = data.oMi
    for k in range(n):
        if V is None:
            pin.computeJointJacobians(model, data, Q[k])
        else:
            pin.computeJointJacobiansTimeVariation(model, data, Q[k], V[k])
            dJ[k] = data.dJ
        J[k] = data.J
        for m, j in enumerate(joints):
            H[k, m] = oMi[j].homogeneous
    return J, dJ, H


def _point_pos(H, p: _Point):
    return H[:, p.slot, :3, :3] @ p.local + H[:, p.slot, :3, 3]


def _point_jac(J, pos, p: _Point):
    """Linear Jacobian (N, 3, nv) of a point at world position pos: J_lin + J_ang × p."""
    Jl, Ja = J[:, :3] * p.mask, J[:, 3:] * p.mask
    return Jl + np.cross(Ja, pos[:, :, None], axisa=1, axisb=1, axisc=1)


def _log3(R):
    """Batched SO(3) logarithm (vector), exact away from π."""
    w = 0.5 * np.stack([R[:, 2, 1] - R[:, 1, 2], R[:, 0, 2] - R[:, 2, 0],
                        R[:, 1, 0] - R[:, 0, 1]], axis=1)
    s = np.linalg.norm(w, axis=1)
    c = 0.5 * (np.trace(R, axis1=1, axis2=2) - 1.0)
    th = np.arctan2(s, c)
    scale = np.where(s > 1e-8, th / np.where(s > 1e-8, s, 1.0), 1.0 + s * s / 6.0)
    return w * scale[:, None]


def _stack_K(J, H, pts, tip):
    """K = [Jc; J_tool] (N, 12, nv) and the world positions of all points."""
    rows, pos = [], {}
    for a, b in pts:
        pa, pb = _point_pos(H, a), _point_pos(H, b)
        rows.append(_point_jac(J, pa, a) - _point_jac(J, pb, b))
        pos[id(a)], pos[id(b)] = pa, pb
    pt = _point_pos(H, tip)
    pos[id(tip)] = pt
    rows += [_point_jac(J, pt, tip), J[:, 3:] * tip.mask]
    return np.concatenate(rows, axis=1), pos


def _residuals(H, pos, pts, tip, P_des, R_des):
    res = [pos[id(a)] - pos[id(b)] for a, b in pts]
    R_tip = H[:, tip.slot, :3, :3]
    res += [pos[id(tip)] - P_des, _log3(R_tip @ np.swapaxes(R_des, 1, 2))]
    return np.concatenate(res, axis=1)


def _point_drift(J, dJ, v, pos, p: _Point):
    """Classical acceleration of a point at a = 0: J̇_lin v + (J̇_ang v) × p + ω × ṗ."""
    Jl, Ja = J[:, :3] * p.mask, J[:, 3:] * p.mask
    dJl, dJa = dJ[:, :3] * p.mask, dJ[:, 3:] * p.mask
    w = np.einsum("nij,nj->ni", Ja, v)
    pdot = np.einsum("nij,nj->ni", Jl, v) + np.cross(w, pos)
    return np.einsum("nij,nj->ni", dJl, v) + np.cross(np.einsum("nij,nj->ni", dJa, v), pos) \
        + np.cross(w, pdot)


def _sigma_min(A):
    return np.linalg.svd(A, compute_uv=False)[:, -1]


def inverse_kinematics_batch(robot: Robot, poses, d_poses=None, dd_poses=None, t=None, *,
                             tol: float = IK_TOL,
                             singularity_margin: float = SINGULARITY_MARGIN,
                             wrist_margin: float = WRIST_MARGIN,
                             branch_tol: float = BRANCH_TOL) -> IKResult:
    """Same result as :func:`inverse_kinematics`, stacked over samples.

    Positions start from the closed-form IK of spec §7 (vectorised) and take one Newton step on
    Pinocchio's [closure residual; tool-pose error]; velocities and accelerations solve Pinocchio's
    ``[Jc; J_tool]`` systems with drifts from ``computeJointJacobiansTimeVariation``. The
    closure residual and tool error reported are re-measured at the returned configuration.
    """
    import importlib

    from .taskspace import rotation, twist, twist_dot

    cf = importlib.import_module(".thesis.ik", __package__)
    poses = np.atleast_2d(np.asarray(poses, dtype=float))
    n = len(poses)
    d_poses = np.zeros_like(poses) if d_poses is None else np.atleast_2d(d_poses)
    dd_poses = np.zeros_like(poses) if dd_poses is None else np.atleast_2d(dd_poses)
    t = np.arange(n, dtype=float) if t is None else np.asarray(t, dtype=float)
    for name, arr in (("pose", poses), ("pose rate", d_poses), ("pose acceleration", dd_poses)):
        bad = np.argwhere(~np.isfinite(arr))
        if len(bad):
            k, c = bad[0]
            raise KinematicsError(f"{name} column {c} is {arr[k, c]}", sample=int(k), time=t[k])
    try:
        q0 = cf.position_ik(robot.params, poses)[:, :12]
    except cf.UnreachableError as exc:
        cls = SingularityError if exc.kind == "singular" else UnreachablePoseError
        raise cls(str(exc), sample=exc.sample, time=float(t[exc.sample]), chain=exc.chain,
                  amount=exc.shortfall) from None
    assert tuple(cf.TREE_JOINTS) == robot.joint_names  # same order, spec §3
    joints, pts, tip = _batch_layout(robot)
    P_des, R_des = poses[:, :3], rotation(poses)
    # Newton polish at the closed form, and velocities with the same factorisation.
    J, _, H = _gather(robot, joints, q0)
    K, pos = _stack_K(J, H, pts, tip)
    rhs = np.zeros((n, 12, 2))
    rhs[:, :, 0] = _residuals(H, pos, pts, tip, P_des, R_des)
    rhs[:, 6:, 1] = twist(poses, d_poses)
    sol = np.linalg.solve(K, rhs)
    q = q0 - sol[:, :, 0]
    v = sol[:, :, 1]
    # Accelerations: K a = [−closure drift; tool acceleration − tool drift], at the final q.
    J, dJ, H = _gather(robot, joints, q, v)
    K, pos = _stack_K(J, H, pts, tip)
    drift = [_point_drift(J, dJ, v, pos[id(a)], a) - _point_drift(J, dJ, v, pos[id(b)], b)
             for a, b in pts]
    drift.append(_point_drift(J, dJ, v, pos[id(tip)], tip))
    drift.append(np.einsum("nij,nj->ni", dJ[:, 3:] * tip.mask, v))
    rhs_a = twist_dot(poses, d_poses, dd_poses)
    rhs_a = np.concatenate([np.zeros((n, 6)), rhs_a], axis=1) - np.concatenate(drift, axis=1)
    a = np.linalg.solve(K, rhs_a[:, :, None])[:, :, 0]
    err = np.abs(_residuals(H, pos, pts, tip, P_des, R_des))
    if err.max() > tol:
        k = int(np.argmax(err.max(axis=1)))
        raise UnreachablePoseError(
            f"one Newton step from the closed form left a residual of {err[k].max():.3g} "
            f"(tolerance {tol:g})", sample=k, time=float(t[k]), amount=float(err[k].max()))
    # Spherical-joint angles and rates (spec §4) and singularity measures.
    sph, dsph = _spherical_batch(robot, H, J, v)
    ia, ip = robot.actuated_v, robot.passive_v
    Jc, Jt = K[:, :6], K[:, 6:]
    Jp = Jc[:, :, ip]
    N_p = -np.linalg.solve(Jp, Jc[:, :, ia])
    fwd = Jt[:, :, ia] + Jt[:, :, ip] @ N_p  # actuator rates → tool twist
    result = IKResult(t=t, poses=poses, q=q, v=v, a=a, spherical=sph, d_spherical=dsph,
                      closure_residual=err[:, :6].max(axis=1), tool_error=err[:, 6:].max(axis=1),
                      wrist_margin=np.abs(np.sin(q[:, robot.idx_q("theta1716")])),
                      sigma_parallel=_sigma_min(Jp), sigma_serial=_sigma_min(fwd),
                      joint_names=robot.joint_names)
    result.constraint_jacobian = Jc.copy()
    _check_margins(robot, result, singularity_margin, wrist_margin, branch_tol)
    return result


def _spherical_batch(robot: Robot, H, J, v):
    """ZYZ angles of R_linkᵀ R_platform Rz(−β1413i) and their rates, stacked (N, 6)."""
    R_p = H[:, 0, :3, :3]
    w_p = np.einsum("nij,nj->ni", J[:, 3:] * _support_mask(robot, "theta54"), v)
    ang, rate = [], []
    for i, leg in enumerate(robot.params.legs, start=1):
        R_l = H[:, 1 + i, :3, :3]
        c, s = np.cos(-leg.beta1413), np.sin(-leg.beta1413)
        C = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        M = np.swapaxes(R_l, 1, 2) @ R_p @ C
        b = np.arccos(np.clip(M[:, 2, 2], -1.0, 1.0))
        a_ = np.arctan2(M[:, 1, 2], M[:, 0, 2])
        c_ = np.arctan2(M[:, 2, 1], -M[:, 2, 0])
        w_l = np.einsum("nij,nj->ni", J[:, 3:] * _support_mask(robot, f"theta76_{i}"), v)
        w_rel = np.einsum("nji,nj->ni", R_l, w_p - w_l)
        Z = np.zeros((len(b), 3, 3))
        Z[:, 0, 1], Z[:, 0, 2] = -np.sin(a_), np.cos(a_) * np.sin(b)
        Z[:, 1, 1], Z[:, 1, 2] = np.cos(a_), np.sin(a_) * np.sin(b)
        Z[:, 2, 0], Z[:, 2, 2] = 1.0, np.cos(b)
        ang.append(np.stack([a_, b, c_], axis=1))
        rate.append(np.linalg.solve(Z, w_rel[:, :, None])[:, :, 0])
    return np.concatenate(ang, axis=1), np.concatenate(rate, axis=1)


def _support_mask(robot: Robot, joint: str) -> np.ndarray:
    model = robot.model
    mask = np.zeros(model.nv)
    for j in model.supports[robot.joint_id(joint)][1:]:
        mask[model.joints[j].idx_v] = 1.0
    return mask


def _check_margins(robot: Robot, r: IKResult, singularity_margin, wrist_margin, branch_tol):
    """Raise at the first sample closer to a singularity than the margins, or a branch flip."""
    checks = [(r.wrist_margin, wrist_margin, "wrist", SingularityError,
               "wrist |sin θ1716| = {v:.4g} is below the margin {m:g} (spray axis nearly "
               "parallel to the platform arm)"),
              (r.sigma_parallel, singularity_margin, "parallel", SingularityError,
               "parallel (passive-joint constraint Jacobian) smallest singular value {v:.4g} "
               "is below the margin {m:g}"),
              (r.sigma_serial, singularity_margin, "serial", SingularityError,
               "serial (actuator-rate to tool-twist map) smallest singular value {v:.4g} is "
               "below the margin {m:g}")]
    first = None
    for values, margin, chain, cls, msg in checks:
        bad = np.flatnonzero(values < margin)
        if len(bad) and (first is None or bad[0] < first[0]):
            k = int(bad[0])
            first = (k, cls(msg.format(v=values[k], m=margin), sample=k, time=float(r.t[k]),
                            chain=chain, amount=float(margin - values[k])))
    if len(r) > 1:
        dt = np.diff(r.t)[:, None]
        jump = np.abs(np.diff(r.q, axis=0) - 0.5 * dt * (r.v[1:] + r.v[:-1]))
        bad = np.flatnonzero(jump.max(axis=1) > branch_tol)
        if len(bad) and (first is None or bad[0] + 1 < first[0]):
            k = int(bad[0]) + 1
            j = int(np.argmax(jump[k - 1]))
            name = robot.joint_names[j]
            first = (k, BranchFlipError(
                f"joint {name} jumped {jump[k - 1, j]:.4g} rad more than its rate predicts "
                f"(limit {branch_tol:g} rad): assembly branch flip or samples too sparse",
                sample=k, time=float(r.t[k]), chain=name, amount=float(jump[k - 1, j])))
    if first is not None:
        raise first[1]
