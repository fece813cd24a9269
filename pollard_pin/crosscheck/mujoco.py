"""Independent engine check: closed-loop inverse dynamics with MuJoCo (docs/model.md §3, §4, §6).

Uses only numpy, MuJoCo (imported lazily: a test/benchmark dependency) and the URDF file; no
Pinocchio. The URDF open tree is loaded with ``MjSpec.from_file``; the two cut spherical
joints of docs/model.md §4 become ``mjEQ_CONNECT`` equalities between sites at Tx(x87i) on
``link_i`` and A_i on ``platform`` (positions read from the URDF fixed joints of the
``<loop_closure>`` frames). ``mj_inverse`` gives the open-tree torques; the actuator torques τ
and the closure forces λ then solve ``[Sᵀ Jcᵀ] [τ; λ] = τ_tree`` with Jc the connect rows of
``efc_J``.

The constrained inverse kinematics (:func:`inverse_kinematics_mujoco`) is MuJoCo's too: Newton
on the closure residual and tool-pose error with ``mj_jacSite`` Jacobians (a site ``tip_site``
at the URDF ``tip`` frame, Tx(x1918) on ``gun``), and exact acceleration drifts from
``mj_rnePostConstraint`` + ``mj_objectAcceleration``. :func:`pipeline_mujoco` chains IK and
inverse dynamics: the complete MuJoCo peer path, timed per stage.

The model itself (the URDF read without Pinocchio, the closed-loop spec, the MJCF file that
:func:`build_mujoco` can read back with ``mjcf_path=``) comes from :mod:`pollard_pin.io.mjcf`.

Modelling notes:

- MuJoCo rejects massless moving bodies, so each massless U-joint cross (docs/model.md §5) is
  removed and its hinge moved into its child body ahead of the child's own hinge. MuJoCo
  composes the joints of one body in order, so the kinematics are unchanged: Ry(θ43) Rz(θ54)
  etc. (docs/model.md §3).
- ``inertiafromgeom`` is off, so masses and inertias are the URDF inertials (checked).
- Contacts, joint limits, springs, dampers and friction loss are disabled (docs/model.md §13:
  ideal joints). The exported file keeps the joint limits (the URDF's); the peer turns them off.
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from ..errors import SolveError
from ..io.mjcf import (  # noqa: F401
    TIP,
    check_mjcf,
    closed_loop_spec,
    default_urdf,
    home_configuration,
    read_urdf,
    require_mujoco,
)
from ..names import ACTUATED
from ..names import TREE_JOINTS as JOINTS

GRAVITY = np.array([0.0, 0.0, -9.81])  # docs/model.md §2
MASS_TOL = 1e-12  # relative tolerance of the mass/inertia check

_CACHE: dict[str, tuple] = {}


def build_mujoco(urdf_path=None, mjcf_path=None):
    """Compile the closed-loop MuJoCo model. Returns ``(model, data, info)``.

    The model is built from the URDF ``urdf_path`` (default: the shipped one), or read from an
    MJCF file ``mjcf_path`` (as :func:`~pollard_pin.io.mjcf.export_mjcf` writes it); the URDF
    is then the reference its contents are checked against (sites, equalities, masses,
    inertias). Either way the joints are made ideal (no limits, springs, damping, friction,
    contacts: docs/model.md §13).

    ``info`` holds the name→address maps (in :data:`JOINTS` order), the site/equality ids, the
    efc sign and the mass/inertia check against the URDF. Raises ``ValueError`` when a check
    fails (gravity, masses, inertias, joints, constraint rows).
    """
    mujoco = require_mujoco()

    path = Path(urdf_path) if urdf_path is not None else default_urdf()
    if mjcf_path is None:
        spec, urdf, merged = closed_loop_spec(path)
    else:
        urdf = read_urdf(path)
        spec = mujoco.MjSpec.from_file(str(mjcf_path))
        moving = [j["child"] for j in urdf["joints"].values() if j["type"] != "fixed"]
        merged = [b for b in moving if b not in {x.name for x in spec.bodies}
                  or not spec.body(b).joints]  # crosses: fused into their parent
    for j in spec.joints:  # ideal joints
        j.limited = j.actfrclimited = mujoco.mjtLimited.mjLIMITED_FALSE
        j.damping = j.stiffness = np.zeros(3)  # MuJoCo 4: polynomial coefficients
        j.armature = j.frictionloss = 0.0
        j.springdamper = np.zeros(2)
    model = spec.compile()
    D = mujoco.mjtDisableBit
    model.opt.disableflags |= (D.mjDSBL_CONTACT | D.mjDSBL_LIMIT | D.mjDSBL_SPRING
                               | D.mjDSBL_DAMPER | D.mjDSBL_FRICTIONLOSS)
    model.opt.jacobian = mujoco.mjtJacobian.mjJAC_DENSE
    data = mujoco.MjData(model)

    if mjcf_path is not None:
        check_mjcf(model, urdf, mjcf_path)
    if not np.array_equal(model.opt.gravity, GRAVITY):
        raise ValueError(f"MuJoCo gravity {model.opt.gravity} != docs/model.md §2 {GRAVITY}")
    for n in JOINTS:
        if mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, n) < 0:
            raise ValueError(f"joint {n!r} missing from the MuJoCo model")
    if model.nv != 12 or np.any(model.jnt_type != mujoco.mjtJoint.mjJNT_HINGE):
        raise ValueError(f"expected 12 hinges, got nv={model.nv}")
    if np.any(model.dof_armature) or np.any(model.dof_damping) or np.any(model.jnt_stiffness):
        raise ValueError("armature/damping/stiffness left in the MuJoCo model")
    jid = [model.joint(n).id for n in JOINTS]
    qadr = model.jnt_qposadr[jid].copy()
    dadr = model.jnt_dofadr[jid].copy()
    if np.any(model.qpos0[qadr] != 0):
        raise ValueError("nonzero qpos0 (joint ref): angles would be offset")

    # Masses and inertias (about the CoG, body frame) against the URDF, docs/model.md §5.
    mass_err, inertia_err, body_mass = 0.0, 0.0, {}
    for b in range(1, model.nbody):
        name = model.body(b).name
        body_mass[name] = float(model.body_mass[b])
        ref = urdf["inertials"].get(name)
        if ref is None:
            if model.body_mass[b] != 0:
                raise ValueError(f"MuJoCo body {name!r} has mass but no URDF inertial")
            continue
        R = np.empty(9)
        mujoco.mju_quat2Mat(R, model.body_iquat[b])
        R = R.reshape(3, 3)
        I = R @ np.diag(model.body_inertia[b]) @ R.T
        mass_err = max(mass_err, abs(model.body_mass[b] - ref["mass"]) / ref["mass"])
        scale = np.abs(ref["inertia"]).max()
        inertia_err = max(inertia_err, np.abs(I - ref["inertia"]).max() / scale,
                          np.abs(model.body_ipos[b] - ref["com"]).max())
    missing = sorted(set(urdf["inertials"]) - set(body_mass))
    if missing or mass_err > MASS_TOL or inertia_err > MASS_TOL:
        raise ValueError(f"MuJoCo inertials differ from the URDF: missing {missing}, mass "
                         f"rel. error {mass_err:.3g}, inertia/CoG error {inertia_err:.3g}")

    # Constraint rows and their sign: efc_J = s·∂(p_A − p_B)/∂q (checked against mj_jacSite).
    eq_names = [c for c, _, _ in urdf["closures"]]
    site_ids = np.array([[model.site(f"{c}_{tag}_site").id for tag in "AB"] for c in eq_names])
    sites = [[(model.site(i).name, model.body(int(model.site(i).bodyid[0])).name,
               model.site(i).pos.copy()) for i in pair] for pair in site_ids]
    eq_ids = np.array([model.equality(n).id for n in eq_names])
    rng = np.random.default_rng(0)
    data.qpos[:] = rng.uniform(-1, 1, model.nq)
    mujoco.mj_fwdPosition(model, data)
    rows, signs = _efc_rows(model, data, eq_ids), []
    jA, jB = np.zeros((3, model.nv)), np.zeros((3, model.nv))
    J = data.efc_J.reshape(data.nefc, model.nv)
    for i, (sa, sb) in enumerate(site_ids):
        mujoco.mj_jacSite(model, data, jA, None, sa)
        mujoco.mj_jacSite(model, data, jB, None, sb)
        Jref, Ji = jA - jB, J[rows[i]]
        s = [s for s in (1.0, -1.0) if np.abs(Ji - s * Jref).max() <= 1e-12 * np.abs(Jref).max()]
        if not s:
            raise ValueError(f"connect rows of {eq_names[i]!r} are not ±(J_A − J_B)")
        signs.append(s[0])
    mujoco.mj_resetData(model, data)
    has_tip = f"{TIP}_site" in [model.site(i).name for i in range(model.nsite)]
    tip = None
    if has_tip:
        s = model.site(f"{TIP}_site")
        tip = (model.body(int(s.bodyid[0])).name, s.pos.tolist())
    info = dict(urdf_path=str(path), mjcf_path=None if mjcf_path is None else str(mjcf_path),
                joints=JOINTS, actuated=ACTUATED, qpos_adr=qadr,
                dof_adr=dadr, actuated_idx=np.array([JOINTS.index(n) for n in ACTUATED]),
                closures=tuple(eq_names), eq_ids=eq_ids, efc_rows=rows, site_ids=site_ids,
                sites=[[(s, link, pos.tolist()) for s, link, pos in pair] for pair in sites],
                efc_sign=np.array(signs), merged_bodies=merged, body_mass=body_mass,
                total_mass=float(mujoco.mj_getTotalmass(model)), mass_rel_error=mass_err,
                inertia_error=inertia_err, gravity=model.opt.gravity.copy(),
                tip_site=model.site(f"{TIP}_site").id if has_tip else -1, tip=tip)
    return model, data, info


def _efc_rows(model, data, eq_ids) -> np.ndarray:
    """(2, 3) efc row indices of the connect equalities; fails on any other active row."""
    mujoco = require_mujoco()

    if data.nefc != 3 * len(eq_ids) or np.any(data.efc_type[:data.nefc]
                                             != mujoco.mjtConstraint.mjCNSTR_EQUALITY):
        raise ValueError(f"expected only the {3 * len(eq_ids)} connect rows, got nefc="
                         f"{data.nefc} of types {data.efc_type[:data.nefc]}")
    ids = data.efc_id[:data.nefc]
    rows = np.array([np.flatnonzero(ids == e) for e in eq_ids])
    if rows.shape != (len(eq_ids), 3):
        raise ValueError(f"connect rows not found: efc_id {ids}")
    return rows


def cached_model(urdf_path, mjcf_path=None):
    key = tuple(str(Path(p).resolve()) if p is not None else "<default>"
                for p in (urdf_path, mjcf_path))
    if key not in _CACHE:
        _CACHE[key] = build_mujoco(urdf_path, mjcf_path)
    return _CACHE[key]


# --- inverse dynamics -------------------------------------------------------------------------
def inverse_dynamics_mujoco(q, v, a, urdf_path=None, built=None, mjcf_path=None) -> dict:
    """Closed-loop inverse dynamics with MuJoCo at samples (N, 12) in :data:`JOINTS` order.

    Returns a dict of

    - ``tau`` (N, 6): actuator torques [N·m], :data:`ACTUATED` order (docs/model.md §6);
    - ``closure_forces`` (N, 2, 3): force the platform exerts ON ``link_i`` at the ball joint
      [N], world axes (docs/model.md §4);
    - ``tree`` (N, 12): open-tree torques (M a + c + g) [N·m], :data:`JOINTS` order;
    - ``residual`` (N, 2): |p_A − p_B| of each connect pair in MuJoCo [m] (sanity check);
    - ``residual_vec`` (N, 2, 3): p_A − p_B [m], world axes.

    ``built`` may pass ``build_mujoco()``'s result; otherwise a cached model is used, built from
    ``urdf_path`` or read from ``mjcf_path`` (see :func:`build_mujoco`).
    """
    mujoco = require_mujoco()

    model, data, info = built if built is not None else cached_model(urdf_path, mjcf_path)
    q, v, a = (np.atleast_2d(np.asarray(x, dtype=float)) for x in (q, v, a))
    n = len(q)
    for label, x in (("q", q), ("v", v), ("a", a)):
        if x.shape != (n, 12):
            raise ValueError(f"{label} has shape {x.shape}, expected ({n}, 12) in order {JOINTS}")
    qadr, dadr, rows = info["qpos_adr"], info["dof_adr"], info["efc_rows"].reshape(-1)
    sa, sb = info["site_ids"][:, 0], info["site_ids"][:, 1]
    nv = model.nv
    # Raw MuJoCo arrays in the loop; index mapping vectorised afterwards.
    Q, V, Acc = np.zeros((n, model.nq)), np.zeros((n, nv)), np.zeros((n, nv))
    Q[:, qadr], V[:, dadr], Acc[:, dadr] = q, v, a
    F, Jraw, X = np.empty((n, nv)), np.empty((n, 6 * nv)), np.empty((n, model.nsite, 3))
    for k in range(n):
        data.qpos[:], data.qvel[:], data.qacc[:] = Q[k], V[k], Acc[k]
        mujoco.mj_inverse(model, data)
        if data.nefc != 6:
            raise ValueError(f"sample {k}: {data.nefc} constraint rows, expected 6")
        # qfrc_inverse has the (soft, ~1e-13) equality force subtracted: add it back → open tree.
        F[k] = data.qfrc_inverse + data.qfrc_constraint + data.qfrc_passive
        Jraw[k] = data.efc_J
        X[k] = data.site_xpos
    tree = F[:, dadr]
    Jc = Jraw.reshape(n, 6, nv)[:, rows][:, :, dadr]
    res = X[:, sa] - X[:, sb]
    # [Sᵀ Jcᵀ][τ; λ] = τ_tree, 12 unknowns per sample.
    A = np.zeros((n, 12, 12))
    A[:, info["actuated_idx"], np.arange(6)] = 1.0
    A[:, :, 6:] = Jc.transpose(0, 2, 1)
    x = np.linalg.solve(A, tree[:, :, None])[:, :, 0]
    # efc rows are s·(J_A − J_B); λ·s is then the force on link_i (A side).
    lam = x[:, 6:].reshape(n, 2, 3) * info["efc_sign"][None, :, None]
    return dict(tau=x[:, :6], closure_forces=lam, tree=tree,
                residual=np.linalg.norm(res, axis=2), residual_vec=res)


# --- constrained inverse kinematics -----------------------------------------------------------
IK_TOL = 1e-12  # m / rad, closure residual and tool-pose error reached by Newton
IK_MAX_ITER = 30
IK_MAX_STEP = 0.5  # rad, largest joint change of one Newton step (damping far from the solution)


class MujocoIKError(SolveError):
    """Newton did not converge at ``sample``; ``residual`` is the largest error reached."""

    def __init__(self, message: str, sample: int | None = None, residual: float | None = None):
        super().__init__(message)
        self.sample, self.residual = sample, residual


def site_drifts(model, data, sites, q, v, out, acc6=None):
    """K̇ v (12,) at MuJoCo-ordered ``q``, ``v`` into ``out``: [closure drifts (p̈_A − p̈_B at
    q̈ = 0) (6); tip classical acceleration at q̈ = 0 (3); ω̇ at q̈ = 0 (3)], world axes.

    qvel = v, qacc = 0; ``mj_comVel`` + ``mj_rnePostConstraint`` fill ``cacc``, and
    ``mj_objectAcceleration(…, flg_local=0)`` returns (ω̇, p̈) of a site: the classical
    acceleration of its point (the ω × v term included; checked against finite differences in
    the tests). ``cacc`` of the world body is −gravity, a uniform offset in every linear
    acceleration: it cancels in the closure differences and is added back for the tip.
    ``sites`` = (A1, B1, A2, B2, tip) site ids.
    """
    mujoco = require_mujoco()

    acc6 = np.empty(6) if acc6 is None else acc6
    sa1, sb1, sa2, sb2, tip = sites
    data.qpos[:], data.qvel[:] = q, v
    data.qacc[:] = 0.0
    mujoco.mj_kinematics(model, data)
    mujoco.mj_comPos(model, data)
    mujoco.mj_comVel(model, data)
    mujoco.mj_rnePostConstraint(model, data)
    oacc, SITE = mujoco.mj_objectAcceleration, mujoco.mjtObj.mjOBJ_SITE
    oacc(model, data, SITE, sa1, acc6, 0)
    out[0:3] = acc6[3:]
    oacc(model, data, SITE, sb1, acc6, 0)
    out[0:3] -= acc6[3:]
    oacc(model, data, SITE, sa2, acc6, 0)
    out[3:6] = acc6[3:]
    oacc(model, data, SITE, sb2, acc6, 0)
    out[3:6] -= acc6[3:]
    oacc(model, data, SITE, tip, acc6, 0)
    out[6:9] = acc6[3:] + model.opt.gravity
    out[9:12] = acc6[:3]
    return out


class _Clock:
    def __init__(self, sink):
        self.sink, self.t = sink, time.perf_counter()

    def lap(self, stage):
        if self.sink is not None:
            now = time.perf_counter()
            self.sink[stage] = self.sink.get(stage, 0.0) + now - self.t
            self.t = now


def inverse_kinematics_mujoco(poses, d_poses=None, dd_poses=None, q_start=None, urdf_path=None,
                              built=None, tol: float = IK_TOL, timings: dict | None = None,
                              max_iter: int = IK_MAX_ITER, predictor: str = "previous") -> dict:
    """Constrained IK with MuJoCo along task poses (N, 6) = (x, y, z, ψ, θ, φ) (docs/model.md §2).

    - Positions: per sample, Newton on e = [p_A − p_B of both closures (6); tip position error
      (3); log(R_tip R_desᵀ) (3)], world axes, with K = [J_A − J_B; J_tip; J_rot,tip] from
      ``mj_jacSite``; warm start from the previous sample (the first from ``q_start``,
      default :func:`home_configuration`); iterate until max |e| ≤ ``tol``, then one more step.
    - Velocities: K v = [0; tool twist (v, ω)].
    - Accelerations: K a = [−closure drift; tool acceleration − tool drift]. The drifts K̇ v
      are exact: with qvel = v and qacc = 0, ``mj_comVel`` + ``mj_rnePostConstraint`` give
      the bodies' spatial accelerations (``cacc``), and ``mj_objectAcceleration`` at the sites
      gives each point's classical acceleration (its ω × v term included) and the angular
      acceleration. ``cacc`` starts from −gravity at the world body, a uniform offset that is
      added back (gravity stays untouched in the model).

    ``timings`` (a dict) accumulates seconds in 'position', 'velocity', 'acceleration'.

    ``predictor="secant"`` starts Newton from 2 q[k−1] − q[k−2] instead of q[k−1] (about one
    step fewer per sample on evenly sampled paths; same solution).
    Angles are not wrapped: they move continuously from the start configuration.

    Returns ``q``, ``v``, ``a`` (N, 12) in :data:`JOINTS` order, ``closure_residual`` (N,)
    and ``tool_error`` (N,) (max |p_A − p_B| and tool-pose error components [m, rad] at the
    returned q) and ``iterations`` (N,) (Newton steps taken, the one past tol included).
    Raises :class:`MujocoIKError` at the first sample where Newton does not converge.
    """
    mujoco = require_mujoco()

    from ..analytic.taskspace import rotation, twist, twist_dot

    clock = _Clock(timings)
    model, data, info = built if built is not None else cached_model(urdf_path)
    tip = info.get("tip_site", -1)
    if tip < 0:
        raise ValueError(f"{info['urdf_path']}: no '{TIP}' frame for the tool tip "
                         "(docs/model.md §3)")
    poses = np.atleast_2d(np.asarray(poses, dtype=float))
    n = len(poses)
    d_poses = np.zeros_like(poses) if d_poses is None else np.atleast_2d(
        np.asarray(d_poses, dtype=float))
    dd_poses = np.zeros_like(poses) if dd_poses is None else np.atleast_2d(
        np.asarray(dd_poses, dtype=float))
    for label, x in (("poses", poses), ("d_poses", d_poses), ("dd_poses", dd_poses)):
        if x.shape != (n, 6):
            raise ValueError(f"{label} has shape {x.shape}, expected ({n}, 6)")
        if not np.all(np.isfinite(x)):
            raise ValueError(f"{label} has non-finite entries")
    if predictor not in ("previous", "secant"):
        raise ValueError(f"predictor must be 'previous' or 'secant', got {predictor!r}")
    qadr, dadr = info["qpos_adr"], info["dof_adr"]
    if not np.array_equal(qadr, dadr):  # hinges only: qpos and qvel share addresses
        raise ValueError("qpos and dof addresses differ")
    nv = model.nv
    (sa1, sb1), (sa2, sb2) = info["site_ids"]
    Rdes = rotation(poses)
    Pdes = poses[:, :3]
    tw, twd = twist(poses, d_poses), twist_dot(poses, d_poses, dd_poses)

    # Everything below runs in MuJoCo's dof order; columns are mapped back at the end.
    q = np.zeros(nv)
    q[qadr] = (home_configuration(urdf_path=info["urdf_path"]) if q_start is None
               else np.asarray(q_start, dtype=float).reshape(12))
    # e[:9] = P·site_xpos − [0; p_des]; the orientation error log(R_tip R_desᵀ) = R_des·r with
    # r from mju_subQuat(q_tip, q_des) (q_des·exp(r) = q_tip).
    P = np.zeros((9, model.nsite, 3))
    for rows, site, sign in ((0, sa1, 1.0), (0, sb1, -1.0), (3, sa2, 1.0), (3, sb2, -1.0),
                             (6, tip, 1.0)):
        P[rows:rows + 3, site] += sign * np.eye(3)
    P = P.reshape(9, -1)
    Pd = np.zeros((n, 9))
    Pd[:, 6:] = Pdes
    Rflat = np.ascontiguousarray(Rdes.reshape(n, 9))
    Qdes = np.empty((n, 4))
    for k in range(n):
        mujoco.mju_mat2Quat(Qdes[k], Rflat[k])

    Q, Ks = np.empty((n, nv)), np.empty((n, 12, nv))
    res, tool_err, iters = np.empty(n), np.empty(n), np.empty(n, dtype=int)
    K, jB = np.zeros((12, nv)), np.zeros((3, nv))
    H, g, step = np.empty((nv, nv)), np.empty(nv), np.empty(nv)
    e = np.empty(12)
    kin, com, jac = mujoco.mj_kinematics, mujoco.mj_comPos, mujoco.mj_jacSite
    mTm, mTv = mujoco.mju_mulMatTMat, mujoco.mju_mulMatTVec
    chol, chol_solve, norm = mujoco.mju_cholFactor, mujoco.mju_cholSolve, mujoco.mju_norm
    xpos, xmat_tip, qpos = data.site_xpos.reshape(-1), data.site_xmat[tip], data.qpos
    K1, K2, Kt, Kr = K[0:3], K[3:6], K[6:9], K[9:12]
    e9, ew = e[:9], e[9:]
    mat2quat, subquat, rotate = mujoco.mju_mat2Quat, mujoco.mju_subQuat, mujoco.mju_mulMatVec3
    quat, r = np.empty(4), np.empty(3)

    def jacobian():  # K at the kinematics in data
        jac(model, data, K1, None, sa1)
        jac(model, data, jB, None, sb1)
        np.subtract(K1, jB, out=K1)
        jac(model, data, K2, None, sa2)
        jac(model, data, jB, None, sb2)
        np.subtract(K2, jB, out=K2)
        jac(model, data, Kt, Kr, tip)

    for k in range(n):
        if predictor == "secant" and k >= 2:
            q = 2.0 * Q[k - 1] - Q[k - 2]
        Pd_k, qd_k, Rd_k = Pd[k], Qdes[k], Rflat[k]
        polished = False
        for it in range(max_iter + 1):
            qpos[:] = q
            kin(model, data)
            com(model, data)
            np.subtract(P @ xpos, Pd_k, out=e9)
            mat2quat(quat, xmat_tip)
            subquat(r, quat, qd_k)
            rotate(ew, Rd_k, r)  # log(R_tip R_desᵀ), world axes
            err = np.abs(e).max()
            if polished:
                break
            if err <= tol:
                polished = True  # one more step: round-off level
            elif it == max_iter:
                raise MujocoIKError(
                    f"sample {k}: Newton did not converge to pose {np.round(poses[k], 6).tolist()}"
                    f" in {max_iter} steps: closure residual {np.abs(e[:6]).max():.3g} m, tool "
                    f"error {np.abs(e[6:]).max():.3g} (m/rad)", sample=k, residual=float(err))
            if not polished or it == 0:  # the last step past tol reuses K (round-off level)
                jacobian()
            # K is square and well conditioned away from singularities (cond ≈ 20–45 on the
            # thesis curve): normal equations with MuJoCo's dense Cholesky, far cheaper than
            # numpy's solve for one 12 × 12 system; least squares if the factor is singular.
            mTm(H, K, K)
            mTv(g, K, e)
            if chol(H, 0.0) == nv:
                chol_solve(step, H, g)
            else:
                step[:] = np.linalg.lstsq(K, e, rcond=None)[0]
            size = norm(step)  # ≥ max |step|: damp only when needed
            if size > IK_MAX_STEP:
                big = np.abs(step).max()
                if big > IK_MAX_STEP:
                    step *= IK_MAX_STEP / big
            q = q - step
        jacobian()  # data holds the kinematics at the returned q; K was one step behind
        Q[k], Ks[k] = q, K
        res[k], tool_err[k], iters[k] = np.abs(e[:6]).max(), np.abs(e[6:]).max(), it
    clock.lap("position")

    rhs = np.zeros((n, 12, 1))
    rhs[:, 6:, 0] = tw
    V = np.linalg.solve(Ks, rhs)[:, :, 0]
    clock.lap("velocity")

    drift = np.empty((n, 12))
    acc6 = np.empty(6)
    sites = (sa1, sb1, sa2, sb2, tip)
    for k in range(n):
        site_drifts(model, data, sites, Q[k], V[k], drift[k], acc6)
    rhs = -drift
    rhs[:, 6:] += twd
    A = np.linalg.solve(Ks, rhs[:, :, None])[:, :, 0]
    clock.lap("acceleration")
    return dict(q=Q[:, dadr], v=V[:, dadr], a=A[:, dadr], closure_residual=res,
                tool_error=tool_err, iterations=iters)


def pipeline_mujoco(poses, d_poses=None, dd_poses=None, timings: dict | None = None,
                    q_start=None, urdf_path=None, built=None, tol: float = IK_TOL,
                    **ik_options) -> dict:
    """The complete MuJoCo peer path: :func:`inverse_kinematics_mujoco` then
    :func:`inverse_dynamics_mujoco`. Returns the keys of both (``q``, ``v``, ``a``,
    ``closure_residual``, ``tool_error``, ``iterations``, ``tau``, ``closure_forces``, ``tree``,
    ``residual``, ``residual_vec``); ``timings`` also gets 'dynamics'. ``ik_options``:
    ``max_iter``, ``predictor``."""
    built = built if built is not None else cached_model(urdf_path)
    ik = inverse_kinematics_mujoco(poses, d_poses, dd_poses, q_start=q_start, built=built,
                                   tol=tol, timings=timings, **ik_options)
    clock = _Clock(timings)
    dyn = inverse_dynamics_mujoco(ik["q"], ik["v"], ik["a"], built=built)
    clock.lap("dynamics")
    return {**ik, **dyn}


__all__ = ["JOINTS", "ACTUATED", "MujocoIKError", "build_mujoco",
           "home_configuration",
           "inverse_dynamics_mujoco", "inverse_kinematics_mujoco", "pipeline_mujoco", "read_urdf"]
