"""Joint loads by free bodies: Newton–Euler summed over each joint's subtree (docs/model.md §17).

Independent of Pinocchio and of ``data.f``: numpy only, with the closed-form kinematics of
docs/model.md §7 (body CoG accelerations, angular velocities and accelerations exact by jets).
For a tree joint j, the wrench of the parent on the child about the joint origin o_j is what
the subtree S_j needs beyond gravity and the closure forces acting on it::

    F_j = Σ_{b ∈ S_j} m_b (a_b − g) − Σ_{ext on S_j} f
    M_j = Σ_{b ∈ S_j} [I_b α_b + ω_b × I_b ω_b + (r_b − o_j) × m_b (a_b − g)]
          − Σ_{ext on S_j} (p − o_j) × f

(I_b the world inertia about the CoG r_b; the rate of angular momentum about the CoG). The
closure forces are not taken from the inverse dynamics: they solve the six passive-joint
conditions axis · M_j = 0 (θ43, θ54, θ65_i, θ76_i), linear in λ — the free-body form of
Jc_pᵀ λ = τ_passive (docs/model.md §13).
"""
from __future__ import annotations

import numpy as np

from ..analytic.closed_form import body_kinematics, forward_frames, position_ik
from ..names import BODIES, PASSIVE, TREE_JOINTS
from .euler_lagrange import GRAVITY

# joint → (frame of its origin and axis in forward_frames, axis column, bodies of its subtree)
_CHAIN0 = ("platform", "wrist1", "wrist2", "gun")
SUBTREES = {
    "theta21": ("arm0", 1, ("arm0",) + _CHAIN0),
    "theta43": ("cross0", 1, _CHAIN0),
    "theta54": ("platform", 2, _CHAIN0),
    "theta1615": ("wrist1", 0, ("wrist1", "wrist2", "gun")),
    "theta1716": ("wrist2", 2, ("wrist2", "gun")),
    "theta1817": ("gun", 0, ("gun",)),
    **{f"theta21_{i}": (f"arm_{i}", 2, (f"arm_{i}", f"link_{i}")) for i in (1, 2)},
    **{f"theta65_{i}": (f"cross_{i}", 1, (f"link_{i}",)) for i in (1, 2)},
    **{f"theta76_{i}": (f"link_{i}", 2, (f"link_{i}",)) for i in (1, 2)},
}


def _closures_on(joint: str, bodies) -> list[tuple[int, float, str]]:
    """(leg index, sign, point frame) of the closure forces acting on a subtree: +λ_i on
    link_i at the ball centre, −λ_i on the platform at A_i (docs/model.md §4)."""
    out = [(i, 1.0, f"closure_link_{i + 1}") for i in range(2) if f"link_{i + 1}" in bodies]
    if "platform" in bodies:
        out += [(i, -1.0, f"closure_platform_{i + 1}") for i in range(2)]
    return out


def joint_loads(params, poses, d_poses, dd_poses, wrist_margin: float = 0.0) -> dict:
    """Loads of the 12 tree joints along a task trajectory, free-body method.

    Returns a dict: ``force``, ``moment`` (N, 12, 3) [N, N·m] — the force of the parent on
    the child and its moment about the joint origin, world axes, joints in ``TREE_JOINTS``
    order; ``axis`` (N, 12, 3); ``closure_forces`` (N, 2, 3) [N], force on link_i.
    """
    kin = body_kinematics(params, poses, d_poses, dd_poses, wrist_margin)
    q = position_ik(params, poses, wrist_margin=wrist_margin)
    frames = forward_frames(params, q[:, :12])
    n = q.shape[0]
    wrench = {}  # body → (f = m(a − g), n = I α + ω × I ω, CoG)
    for name in BODIES:
        b, k = params.body(name), kin[name]
        R = k["R"]
        Iw = R @ b.inertia_matrix @ np.swapaxes(R, -1, -2)
        Iw_w = np.einsum("nij,nj->ni", Iw, k["omega"])
        wrench[name] = (b.mass * (k["a"] - GRAVITY),
                        np.einsum("nij,nj->ni", Iw, k["alpha"]) + np.cross(k["omega"], Iw_w),
                        k["r"])
    point = {f: np.broadcast_to(frames[f][1], (n, 3)) for leg in (1, 2)
             for f in (f"closure_link_{leg}", f"closure_platform_{leg}")}
    F0, M0, axis = (np.zeros((n, 12, 3)) for _ in range(3))
    dM = np.zeros((n, 12, 3, 6))  # ∂M_j/∂λ (the closure terms, linear in λ)
    dF = np.zeros((12, 3, 6))
    for j, joint in enumerate(TREE_JOINTS):
        frame, col, bodies = SUBTREES[joint]
        R, o = frames[frame]
        o = np.broadcast_to(o, (n, 3))
        axis[:, j] = R[:, :, col]
        for body in bodies:
            f, nb, r = wrench[body]
            F0[:, j] += f
            M0[:, j] += nb + np.cross(r - o, f)
        for i, sign, p in _closures_on(joint, bodies):
            # the moment term −(p − o) × (sign·λ_i), column by column of a 3 × 3 block
            d = point[p] - o
            for c in range(3):
                e = np.zeros(3)
                e[c] = 1.0
                dM[:, j, :, 3 * i + c] = -sign * np.cross(d, e)
                dF[j, c, 3 * i + c] = -sign
    P = [TREE_JOINTS.index(p) for p in PASSIVE]
    # axis · (M0 + dM λ) = 0 at the passive joints: 6 equations, 6 unknowns per sample.
    A = np.einsum("npi,npik->npk", axis[:, P], dM[:, P])
    b = -np.einsum("npi,npi->np", axis[:, P], M0[:, P])
    lam = np.linalg.solve(A, b[..., None])[..., 0]
    force = F0 + np.einsum("jik,nk->nji", dF, lam)
    moment = M0 + np.einsum("njik,nk->nji", dM, lam)
    return {"force": force, "moment": moment, "axis": axis, "closure_forces": lam.reshape(n, 2, 3),
            "joints": TREE_JOINTS}


def static_loads(params, poses) -> dict:
    """The same at rest (v = a = 0): subtree weights and closure forces only."""
    z = np.zeros_like(np.asarray(poses, dtype=float))
    return joint_loads(params, poses, z, z)


__all__ = ["joint_loads", "static_loads", "SUBTREES", "PASSIVE"]
