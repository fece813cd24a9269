"""Distance to singularities (docs/model.md §12): wrist, parallel (passive-joint constraint
Jacobian) and serial (actuator-rate → tool-twist map) conditioning, and the margin checks."""
from __future__ import annotations

import numpy as np

from .errors import BranchFlipError, SingularityError

SINGULARITY_MARGIN = 1e-3  # default smallest singular value allowed (parallel and serial)
WRIST_MARGIN = 0.05  # default smallest |sin θ1716| allowed (≈ 2.9°)
BRANCH_TOL = 0.05  # rad, largest departure from the trapezoid prediction between samples


def sigma_min(A):
    """Smallest singular value of each (6 × 6) matrix, from the Gram matrix's eigenvalues."""
    return np.sqrt(np.maximum(np.linalg.eigvalsh(np.swapaxes(A, -1, -2) @ A)[..., 0], 0.0))


def actuator_velocity_map(Jc: np.ndarray, actuated_v, passive_v) -> np.ndarray:
    """N (..., nv, 6) with v = N q̇_act on the closed loops: Jc_p q̇_p = −Jc_a q̇_act."""
    N = np.zeros(Jc.shape[:-2] + (Jc.shape[-1], len(actuated_v)))
    N[..., actuated_v, :] = np.eye(len(actuated_v))
    N[..., passive_v, :] = -np.linalg.solve(Jc[..., passive_v], Jc[..., actuated_v])
    return N


def conditioning(K: np.ndarray, actuated_v, passive_v):
    """σ_min of the passive-joint constraint Jacobian (parallel singularity) and of the
    actuator-rate → tool-twist map (serial singularity), from K = [Jc; J_tool] (..., 12, nv)."""
    Jc, Jt = K[..., :6, :], K[..., 6:, :]
    return (sigma_min(Jc[..., passive_v]),
            sigma_min(Jt @ actuator_velocity_map(Jc, actuated_v, passive_v)))


def check_margins(robot, r, singularity_margin, wrist_margin, branch_tol):
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
