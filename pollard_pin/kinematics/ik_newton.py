"""Sample-by-sample constrained IK with Pinocchio's own frame Jacobians and classical
accelerations (docs/model.md §7, §11): Newton with continuation on the assembly branch."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from ..analytic.taskspace import rotation, twist, twist_dot
from ..checks import float_array
from ..model.build import Robot, constraint_jacobian
from .errors import KinematicsError, KinematicsInputError, SingularityError, UnreachablePoseError
from .ik_common import (
    IkOptions,
    IKResult,
    KinematicFrames,
    closed_form_angles,
    ik_options,
    task_inputs,
    zyz,
    zyz_rates,
)
from .margins import Margins
from .singularity import (
    BranchQuantities,
    check_margins,
    conditioning,
    flip_error,
    same_branch,
)


def pose_error(model, data, fr: KinematicFrames, q, p_des, R_des):
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


def kinematic_matrix(model, data, cms, cds, fr: KinematicFrames, q):
    """K = [Jc; J_tool] (12 × 12), world axes: K v = [closure velocity; tool twist]."""
    Jc = constraint_jacobian(model, data, cms, cds, q)
    Jt = pin.getFrameJacobian(model, data, fr.tip, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    return np.vstack([Jc, Jt])


def frame_drifts(model, data, fr: KinematicFrames, q, v):
    """[closure acceleration drift; tool drift] at a = 0: K̇ v from classical accelerations."""
    pin.forwardKinematics(model, data, q, v, np.zeros(model.nv))
    LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
    out = [pin.getFrameClassicalAcceleration(model, data, a, LWA).linear
           - pin.getFrameClassicalAcceleration(model, data, b, LWA).linear
           for a, b in zip(fr.closure_a, fr.closure_b)]
    acc = pin.getFrameClassicalAcceleration(model, data, fr.tip, LWA)
    out += [acc.linear, acc.angular]
    return np.concatenate(out)


def spherical_angles(data, fr: KinematicFrames):
    """Cut spherical-joint angles (6,) and rates (6,) after forwardKinematics(q, v)."""
    oMp = data.oMi[fr.platform_joint]
    w_p = oMp.rotation @ data.v[fr.platform_joint].angular
    ang, rate = [], []
    for jl, C in zip(fr.link_joints, fr.spherical_offset):
        oMl = data.oMi[jl]
        a = zyz(oMl.rotation.T @ oMp.rotation @ C)
        ang.append(a)
        rate.append(zyz_rates(a, oMl.rotation.T @ (w_p - oMl.rotation @ data.v[jl].angular)))
    return np.concatenate(ang), np.concatenate(rate)


@dataclass(frozen=True)
class _Kinematics:
    """The model, data, constraints and frame ids the per-sample solver works on."""

    model: object
    data: object
    cms: object
    cds: object
    fr: KinematicFrames

    @classmethod
    def of(cls, robot: Robot) -> _Kinematics:
        return cls(robot.model, robot.data, robot.constraint_models, robot.constraint_datas,
                   KinematicFrames.of(robot))


def _newton(kin: _Kinematics, q, p_des, R_des, tol, max_iter):
    model, data, cms, cds, fr = kin.model, kin.data, kin.cms, kin.cds, kin.fr
    e = pose_error(model, data, fr, q, p_des, R_des)
    polished = False
    for _ in range(max_iter):
        if np.abs(e).max() <= tol:
            if polished:
                return q, e, True
            polished = True  # one more step past tol: quadratic convergence to round-off
        K = kinematic_matrix(model, data, cms, cds, fr, q)
        try:
            step = np.linalg.solve(K, e)
        except np.linalg.LinAlgError:  # exactly singular K on the way: least-squares step
            step = np.linalg.lstsq(K, e, rcond=None)[0]
        q = q - step * min(1.0, 0.5 / max(np.abs(step).max(), 1e-300))
        e = pose_error(model, data, fr, q, p_des, R_des)
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


def _diagnose(robot: Robot, pose, k, tk, e, margins: Margins):
    """Why Newton failed at sample k: the closed form names the chain and the shortfall."""
    try:
        closed_form_angles(robot, np.asarray(pose)[None, :], np.array([tk]), margins)
    except KinematicsError as exc:
        extra = {"sigma": exc.sigma} if isinstance(exc, SingularityError) else {}
        return type(exc)(exc.detail, sample=k, time=tk, chain=exc.chain, amount=exc.amount,
                         **extra)
    return UnreachablePoseError(
        f"Newton did not converge to pose {np.round(pose, 6).tolist()}: closure residual "
        f"{np.abs(e[:6]).max():.3g} m, tool error {np.abs(e[6:]).max():.3g} (m/rad)",
        sample=k, time=tk, amount=float(np.abs(e).max()))


def _start_configuration(robot: Robot, q_start) -> np.ndarray:
    q = float_array(q_start, "q_start", error=KinematicsInputError).reshape(-1)
    if q.shape != (robot.model.nq,) or not np.isfinite(q).all():
        raise KinematicsInputError(f"q_start must be {robot.model.nq} finite joint angles "
                                   f"({', '.join(robot.joint_names)}), got {q_start!r}",
                                   chain="q_start")
    return q.copy()


def _stop(stats_row, margins: Margins) -> bool:
    """A margin or numerical floor is crossed at this sample (check_margins names it)."""
    _, _, wrist, sp, ss, sp_max, ss_max = stats_row
    bad = margins.violations(wrist=wrist, parallel=sp, serial=ss, parallel_max=sp_max,
                             serial_max=ss_max)
    return any(bool(b) for b in bad.values())


def inverse_kinematics_newton(robot: Robot, poses, d_poses=None, dd_poses=None, t=None,
                              q_start=None, options: IkOptions | None = None, *,
                              progress=None) -> IKResult:
    """Sample-by-sample constrained IK (``options``: its ``margins``, ``tol`` and
    ``max_iter``).

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
    options = ik_options(options)
    margins = options.margins
    kin = _Kinematics.of(robot)
    fr = kin.fr
    poses, d_poses, dd_poses, t = task_inputs(poses, d_poses, dd_poses, t)
    n = len(poses)
    Rs = rotation(poses)
    tw, twd = twist(poses, d_poses), twist_dot(poses, d_poses, dd_poses)
    nv = kin.model.nv
    rows = {k: np.empty((n, nv)) for k in ("q", "v", "a")}
    rows.update(spherical=np.empty((n, 6)), d_spherical=np.empty((n, 6)),
                stats=np.empty((n, 7)))
    if q_start is None:  # docs/model.md §9 branches, through the closed form at the first pose
        # a start only: the margins judge the solution Newton reports (_stop, check_margins)
        q = closed_form_angles(robot, poses[:1], t[:1], None)[0]
    else:
        q = _start_configuration(robot, q_start)

    def solve(guess, pose, R=None):
        return _newton(kin, guess, pose[:3], rotation(pose) if R is None else R, options.tol,
                       options.max_iter)

    branch = BranchQuantities(robot)
    ref = None
    for k in range(n):
        if k == 0:
            q, e, ok = solve(q, poses[0], Rs[0])
            signs = branch.signs_list(q)
        else:
            q, e, ok, signs = _next_position(solve, branch, rows, (poses, t, Rs), k, ref)
        if not ok:
            raise _diagnose(robot, poses[k], k, t[k], e, margins)
        # The reference keeps the last non-zero sign (a zero is a boundary: no information).
        ref = signs if ref is None else [s if s else r for s, r in zip(signs, ref)]
        K, v, a = _rates(kin, q, tw[k], twd[k])
        rows["stats"][k] = (np.abs(e[:6]).max(), np.abs(e[6:]).max(),
                            abs(np.sin(q[fr.wrist_q])),
                            *conditioning(K, fr.actuated_v, fr.passive_v, full=True))
        rows["spherical"][k], rows["d_spherical"][k] = spherical_angles(kin.data, fr)
        rows["q"][k], rows["v"][k], rows["a"][k] = q, v, a
        if progress is not None:
            progress(k + 1, n)
        if (_stop(rows["stats"][k], margins)
                or not math.isfinite(float(v.sum() + a.sum()))):  # NaN or inf anywhere
            n = k + 1  # stop here: the check below raises at the first offending sample
            break
    result = _result(robot, t, poses, rows, n)
    check_margins(robot, result, margins)
    return result


def _next_position(solve, branch: BranchQuantities, rows, task, k: int, ref):
    """(q, e, ok, signs) at sample k > 0: Newton from a second-order Taylor step off sample
    k − 1, or, where that lands off the branch signs ``ref``, continuation along the pose
    segment (:class:`BranchFlipError` where the motion crosses the assembly mode's
    boundary). ``task``: (poses, t, their rotations)."""
    poses, t, Rs = task
    dt = t[k] - t[k - 1]
    q_prev = rows["q"][k - 1]
    q = q_prev + dt * rows["v"][k - 1] + 0.5 * dt * dt * rows["a"][k - 1]
    q, e, ok = solve(q if np.isfinite(q).all() else q_prev, poses[k], Rs[k])
    signs = branch.signs_list(q)
    if not (ok and same_branch(signs, ref)):
        q, e, ok, flip = _follow(solve, branch.signs_list, q_prev, poses[k - 1], poses[k], ref)
        if flip is not None:
            s_, q_a, q_b = flip
            va, vb = branch(q_a), branch(q_b)
            j = next(i for i, (a_, b_) in enumerate(zip(branch.signs_list(q_b), ref))
                     if a_ * b_ < 0)
            raise flip_error(k - 1, k, j, float(va[j]), float(vb[j]), t[k],
                             near=float(t[k - 1] + s_ * dt))
        signs = branch.signs_list(q)
    return q, e, ok, signs


def _rates(kin: _Kinematics, q, twist_k, twist_dot_k):
    """(K, v, a) at q: K v = [0; twist], K a = [−closure drift; twist rate − tool drift];
    NaN where K is singular (check_margins names the singularity). Leaves ``kin.data`` at
    (q, v) for :func:`spherical_angles`."""
    model, data, fr = kin.model, kin.data, kin.fr
    K = kinematic_matrix(model, data, kin.cms, kin.cds, fr, q)
    rhs_v = np.zeros(12)
    rhs_v[6:] = twist_k
    try:
        v = np.linalg.solve(K, rhs_v)
        drift = frame_drifts(model, data, fr, q, v)
        rhs_a = -drift
        rhs_a[6:] += twist_dot_k
        a = np.linalg.solve(K, rhs_a)
    except np.linalg.LinAlgError:  # singular K
        v = a = np.full(model.nv, np.nan)
        pin.forwardKinematics(model, data, q, np.zeros(model.nv))
    return K, v, a


def _result(robot: Robot, t, poses, rows, n: int) -> IKResult:
    """The first ``n`` samples of ``rows`` as an IKResult."""
    stats = rows["stats"]
    return IKResult(t=t[:n], poses=poses[:n], q=rows["q"][:n], v=rows["v"][:n],
                    a=rows["a"][:n], spherical=rows["spherical"][:n],
                    d_spherical=rows["d_spherical"][:n], closure_residual=stats[:n, 0],
                    tool_error=stats[:n, 1], wrist_margin=stats[:n, 2],
                    sigma_parallel=stats[:n, 3], sigma_serial=stats[:n, 4],
                    joint_names=robot.joint_names, sigma_parallel_max=stats[:n, 5],
                    sigma_serial_max=stats[:n, 6])
