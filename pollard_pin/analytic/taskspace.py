"""Task coordinates (docs/model.md §2): q = (x, y, z, ψ, θ, φ), R = Rx(θ) Ry(ψ) Rz(φ).

Vectorised over samples: arrays of shape (N, 6) in, (N, ...) out. ω is the tool's angular
velocity in world axes.
"""
from __future__ import annotations

import numpy as np

from ..errors import InputError

TASK_NAMES = ("x", "y", "z", "psi", "theta", "phi")
# Largest |component| accepted (m, rad, and per s, per s²): a robot of ~1 m never needs more,
# and squares of larger values lose every digit of the closed form's C = |d|² + r² − L²
# (docs/model.md §7) long before they overflow. Beyond it the input is a unit or data error.
MAX_ABS_TASK = 1e6
_UNITS = {"": ("m", "rad"), "d_": ("m/s", "rad/s"), "dd_": ("m/s²", "rad/s²")}


class TaskInputError(InputError):
    """An invalid task-space input (numpy-only layer; the pipeline re-raises it as
    :class:`~pollard_pin.kinematics.errors.KinematicsInputError` with the sample's time).
    ``column`` names the entry (e.g. ``"d_psi"``, ``"wrist_margin"``), ``sample`` its row."""

    def __init__(self, detail: str, sample: int | None = None, column: str | None = None,
                 value: float | None = None):
        super().__init__(detail if sample is None else f"sample {sample}: {detail}")
        self.detail, self.sample, self.column, self.value = detail, sample, column, value


def check_task_array(arr, prefix: str = "") -> None:
    """Raise :class:`TaskInputError` at the first non-finite or absurd (> MAX_ABS_TASK)
    entry of an (N, 6) pose (``prefix`` ""), rate ("d_") or acceleration ("dd_") array,
    naming the column (e.g. ``d_psi``), the sample and its value."""
    a = np.asarray(arr, dtype=float)
    bad = ~(np.abs(a) <= MAX_ABS_TASK)  # NaN compares False: caught here too
    if not bad.any():
        return
    k, c = (int(i) for i in np.argwhere(bad)[0])
    v, name = a[k, c], prefix + TASK_NAMES[c]
    if np.isfinite(v):
        unit = _UNITS.get(prefix, ("", ""))[c >= 3]
        msg = (f"{name} = {v:.6g} is absurd: |{name}| > {MAX_ABS_TASK:g} {unit} "
               "(a unit or data error?)")
    else:
        msg = f"{name} = {v} is not a finite number"
    raise TaskInputError(msg, sample=k, column=name, value=float(v))


def rotation(pose: np.ndarray) -> np.ndarray:
    """R = Rx(θ) Ry(ψ) Rz(φ) for poses (..., 6) → (..., 3, 3)."""
    pose = np.asarray(pose, dtype=float)
    psi, th, phi = pose[..., 3], pose[..., 4], pose[..., 5]
    cs, ss, ct, st = np.cos(psi), np.sin(psi), np.cos(th), np.sin(th)
    cp, sp = np.cos(phi), np.sin(phi)
    R = np.empty(pose.shape[:-1] + (3, 3))
    R[..., 0, 0] = cs * cp
    R[..., 0, 1] = -cs * sp
    R[..., 0, 2] = ss
    R[..., 1, 0] = st * ss * cp + ct * sp
    R[..., 1, 1] = -st * ss * sp + ct * cp
    R[..., 1, 2] = -st * cs
    R[..., 2, 0] = -ct * ss * cp + st * sp
    R[..., 2, 1] = ct * ss * sp + st * cp
    R[..., 2, 2] = ct * cs
    return R


def turn(rx: float, ry: float, rz: float) -> np.ndarray:
    """R = Rx(rx)·Ry(ry)·Rz(rz) for angles [deg] about the world axes (a part's or a cell
    robot's base rotation): the tool pose's composition, docs/model.md §2."""
    return rotation(np.radians([0.0, 0.0, 0.0, ry, rx, rz]))


def angles_from_rotation(R: np.ndarray) -> np.ndarray:
    """(ψ, θ, φ) of R = Rx(θ) Ry(ψ) Rz(φ), with ψ in [−π/2, π/2]."""
    psi = np.arctan2(R[..., 0, 2], np.hypot(R[..., 0, 0], R[..., 0, 1]))
    th = np.arctan2(-R[..., 1, 2], R[..., 2, 2])
    phi = np.arctan2(-R[..., 0, 1], R[..., 0, 0])
    return np.stack([psi, th, phi], axis=-1)


def pose_from_se3(M) -> np.ndarray:
    """Task pose (6,) of a pinocchio.SE3."""
    return np.concatenate([M.translation, angles_from_rotation(M.rotation)])


def se3_from_pose(pose):
    import pinocchio as pin

    pose = np.asarray(pose, dtype=float)
    return pin.SE3(rotation(pose), pose[:3].copy())


def rate_matrix(pose: np.ndarray) -> np.ndarray:
    """E with ω = E · (ψ̇, θ̇, φ̇): columns Rx(θ)e_y, e_x, Rx(θ)Ry(ψ)e_z. Shape (..., 3, 3)."""
    pose = np.asarray(pose, dtype=float)
    psi, th = pose[..., 3], pose[..., 4]
    E = np.zeros(pose.shape[:-1] + (3, 3))
    E[..., 1, 0], E[..., 2, 0] = np.cos(th), np.sin(th)
    E[..., 0, 1] = 1.0
    E[..., 0, 2] = np.sin(psi)
    E[..., 1, 2] = -np.sin(th) * np.cos(psi)
    E[..., 2, 2] = np.cos(th) * np.cos(psi)
    return E


def rate_matrix_dot(pose: np.ndarray, dpose: np.ndarray) -> np.ndarray:
    """Ė, the time derivative of :func:`rate_matrix` along ``dpose``."""
    psi, th = pose[..., 3], pose[..., 4]
    dpsi, dth = dpose[..., 3], dpose[..., 4]
    Ed = np.zeros(np.shape(pose)[:-1] + (3, 3))
    Ed[..., 1, 0], Ed[..., 2, 0] = -np.sin(th) * dth, np.cos(th) * dth
    Ed[..., 0, 2] = np.cos(psi) * dpsi
    Ed[..., 1, 2] = -np.cos(th) * np.cos(psi) * dth + np.sin(th) * np.sin(psi) * dpsi
    Ed[..., 2, 2] = -np.sin(th) * np.cos(psi) * dth - np.cos(th) * np.sin(psi) * dpsi
    return Ed


def twist(pose: np.ndarray, dpose: np.ndarray) -> np.ndarray:
    """Tool twist (v, ω), world axes, (..., 6), from pose rates."""
    w = np.einsum("...ij,...j->...i", rate_matrix(pose), dpose[..., 3:])
    return np.concatenate([dpose[..., :3], w], axis=-1)


def twist_dot(pose: np.ndarray, dpose: np.ndarray, ddpose: np.ndarray) -> np.ndarray:
    """Tool point acceleration and angular acceleration (a, ω̇), world axes: ω̇ = E ë + Ė ė."""
    wd = (np.einsum("...ij,...j->...i", rate_matrix(pose), ddpose[..., 3:])
          + np.einsum("...ij,...j->...i", rate_matrix_dot(pose, dpose), dpose[..., 3:]))
    return np.concatenate([ddpose[..., :3], wd], axis=-1)


def euler_rates(pose: np.ndarray, tw: np.ndarray) -> np.ndarray:
    """Inverse of :func:`twist`: pose rates (..., 6) from (v, ω). Singular where cos ψ = 0."""
    rates = np.linalg.solve(rate_matrix(pose), tw[..., 3:, None])[..., 0]
    return np.concatenate([tw[..., :3], rates], axis=-1)
