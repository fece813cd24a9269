"""Constrained IK stacked over samples (docs/model.md §7, §11): the closed form, one Newton
step and the velocity and acceleration systems, with no Python loop over samples."""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..analytic import closed_form
from ..analytic.taskspace import MAX_ABS_TASK, rotation, twist, twist_dot
from ..model.build import TIP_FRAME, Robot
from ..timing import Stopwatch
from . import kernels
from .errors import UnreachablePoseError
from .ik_common import (
    BATCH_CHUNK,
    IK_TOL,
    IkOptions,
    IKResult,
    KinematicFrames,
    closed_form_angles,
    ik_options,
    task_inputs,
    zyz,
    zyz_rates,
)
from .limits import limit_violations
from .margins import Margins, as_margins
from .singularity import (
    BranchQuantities,
    check_margins,
    conditioning,
    finite_rows,
    inverse_stack,
)
from .tree import Point, TreeArrays, matvec, support_cols, tree_arrays


# --- batched path ------------------------------------------------------------------------------
# No Python loop over samples: joint placements, Jacobians and their time variation come from
# passes over Pinocchio's model tree stacked over samples (docs/model.md §11), and points,
# residuals, drifts and every 12 × 12 system are stacked over samples in numpy.
@dataclass(frozen=True)
class Layout:
    closures: tuple[tuple[Point, Point], ...]
    tip: Point
    platform: int
    links: tuple[int, ...]
    spherical_offset: tuple[np.ndarray, ...]  # Rz(−β1413i), docs/model.md §4
    joints: tuple[int, ...]  # every joint whose placement is needed, parents first
    # K's block-triangular partition (closure rows, tool rows, tool-support columns, the
    # others), when the tool is moved by exactly as many joints as it has rows; else None.
    blocks: tuple[np.ndarray, ...] | None = None
    tree: TreeArrays | None = None  # the same, as arrays for the compiled kernels
    wrist_q: int = -1  # θ1716's configuration index
    joint_names: tuple[str, ...] = ()  # the robot's, looked up once


_LAYOUTS: dict = {}  # id(robot) → (robot, its Layout): the last few robots', kept alive
_LAYOUTS_KEPT = 8


def layout(robot: Robot) -> Layout:
    """The robot's :class:`Layout`, made once per robot (a plan asks ~1000 times; 1 ms each)."""
    hit = _LAYOUTS.get(id(robot))
    if hit is not None and hit[0] is robot:
        return hit[1]
    if len(_LAYOUTS) >= _LAYOUTS_KEPT:
        _LAYOUTS.pop(next(iter(_LAYOUTS)))
    lay = _layout(robot)
    _LAYOUTS[id(robot)] = (robot, lay)
    return lay


def _layout(robot: Robot) -> Layout:
    model = robot.model

    def point(frame_name):
        f = model.frames[robot.frame_id(frame_name)]
        local = np.array(f.placement.translation)
        return Point(int(f.parentJoint), local, support_cols(model, f.parentJoint))

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
    tree = tree_arrays(model, joints, points,
                        [3 * i for i in range(len(closures)) for _ in range(2)] + [rows],
                        [1.0, -1.0] * len(closures) + [1.0])
    return Layout(closures, tip, fr.platform_joint, fr.link_joints, fr.spherical_offset,
                   tuple(joints), blocks, tree, fr.wrist_q, robot.joint_names)


def kinematic_inverse(K: np.ndarray, lay: Layout) -> np.ndarray:
    """K⁻¹ of the stacked [Jc; J_tool] (NaN where singular). The tool rows involve only the
    tool's supporting joints, so K is block-triangular (docs/model.md §11) and two inverses of
    half the size give K⁻¹ (compiled, :func:`.kernels.block_inverse`)."""
    if lay.blocks is None:
        return inverse_stack(K)
    return kernels.block_inverse(K, *lay.blocks)


def _log3(R):
    """Batched SO(3) logarithm (vector), exact away from π."""
    w = 0.5 * np.stack([R[:, 2, 1] - R[:, 1, 2], R[:, 0, 2] - R[:, 2, 0],
                        R[:, 1, 0] - R[:, 0, 1]], axis=1)
    s = np.linalg.norm(w, axis=1)
    c = 0.5 * (np.trace(R, axis1=1, axis2=2) - 1.0)
    th = np.arctan2(s, c)
    scale = np.where(s > 1e-8, th / np.where(s > 1e-8, s, 1.0), 1.0 + s * s / 6.0)
    return w * scale[:, None]


def _residuals(R, pos, lay: Layout, P_des, R_des) -> np.ndarray:
    """[closure p_A − p_B (6); tip position error (3); orientation error (3)], (N, 12), from
    the placements R and point positions of :func:`point_rows`."""
    nc = len(lay.closures)
    res = [pos[:, 2 * i] - pos[:, 2 * i + 1] for i in range(nc)]
    R_tip = R[lay.tree.slot[lay.tip.joint]]
    res += [pos[:, 2 * nc] - P_des, _log3(R_tip @ np.swapaxes(R_des, 1, 2))]
    return np.concatenate(res, axis=1)


def point_rows(lay: Layout, R, o, nv: int):
    """K = [Jc; J_tool] (N, 12, nv) and the points' positions (N, P, 3): point Jacobians
    z_c × (p − o_c) summed over the joints moving each point, compiled
    (:func:`.kernels.point_jacobians`)."""
    t = lay.tree
    return kernels.point_jacobians(R, o, t.axis, t.col, t.pt_slot, t.pt_local, t.pt_support,
                                   t.pt_row, t.pt_sign, *t.tool, nv)


def point_drifts(lay: Layout, R, o, v, pos):
    """K̇ v (N, 12) and every body's angular velocity (S, N, 3), compiled
    (:func:`.kernels.point_drifts`)."""
    t = lay.tree
    return kernels.point_drifts(R, o, t.parent, t.axis, t.col, v, t.pt_slot, t.pt_row, t.pt_sign,
                                pos, *t.tool)


POLISH_TOL = 1e-14  # m / rad: closed-form residual above which the Newton step is applied
SCREEN = 8  # samples per sequence screened by the closed form before the rest (reach)


def inverse_kinematics_batch(robot: Robot, poses, d_poses=None, dd_poses=None, t=None,
                             options: IkOptions | None = None, *, progress=None,
                             timings: dict | None = None, at_rest: bool = False) -> IKResult:
    """Same result as :func:`inverse_kinematics`, stacked over samples (``options``: its
    ``margins``, ``tol`` and ``chunk``, samples per block). ``at_rest`` (no rates or
    accelerations given: a caller that reads the positions): the rates, accelerations and
    spherical rates are K⁻¹·0 without the drifts (:func:`_batch_block`), the same samples
    refused with the same error, the other figures the same.

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
    options = ik_options(options)
    margins, chunk = options.margins, options.chunk
    clock = Stopwatch(timings)
    at_rest = at_rest and d_poses is None and dd_poses is None  # none given: zeros
    poses, d_poses, dd_poses, t = task_inputs(poses, d_poses, dd_poses, t)
    n = len(poses)
    q0 = closed_form_angles(robot, poses, t, margins)
    clock.lap("position")
    result = None
    for start in range(0, n, chunk):
        sl = slice(start, min(start + chunk, n))
        task = (poses[sl], d_poses[sl], dd_poses[sl], t[sl])
        part = _batch_block(robot, q0[sl], task, options.tol, start, clock, at_rest=at_rest)
        result = part if n <= chunk else gather(result, part, sl, poses, t)
        if progress is not None:
            progress(sl.stop, n)
    check_margins(robot, result, margins)
    clock.lap("analysis")
    return result


def gather(result: IKResult | None, part: IKResult, sl: slice, poses, t) -> IKResult:
    """``part``, the block of samples ``sl``, written in place into ``result`` (None at the
    first block: made then, with room for every sample of ``poses`` and ``t``, which it
    holds whole). The same arrays, bit for bit, as concatenating the blocks, without keeping
    them all until the end."""
    if result is None:
        n = len(t)
        result = replace(part, t=t, poses=poses, **{
            f: np.empty((n, *a.shape[1:]), a.dtype) for f, a in vars(part).items()
            if isinstance(a, np.ndarray) and f not in ("t", "poses")})
    for f, a in vars(part).items():
        if isinstance(a, np.ndarray) and f not in ("t", "poses"):
            getattr(result, f)[sl] = a
    return result


def _batch_block(robot: Robot, q0, task, tol, start, clock, strict: bool = True,
                 at_rest: bool = False) -> IKResult:
    """One block of samples from its closed-form angles ``q0``; ``task``: its (poses,
    d_poses, dd_poses, t), the first being sample ``start``; not ``strict``: a residual above
    ``tol`` is left in the result's residuals instead of raised. ``at_rest`` (the rates and
    accelerations given are zeros): the rates, accelerations and spherical rates are K⁻¹·0
    and the rates of a body at rest (0 but where their system is singular: NaN, as the drifts
    of v = 0 give), the drifts not computed; every other figure the same."""
    poses, d_poses, dd_poses, t = task
    n = len(poses)
    model = robot.model
    lay = layout(robot)
    P_des, R_des = poses[:, :3], rotation(poses)
    # Newton polish at the closed form; velocities with the same matrix (one stacked solve).
    R, o = lay.tree.placements(q0)
    K, pos = point_rows(lay, R, o, model.nv)
    rhs = np.zeros((n, 12, 2))
    rhs[:, :, 0] = _residuals(R, pos, lay, P_des, R_des)
    clock.lap("position")
    if not at_rest:
        rhs[:, 6:, 1] = twist(poses, d_poses)
    # One K⁻¹ per sample serves the Newton step, the velocities, the accelerations and the
    # serial conditioning (conditioning(K_inv=...)). NaN where K is singular (checked below).
    K_inv = kinematic_inverse(K, lay)
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
        K[moved], pos[moved] = point_rows(lay, R_m, o_m, model.nv)
        K_inv[moved] = kinematic_inverse(K[moved], lay)
        v[moved] = matvec(K_inv[moved], rhs[moved, :, 1])
    clock.lap("velocity")
    # Accelerations: K a = [−closure drift; tool acceleration − tool drift].
    singular = ~np.isfinite(v).all(axis=1)
    if singular.any():  # keep NaN out of the drifts; those samples stay NaN
        v = np.where(singular[:, None], 0.0, v)
    if at_rest:  # K⁻¹ times the zero drift of v = 0: 0 where K⁻¹'s row is finite
        a, omega = v * 0.0, np.zeros((R.shape[0], n, 3))
    else:
        drift, omega = point_drifts(lay, R, o, v, pos)
        rhs_a = -drift
        rhs_a[:, 6:] += twist_dot(poses, d_poses, dd_poses)
        a = matvec(K_inv, rhs_a)
    if singular.any():
        v[singular] = a[singular] = np.nan
    # re-measured at the returned configuration: where no sample moved, that is the closed
    # form's, whose residuals are already at hand (the same numbers)
    err = np.abs(_residuals(R, pos, lay, P_des, R_des) if len(moved) else rhs[:, :, 0])
    if strict and not err.max() <= tol:
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
                      wrist_margin=np.abs(np.sin(q[:, lay.wrist_q])),
                      sigma_parallel=sp, sigma_serial=ss, sigma_parallel_max=sp_max,
                      sigma_serial_max=ss_max, joint_names=lay.joint_names,
                      constraint_jacobian=K[:, :6])
    clock.lap("analysis")
    return result


def reachable_sequences(robot: Robot, poses, margins: Margins | None = None) -> np.ndarray:
    """Whether each of S sequences of N static tool poses, ``poses`` (S, N, 6), is in reach:
    (S,) booleans, each what :func:`inverse_kinematics_batch` with ``margins`` (default
    :class:`Margins`'s) followed by :func:`.limits.check_joint_limits` would say of that
    sequence alone (no error raised: reach), with the sequences stacked into one batch. The
    per-sample rules run on every sample (the closed form, the wrist margin, the Newton
    residual, the margins and floors, finite results, the joint limits), the closed form's
    angles unwrapped within each sequence as alone; a sequence also fails where an
    assembly-branch sign takes both signs along it (a flip, :func:`.singularity.check_margins`).
    A non-finite or absurd pose raises the
    :class:`~pollard_pin.kinematics.KinematicsInputError` its sequence would
    (the first such sequence's).
    """
    margins = as_margins(margins)
    poses = np.asarray(poses, dtype=float)
    S, N = poses.shape[:2]
    bad = ~(np.abs(poses) <= MAX_ABS_TASK).all(axis=(1, 2))
    if bad.any():  # the first such sequence's own input error, as alone
        task_inputs(poses[int(np.argmax(bad))], None, None, None)
    # a screen: a few samples of each sequence through the closed form first (any failing
    # sample fails its sequence), the rest only for the sequences that pass it
    ok = np.ones(S, dtype=bool)
    if N > 2 * SCREEN:
        ok = _closed_form_passes(robot, poses[:, np.linspace(0, N - 1, SCREEN).astype(int)],
                                 margins)[0].all(axis=1)
    good = np.flatnonzero(ok)
    group = max(1, BATCH_CHUNK // N)  # sequences per batch: memory bounded by BATCH_CHUNK
    for g in range(0, len(good), group):
        seqs = good[g:g + group]
        passes, q18 = _closed_form_passes(robot, poses[seqs], margins)
        alive = passes.all(axis=1)
        ok[seqs] = alive
        if alive.any():
            ok[seqs[alive]] = _solved_pass(robot, poses[seqs[alive]], q18[alive], margins)
    return ok


def _solved_pass(robot: Robot, poses, q18, margins: Margins) -> np.ndarray:
    """Per sequence of ``poses`` (S, N, 6) whose closed form ``q18`` (S, N, 18) solves every
    sample: the rest of :func:`reachable_sequences`' rules hold, (S,) booleans. A screen
    first: SCREEN samples of each sequence solved alone from the whole sequence's unwrapped
    angles (each sample's figures the whole solve's, to the bit) fail the sequences where
    one of them breaks a rule (a branch sign taking both signs among them, both along the
    whole), most of those that fail (the joint limits, the margins), at ~2 % of the solve."""
    S, N = poses.shape[:2]
    q0 = continuous_sequences(q18[:, :, :12])
    ok = np.ones(S, dtype=bool)
    if N > 2 * SCREEN:
        at = np.linspace(0, N - 1, SCREEN).astype(int)
        ok = _rules_hold(robot, poses[:, at], q0[:, at], margins)
    if ok.any():
        ok[ok] = _rules_hold(robot, poses[ok], q0[ok], margins)
    return ok


def _rules_hold(robot: Robot, poses, q0, margins: Margins) -> np.ndarray:
    """:func:`_solved_pass`'s rules on sequences of ``poses`` (S, N, 6) from their unwrapped
    closed-form angles ``q0`` (S, N, 12), (S,) booleans."""
    S, N = poses.shape[:2]
    q0 = q0.reshape(S * N, -1)
    sub = poses.reshape(-1, 6)
    zero, t = np.zeros_like(sub), np.tile(np.arange(N, dtype=float), S)
    fine, q = [], []
    for a in range(0, len(sub), BATCH_CHUNK):
        sl = slice(a, min(a + BATCH_CHUNK, len(sub)))
        r = _batch_block(robot, q0[sl], (sub[sl], zero[sl], zero[sl], t[sl]), IK_TOL, a,
                         Stopwatch(None), strict=False, at_rest=True)
        sph = [np.abs(np.sin(r.spherical[:, 3 * i - 2])) for i in (1, 2)]
        viol = margins.violations(wrist=r.wrist_margin, parallel=r.sigma_parallel,
                                  serial=r.sigma_serial, parallel_max=r.sigma_parallel_max,
                                  serial_max=r.sigma_serial_max, spherical=sph)
        f = np.maximum(r.closure_residual, r.tool_error) <= IK_TOL
        f &= ~np.logical_or.reduce(list(viol.values()))
        f &= finite_rows(r)
        f &= ~limit_violations(robot.params, r.q, robot.joint_names)[0].any(axis=1)
        fine.append(f)
        q.append(r.q)
    signs = BranchQuantities(robot).signs(np.concatenate(q)).reshape(S, N, -1)
    flip = ((signs > 0).any(axis=1) & (signs < 0).any(axis=1)).any(axis=1)
    return np.concatenate(fine).reshape(S, N).all(axis=1) & ~flip


def continuous_sequences(q) -> np.ndarray:
    """:func:`.closed_form.make_continuous` of each of S sequences of angles ``q`` (S, N, J),
    (S, N, J): one call over the sequences side by side as columns (each column's turns and
    unwrapping are its own), bit for bit each sequence's alone."""
    S, N, J = q.shape
    side = np.ascontiguousarray(np.swapaxes(q, 0, 1)).reshape(N, S * J)
    return np.swapaxes(closed_form.make_continuous(side).reshape(N, S, J), 0, 1)


def _closed_form_passes(robot: Robot, poses, margins: Margins):
    """Per sample of ``poses`` (S, N, 6): the closed form solves it and its wrist keeps the
    margin (:func:`.ik_common.closed_form_angles`' rules), (S, N) booleans, and the closed
    form's angles (S, N, 18)."""
    S, N = poses.shape[:2]
    q18, failed = closed_form.position_ik_masked(robot.params, poses.reshape(S * N, 6))
    bad = np.logical_or.reduce(list(failed.values()))
    bad |= margins.violations(wrist=np.abs(np.sin(q18[:, closed_form.JOINTS.index(
        "theta1716")])))["wrist"]
    return ~bad.reshape(S, N), q18.reshape(S, N, -1)


def _spherical_batch(lay: Layout, R, omega):
    """ZYZ angles of R_linkᵀ R_platform Rz(−β1413i) and their rates (docs/model.md §4), (N, 6)
    each, from the placements R and body angular velocities ω (slots first)."""
    slot = lay.tree.slot
    R_p, w_p = R[slot[lay.platform]], omega[slot[lay.platform]]
    ang, rate = [], []
    for link, C in zip(lay.links, lay.spherical_offset):
        R_l = R[slot[link]]
        ang.append(zyz(np.swapaxes(R_l, 1, 2) @ R_p @ C))
        rate.append(zyz_rates(ang[-1], matvec(np.swapaxes(R_l, 1, 2),
                                                w_p - omega[slot[link]])))
    return np.concatenate(ang, axis=1), np.concatenate(rate, axis=1)
