"""The thesis' Euler–Lagrange dynamics in task coordinates (docs/model.md §8, thesis §3.3–3.7).

q = (x, y, z, ψ, θ, φ). For each of the 9 moving bodies k, v_G = M_v(q) q̇ and ω = M_ω(q) q̇
(world frame). The M's are exact: the closed-form IK (docs/model.md §7) run on jets whose derivative
directions are the unit vectors e_j with q̈ = 0 (column j of M = ∂/∂q_j). A 7th direction carrying
the actual q̇ (still q̈ = 0) gives v, ω and Ṁ_v q̇, Ṁ_ω q̇ in the same pass.

    D(q)     = Σ m M_vᵀ M_v + M_ωᵀ I_w M_ω,             I_w = R I Rᵀ
    V(q,q̇)q̇ = Σ m M_vᵀ (Ṁ_v q̇) + M_ωᵀ (I_w Ṁ_ω q̇ + ω × I_w ω)
    C(q)     = ∂U/∂q = −Σ m M_vᵀ g,                      g = (0, 0, −9.81)
    Q        = D q̈ + V q̇ + C = J_τᵀ τ                  (3.152)–(3.154)

V q̇ is the projection of the rate of momentum minus D q̈ (Kane/Jourdain form); it equals the
Lagrangian Ḋ q̇ − ½ ∂(q̇ᵀ D q̇)/∂q because ∂v/∂q̇ = M_v and d/dt(∂v/∂q̇) = ∂v/∂q (the "cancellation
of dots"); the tests check this identity against finite differences of D(q).
"""
from __future__ import annotations

import numpy as np

from ..analytic.closed_form import as_poses, body_states, direction_jet, vee_skew
from ..analytic.jet import Jet
from ..names import ACTUATED, BODIES

GRAVITY = np.array([0.0, 0.0, -9.81])


def _terms(params, poses, d_poses=None, wrist_margin=0.0):
    """D, V q̇, C, J_τ, K, U for (N, 6) poses; V q̇ and K need d_poses (else zero).

    Two jet passes: first order along e_1..e_6 (the M's, J_τ), and second order along the
    actual q̇ with q̈ = 0 (v, ω and Ṁ_v q̇, Ṁ_ω q̇).
    """
    x = as_poses(poses)
    n = x.shape[0]
    unit, q = body_states(params, direction_jet(x), wrist_margin)
    moving = d_poses is not None
    if moving:
        along, _ = body_states(params, Jet(x, as_poses(d_poses), np.zeros_like(x)),
                                wrist_margin)
    D = np.zeros((n, 6, 6))
    C, Vqd, K, U = np.zeros((n, 6)), np.zeros((n, 6)), np.zeros(n), np.zeros(n)
    for name in BODIES:
        b = params.body(name)
        R, r = unit[name]
        Rv = R.v[:, 0]
        Rt = np.swapaxes(Rv, -1, -2)
        Iw = Rv @ b.inertia_matrix @ Rt
        Mv = r.d  # (N, 6, 3): row j = ∂r_G/∂q_j, i.e. M_vᵀ
        Mw = vee_skew(R.d @ Rt[:, None])  # (N, 6, 3): row j = vee(∂R/∂q_j Rᵀ), i.e. M_ωᵀ
        D += b.mass * Mv @ np.swapaxes(Mv, -1, -2) + Mw @ Iw @ np.swapaxes(Mw, -1, -2)
        C -= b.mass * Mv @ GRAVITY
        U -= b.mass * r.v[:, 0] @ GRAVITY
        if moving:
            R2, r2 = along[name]
            v, w = r2.d, vee_skew(R2.d @ Rt)
            Mdv = r2.dd  # Ṁ_v q̇ (q̈ = 0)
            Mdw = vee_skew(R2.dd @ Rt)  # Ṁ_ω q̇
            Iww = np.einsum("nij,nj->ni", Iw, w)
            h = np.einsum("nij,nj->ni", Iw, Mdw) + np.cross(w, Iww)
            Vqd += np.einsum("nij,nj->ni", Mv, b.mass * Mdv) + np.einsum("nij,nj->ni", Mw, h)
            K += 0.5 * (b.mass * np.einsum("ni,ni->n", v, v) + np.einsum("ni,ni->n", w, Iww))
    J_tau = np.stack([q[a].d for a in ACTUATED], axis=-2)
    return {"D": D, "Vqd": Vqd, "C": C, "J_tau": J_tau, "K": K, "U": U}


def _solve_T(J_tau, Q):
    """τ = J_τ⁻ᵀ Q, batched."""
    return np.linalg.solve(np.swapaxes(J_tau, -1, -2), Q[..., None])[..., 0]


def inverse_dynamics(params, poses, d_poses, dd_poses, wrist_margin: float = 0.0) -> dict:
    """Actuator torques along a task trajectory by (3.154) with all six actuators (docs/model.md
    §6, §8): the thesis' method, numpy only, independent of Pinocchio.

    Parameters
    ----------
    params : Params
        The model's numbers (:func:`~pollard_pin.load_params`, or ``robot.params``).
    poses, d_poses, dd_poses : ndarray
        Tool poses (N, 6) (x, y, z [m], ψ, θ, φ [rad]) and their first and second time
        derivatives.
    wrist_margin : float, optional
        The smallest ``|sin θ1716|`` allowed by the closed-form IK (default 0).

    Returns
    -------
    dict
        ``tau`` (N, 6) in :attr:`Robot.actuated` order [N·m]; ``D`` (N, 6, 6), ``Vqd``,
        ``C``, ``Q`` (N, 6): the terms of D q̈ + V q̇ + C = Q = J_τᵀ τ; ``J_tau``
        (N, 6, 6); ``qd_act`` = J_τ q̇ (N, 6); ``K``, ``U`` (N,) energies [J].

    Examples
    --------
    The thesis' method and Pinocchio agree on the torques to round-off:

    >>> import numpy as np
    >>> import pollard_pin as pp
    >>> from pollard_pin.crosscheck import euler_lagrange
    >>> robot = pp.load()
    >>> traj = pp.thesis_trajectory(samples=201)
    >>> tau = euler_lagrange.inverse_dynamics(robot.params, traj.poses, traj.d_poses,
    ...                                       traj.dd_poses)["tau"]
    >>> ours = pp.run_pipeline(robot, traj).dynamics.tau
    >>> bool(np.abs(tau - ours).max() < 1e-12)                     # N·m; 3e-15 achieved
    True
    """
    qd, qdd = as_poses(d_poses), as_poses(dd_poses)
    out = _terms(params, poses, qd, wrist_margin)
    out["Q"] = np.einsum("nij,nj->ni", out["D"], qdd) + out["Vqd"] + out["C"]
    out["tau"] = _solve_T(out["J_tau"], out["Q"])
    out["qd_act"] = np.einsum("nij,nj->ni", out["J_tau"], qd)
    return out


def mass_matrix(params, poses) -> np.ndarray:
    """The task-space mass matrix D(q) of docs/model.md §8.

    Parameters
    ----------
    params : Params
        The model's numbers.
    poses : ndarray
        Tool poses (N, 6).

    Returns
    -------
    ndarray
        (N, 6, 6), symmetric positive definite away from singularities [kg, kg·m, kg·m²].
    """
    return _terms(params, poses)["D"]


def energy(params, poses, d_poses):
    """Kinetic and gravitational potential energy (U = −Σ m gᵀ r_G) along a task trajectory.

    Parameters
    ----------
    params : Params
        The model's numbers.
    poses, d_poses : ndarray
        Tool poses (N, 6) and their rates.

    Returns
    -------
    K, U : ndarray
        Each (N,) [J].
    """
    t = _terms(params, poses, as_poses(d_poses))
    return t["K"], t["U"]


def gravity_torques(params, poses) -> np.ndarray:
    """Static actuator torques τ = J_τ⁻ᵀ ∂U/∂q: what holds the robot still at each pose.

    Parameters
    ----------
    params : Params
        The model's numbers.
    poses : ndarray
        Tool poses (N, 6).

    Returns
    -------
    ndarray
        (N, 6) [N·m], :attr:`Robot.actuated` order.
    """
    t = _terms(params, poses)
    return _solve_T(t["J_tau"], t["C"])


def three_actuator_analysis(params, poses, d_poses, dd_poses) -> dict:
    """What (3.154) gives with the thesis' three base actuators only (docs/model.md §6).

    J_τ is then 3×6 and J_τ⁻ᵀ does not exist: J_τᵀ τ = Q is 6 equations in 3 unknowns. This
    returns the least-squares torques τ_ls = pinv(J_3ᵀ) Q, the residual r = Q − J_3ᵀ τ_ls (the part
    of Q no base torque can produce), the wrist share Q_w = J_wᵀ τ_w of the six-actuator
    solution, the singular values of J_3, and a 'summary' dict of headline numbers.
    """
    full = inverse_dynamics(params, poses, d_poses, dd_poses)
    Q, Jt = full["Q"], full["J_tau"]
    J3, Jw = Jt[:, :3], Jt[:, 3:]
    tau_ls = np.einsum("nij,nj->ni", np.linalg.pinv(np.swapaxes(J3, -1, -2)), Q)
    resid = Q - np.einsum("nji,nj->ni", J3, tau_ls)
    Qw = np.einsum("nji,nj->ni", Jw, full["tau"][:, 3:])
    qn = np.linalg.norm(Q, axis=1)
    rel = np.linalg.norm(resid, axis=1) / np.where(qn > 0, qn, np.nan)
    summary = {
        "rank_J3": int(np.linalg.matrix_rank(J3[0])),
        "max_rel_residual": float(np.nanmax(rel)),
        "median_rel_residual": float(np.nanmedian(rel)),
        "max_abs_residual": np.abs(resid).max(axis=0).tolist(),
        "peak_tau_ls": np.abs(tau_ls).max(axis=0).tolist(),
        "peak_tau6_base": np.abs(full["tau"][:, :3]).max(axis=0).tolist(),
        "max_abs_tau_ls_minus_tau6_base": np.abs(tau_ls - full["tau"][:, :3]).max(axis=0).tolist(),
        "peak_tau6_wrist": np.abs(full["tau"][:, 3:]).max(axis=0).tolist(),
    }
    return {"tau_ls": tau_ls, "residual": resid, "rel_residual": rel, "Q": Q, "Q_wrist": Qw,
            "tau6": full["tau"], "singular_values_J3": np.linalg.svd(J3, compute_uv=False),
            "summary": summary}


__all__ = ["GRAVITY", "inverse_dynamics", "mass_matrix", "energy", "gravity_torques",
           "three_actuator_analysis"]
