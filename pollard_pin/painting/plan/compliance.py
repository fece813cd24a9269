"""How far the gun gives along a paint program (docs/model.md §27.7): the compliant drives'
deflection d = J K⁻¹ (Jᵀ W − τ_g) of :mod:`pollard_pin.dynamics.drives.stiffness` at every sample
of the program, under the robot's weight and the spray's recoil, split along the gun's axis.

The recoil is a force of ``recoil`` [N] × the trigger at the tip along −a (a = R e_x the
spray axis): the jet's momentum leaves the nozzle along a and pushes the gun back. A round jet
has no moment about its axis and no side force, so one number states it.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...analytic.taskspace import angles_from_rotation, rotation
from ...dynamics.drives.stiffness import check_stiffness, deflection_at
from ...errors import InputError
from ...paths.trajectory import Trajectory
from ..errors import ReachError
from ..job import MAX_RECOIL
from .checks import reach

CHUNK = 4096  # samples per block: the IK's and the maps' arrays stay some 50 MB


@dataclass(frozen=True)
class ProgramDeflection:
    """Per sample of a program (N samples, the robot's base frame): ``deflection`` (N, 6) the
    tip's translation dx, dy, dz [m] and the gun's rotation vector rx, ry, rz [rad];
    ``axis`` (N, 3) the rigid spray axis; ``standoff`` (N,) the tip's translation along the
    axis [m] (> 0: towards the surface, the standoff shrinks by it); ``lateral`` (N,) the
    translation across the axis [m]; ``tilt`` (N,) the rotation's part perpendicular to the
    axis [rad] (the part about it does not move the spray)."""

    deflection: np.ndarray
    axis: np.ndarray
    standoff: np.ndarray
    lateral: np.ndarray
    tilt: np.ndarray


def recoil_wrench(axes, spray, recoil: float) -> np.ndarray:
    """The recoil wrench (N, 6) on the tool (force at the tip, world axes; no moment):
    −recoil × trigger × a."""
    w = np.zeros((len(axes), 6))
    w[:, :3] = -recoil * np.asarray(spray, dtype=float)[:, None] * axes
    return w


def program_deflection(robot, trajectory: Trajectory, stiffness, spray=None,
                       recoil: float = 0.0) -> ProgramDeflection:
    """The gun's deflection at every sample of a paint program under the weight and the
    spray's recoil along −a, the spray axis (docs/model.md §27.2, §27.7).

    Parameters
    ----------
    robot : Robot
        The model (:func:`pollard_pin.load`).
    trajectory : Trajectory
        The program, in the robot's base frame.
    stiffness : ArrayLike
        The six drives' stiffnesses [N·m/rad].
    spray : ArrayLike or None, optional
        The trigger per sample, 0…1 (default 1 throughout).
    recoil : float, optional
        The spray's push back on the gun [N] while the trigger is on (default 0).

    Returns
    -------
    ProgramDeflection
        Per sample the ``deflection`` (N, 6) [m, rad], the rigid spray ``axis`` (N, 3), the
        ``standoff`` (N,) [m] change along it (> 0: towards the surface), the ``lateral``
        (N,) [m] translation across it and the ``tilt`` (N,) [rad].

    Raises
    ------
    KinematicsError
        A pose out of reach or singular, naming the sample (the IK is ``run``'s).
    StiffnessError
        A stiffness missing or invalid.
    """
    k = check_stiffness(stiffness)
    poses = np.asarray(trajectory.poses, dtype=float)
    n = len(poses)
    spray = np.ones(n) if spray is None else np.asarray(spray, dtype=float)
    if spray.shape != (n,) or not np.all((spray >= 0) & (spray <= 1)):
        raise InputError(f"spray: one trigger fraction in [0, 1] per sample ({n}), got shape "
                         f"{spray.shape}")
    if isinstance(recoil, bool) or not 0 <= recoil <= MAX_RECOIL:  # NaN fails too
        raise InputError(f"recoil = {recoil!r}: expected a force of 0 to {MAX_RECOIL:g} N")
    axes = rotation(poses)[:, :, 0]
    d = np.empty((n, 6))
    for start in range(0, n, CHUNK):
        sl = slice(start, start + CHUNK)
        try:
            q = reach(robot, poses[sl]).q
        except ReachError as exc:  # the sample counted from the program's start
            raise ReachError(str(exc), start + exc.sample, exc.pose) from None
        d[sl] = deflection_at(robot, q, k, recoil_wrench(axes[sl], spray[sl], recoil))
    along = np.einsum("ij,ij->i", d[:, :3], axes)
    turn = np.einsum("ij,ij->i", d[:, 3:], axes)
    lateral = np.linalg.norm(d[:, :3] - along[:, None] * axes, axis=1)
    tilt = np.linalg.norm(d[:, 3:] - turn[:, None] * axes, axis=1)
    return ProgramDeflection(d, axes, along, lateral, tilt)


def deflected_poses(poses, deflection) -> np.ndarray:
    """The poses (N, 6) moved by the deflection (N, 6): the tip by (dx, dy, dz), the
    orientation turned by the rotation vector (rx, ry, rz), world axes: R' = exp(r) R."""
    poses = np.asarray(poses, dtype=float)
    d = np.asarray(deflection, dtype=float)
    r = d[:, 3:]
    angle = np.linalg.norm(r, axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        u = np.where(angle[:, None] > 0, r / angle[:, None], 0.0)
    c, s = np.cos(angle)[:, None, None], np.sin(angle)[:, None, None]
    ux = np.zeros((len(r), 3, 3))
    ux[:, 0, 1], ux[:, 0, 2], ux[:, 1, 2] = -u[:, 2], u[:, 1], -u[:, 0]
    ux -= np.swapaxes(ux, 1, 2)
    # Rodrigues: exp(r) = I + sin θ [u]× + (1 − cos θ) [u]×²
    E = np.eye(3) + s * ux + (1 - c) * (ux @ ux)
    out = poses.copy()
    out[:, :3] += d[:, :3]
    out[:, 3:] = angles_from_rotation(E @ rotation(poses))
    return out


__all__ = ["CHUNK", "ProgramDeflection", "deflected_poses", "program_deflection",
           "recoil_wrench"]
