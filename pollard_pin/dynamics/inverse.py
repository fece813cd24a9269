"""Closed-loop inverse dynamics with Pinocchio (docs/model.md §13).

RNEA on the open tree, then ``tau_tree = Sᵀ τ + Jcᵀ λ`` (12 × 12, square) for the six actuator
torques τ (docs/model.md §6 order) and the two closure forces λ_i, the force the platform exerts
on ``link_i`` at the ball joint, world axes [N] (docs/model.md §4).
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from functools import cache

import numpy as np
import pinocchio as pin

from ..checks import instance
from ..kinematics.closure import closure_drift
from ..kinematics.errors import SingularityError
from ..kinematics.ik import IKResult
from ..kinematics.singularity import (
    SIGMA_FLOOR,
    actuator_velocity_map,
    sigma_range,
    solve_small,
    solve_stack,
)
from ..kinematics.tree import cross, joint_motion
from ..model.build import Robot, check_robot, constraint_jacobian
from ..timing import Stopwatch


@dataclass(frozen=True)
class JointLosses:
    """Optional joint friction and rotor inertia, per tree joint (default zero; the thesis gives
    none).

    ``viscous`` [N·m·s/rad] and ``armature`` [kg·m²] are (12,) arrays or scalars; ``coulomb``
    [N·m] acts as ``coulomb · tanh(q̇ / coulomb_speed)``.
    """

    viscous: np.ndarray | float = 0.0
    coulomb: np.ndarray | float = 0.0
    armature: np.ndarray | float = 0.0
    coulomb_speed: float = 1e-3

    def torque(self, v: np.ndarray, a: np.ndarray) -> np.ndarray:
        return (np.asarray(self.armature) * a + np.asarray(self.viscous) * v
                + np.asarray(self.coulomb) * np.tanh(v / self.coulomb_speed))


@dataclass
class DynamicsResult:
    t: np.ndarray
    tau: np.ndarray  # (N, 6) actuator torques [N·m], docs/model.md §6 order
    closure_forces: np.ndarray  # (N, 2, 3) force of the platform on link_i [N], world axes
    tau_tree: np.ndarray  # (N, 12) open-tree RNEA torques (losses included)
    actuator_velocity: np.ndarray  # (N, 6) [rad/s]
    kinetic: np.ndarray | None  # (N,) [J]; None when computed with energies=False
    potential: np.ndarray | None  # (N,) [J], gravity (docs/model.md §2)
    actuated: tuple[str, ...]

    @property
    def power(self) -> np.ndarray:
        """Actuator mechanical power τ·q̇ [W], (N, 6)."""
        return self.tau * self.actuator_velocity

    @property
    def work(self) -> np.ndarray:
        """Cumulative actuator work [J] by the trapezoid rule, (N, 6), zero at the start."""
        p = self.power
        w = np.zeros_like(p)
        w[1:] = np.cumsum(0.5 * (p[1:] + p[:-1]) * np.diff(self.t)[:, None], axis=0)
        return w

    @property
    def energy(self) -> np.ndarray:
        """Total mechanical energy K + U [J] of all bodies."""
        if self.kinetic is None:
            raise ValueError("energies were not computed (inverse_dynamics(..., energies=False))")
        return self.kinetic + self.potential

    def columns(self) -> dict[str, np.ndarray]:
        cols = {}
        for prefix, arr in (("tau", self.tau), ("power", self.power), ("work", self.work)):
            cols.update({f"{prefix}_{n}": arr[:, i] for i, n in enumerate(self.actuated)})
        for i in range(2):
            cols.update({f"f{i + 1}_{c}": self.closure_forces[:, i, j]
                         for j, c in enumerate("xyz")})
        if self.kinetic is not None:
            cols.update({"kinetic_energy": self.kinetic, "potential_energy": self.potential})
        return cols



def stacked_energies(model, Q: np.ndarray, V: np.ndarray):
    """Kinetic and potential energy (N,) of every sample at once, as Pinocchio's
    ``computeKineticEnergy`` / ``computePotentialEnergy`` (U = −Σ m gᵀ c), from one pass over
    the model tree in numpy (docs/model.md §13): no Python loop over samples."""
    mo = joint_motion(model, Q, V)
    n = len(Q)
    kinetic, potential = np.zeros(n), np.zeros(n)
    g = np.asarray(model.gravity.linear)
    for j in range(1, model.njoints):
        R, o = mo.R[j], mo.o[j]
        Y = model.inertias[j]
        if Y.mass <= 0.0:
            continue
        c = np.asarray(Y.lever)
        r = R[:, :, 0] * c[0] + R[:, :, 1] * c[1] + R[:, :, 2] * c[2]
        v_c = mo.vo[j] + cross(mo.w[j], r)
        wb = np.einsum("nji,nj->ni", R, mo.w[j])  # body axes: the inertia is constant there
        kinetic += 0.5 * (Y.mass * (v_c * v_c).sum(axis=1)
                          + ((wb @ np.asarray(Y.inertia)) * wb).sum(axis=1))
        potential -= Y.mass * ((o + r) @ g)
    return kinetic, potential


RNEA_THREADS = 2  # OpenMP threads of Pinocchio's batched RNEA
# Fewer samples run on one thread: starting a thread team costs more than it saves there
# (each sample's torques are the same on any thread).
RNEA_TEAM_SAMPLES = 4096


def batched_rnea(model, Q: np.ndarray, V: np.ndarray, A: np.ndarray) -> np.ndarray:
    """Open-tree RNEA torques (N, nv) of every sample: Pinocchio's ``rneaInParallel`` over a
    model pool, one call for the whole stack (no Python loop over samples)."""
    n = len(Q)
    tau = np.empty((model.nv, n), order="F")
    if n:
        threads = rnea_threads() if n >= RNEA_TEAM_SAMPLES else 1
        pool = pin.ModelPool(model, threads)
        pin.rneaInParallel(threads, pool, np.asfortranarray(Q.T), np.asfortranarray(V.T),
                           np.asfortranarray(A.T), tau)
    return tau.T


# GNU OpenMP cannot start a thread team in a process forked after its parent ran one: the
# child hangs in libgomp (seen in the sweep's forked workers after a `run` in the parent).
# One thread needs no team, so a forked child runs the RNEA on one thread.
_TEAM_PID = []  # the process that started an OpenMP team (its first call), if any


def rnea_threads() -> int:
    """OpenMP threads :func:`batched_rnea` may use in this process: RNEA_THREADS, or 1 in a
    child forked after its parent started a team."""
    if not _TEAM_PID:
        _TEAM_PID.append(os.getpid())
    return RNEA_THREADS if _TEAM_PID[0] == os.getpid() else 1


def _parallel_singular(robot: Robot, Jc, k: int, sp=None, sp_max=None, t=None, why=""):
    if sp is None:
        sp, sp_max = (float(x) for x in sigma_range(Jc.reshape((-1,) + Jc.shape[-2:])[k][
            :, robot.passive_v]))
    return SingularityError(
        f"the closure-force system Jc_pᵀ λ = τ_passive is singular{why}: the passive-joint "
        f"constraint Jacobian's smallest singular value {sp:.3g} is below the numerical floor "
        f"{SIGMA_FLOOR:g} × σ_max = {SIGMA_FLOOR * sp_max:.3g} (parallel singularity, "
        "docs/model.md §12)", sigma=sp, chain="parallel",
        sample=k if Jc.ndim > 2 else None,
        time=None if t is None else float(np.atleast_1d(t)[k]))


def split_tree_torques(robot: Robot, Jc: np.ndarray, tau_tree: np.ndarray, t=None):
    """Solve tau_tree = Sᵀτ + Jcᵀλ (stacked (..., 6, nv), (..., nv)) for τ and λ.

    The passive rows alone give Jc_pᵀλ = tau_p (6 × 6); the actuated rows then give τ. Where
    Jc_p is exactly singular, or the result is not finite, raises :class:`SingularityError`
    naming the sample, its time (from ``t``) and σ.
    """
    ia, ip = robot.actuated_v, robot.passive_v
    lam, _ = solve_stack(np.swapaxes(Jc[..., ip], -1, -2), tau_tree[..., ip, None])
    tau = tau_tree[..., ia] - (np.swapaxes(Jc[..., ia], -1, -2) @ lam)[..., 0]
    bad = ~(np.isfinite(tau).all(axis=-1) & np.isfinite(lam).all(axis=(-2, -1)))
    if bad.any():
        raise _parallel_singular(robot, Jc, int(np.argmax(bad.reshape(-1))), t=t,
                                 why=" (torques not finite)")
    return tau, lam[..., 0]


def inverse_dynamics_sample(robot: Robot, q, v, a, losses: JointLosses | None = None,
                            Jc=None):
    """(τ (6,), λ (2, 3), tau_tree (12,)) at one state; ``Jc``: the constraint Jacobian at
    ``q`` if already at hand."""
    model, data = robot.model, robot.data
    tau_tree = pin.rnea(model, data, q, v, a).copy()
    if losses is not None:
        tau_tree += losses.torque(v, a)
    if Jc is None:
        Jc = constraint_jacobian(model, data, robot.constraint_models, robot.constraint_datas,
                                 q)
    sp, sp_max = (float(x) for x in sigma_range(Jc[:, robot.passive_v]))
    if not sp >= SIGMA_FLOOR * sp_max:
        raise _parallel_singular(robot, Jc, 0, sp, sp_max)
    tau, lam = split_tree_torques(robot, Jc, tau_tree)
    return tau, lam.reshape(2, 3), tau_tree


def inverse_dynamics(robot: Robot, ik: IKResult, losses: JointLosses | None = None,
                     energies: bool = True, timings: dict | None = None) -> DynamicsResult:
    """Actuator torques, closure forces and energies along an IK result.

    One RNEA (and, with ``energies``, K and U) per sample; the ``[Sᵀ Jcᵀ]`` systems are solved
    stacked (passive rows first, 6 × 6), reusing the IK's constraint Jacobians when it has them
    (docs/model.md §13).

    Parameters
    ----------
    robot : Robot
        The model (:func:`pollard_pin.load`).
    ik : IKResult
        Joint positions, velocities and accelerations (:func:`pollard_pin.inverse_kinematics`).
    losses : pollard_pin.dynamics.inverse.JointLosses or None, optional
        Joint friction and rotor inertia to add (default none: ideal joints, as the thesis).
    energies : bool, optional
        Also compute the kinetic and potential energies (default True).
    timings : dict or None, optional
        Accumulates the seconds spent per stage.

    Returns
    -------
    pollard_pin.dynamics.inverse.DynamicsResult
        ``tau`` (N, 6) actuator torques [N·m] (:attr:`Robot.actuated` order),
        ``closure_forces`` (N, 2, 3) the force of the platform on each leg at its ball joint
        [N], world axes, the open-tree torques, actuator velocities, energies [J]; ``power``
        [W] and ``work`` [J] as properties.

    Raises
    ------
    SingularityError
        A sample where the closure system is singular (a parallel singularity).

    Examples
    --------
    >>> import pollard_pin as pp
    >>> robot = pp.load()
    >>> traj = pp.thesis_trajectory(duration=20.0, samples=201)
    >>> ik = pp.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    >>> dyn = pp.inverse_dynamics(robot, ik)
    >>> dyn.tau.shape, dyn.closure_forces.shape
    ((201, 6), (201, 2, 3))
    >>> round(float(abs(dyn.tau[:, 0]).max()), 2)      # theta21's peak torque [N·m]
    1.21
    """
    check_robot(robot)
    instance(ik, "ik", IKResult, "an IKResult (pollard_pin.inverse_kinematics)")
    instance(losses, "losses", JointLosses, "a JointLosses", none=True)
    clock = Stopwatch(timings)
    model, data = robot.model, robot.data
    n = len(ik)
    Q, V, A = ik.q, ik.v, ik.a
    tree = batched_rnea(model, Q, V, A)
    K, U = stacked_energies(model, Q, V) if energies else (None, None)
    if losses is not None:
        tree += losses.torque(V, A)
    Jc = ik.constraint_jacobian
    if Jc is None:
        Jc = np.stack([constraint_jacobian(model, data, robot.constraint_models,
                                           robot.constraint_datas, q) for q in Q])
    # Numerically singular Jc_p (docs/model.md §12): the IK measured σ at the same q.
    sp, sp_max = ik.sigma_parallel, getattr(ik, "sigma_parallel_max", None)
    if sp is None or sp_max is None:
        sp, sp_max = sigma_range(Jc[..., robot.passive_v])
    low = np.flatnonzero(~(sp >= SIGMA_FLOOR * sp_max))
    if len(low):
        k = int(low[0])
        raise _parallel_singular(robot, Jc, k, float(sp[k]), float(sp_max[k]), ik.t)
    tau, lam = split_tree_torques(robot, Jc, tree, ik.t)
    clock.lap("dynamics")
    return DynamicsResult(t=ik.t, tau=tau, closure_forces=lam.reshape(n, 2, 3),
                          tau_tree=tree, actuator_velocity=V[:, robot.actuated_v], kinetic=K,
                          potential=U, actuated=robot.actuated)


def reduced_mass_matrix(robot: Robot, q, N=None) -> np.ndarray:
    """Closed-loop inertia seen by the actuators, Nᵀ M N with v = N q̇_act (6 × 6); ``N`` at
    ``q`` if already at hand (:func:`~pollard_pin.kinematics.singularity.
    actuator_velocity_map`)."""
    model, data = robot.model, robot.data
    if N is None:
        Jc = constraint_jacobian(model, data, robot.constraint_models, robot.constraint_datas,
                                 q)
        N = actuator_velocity_map(Jc, robot.actuated_v, robot.passive_v)
    return N.T @ _mass_matrix(model, data, q) @ N


def _mass_matrix(model, data, q) -> np.ndarray:
    M = np.array(pin.crba(model, data, q))
    lower = _lower(model.nv)
    M[lower] = M.T[lower]  # crba fills the upper triangle only
    return M


@cache
def _lower(n: int):
    """Indices of the strict lower triangle of n × n (np.tril_indices costs ≈ 10 µs)."""
    return np.tril_indices(n, -1)


def reduced_dynamics(robot: Robot, q, v, losses: JointLosses | None = None, Jc=None, N=None):
    """(M_red (6, 6), h_red (6,)): the closed-loop dynamics in actuator coordinates,
    τ = M_red(q)·θ̈ + h_red(q, v), at a closed state (q, v) (docs/model.md §18).

    M_red = NᵀMN; h_red = Nᵀ(M a₀ + h(q, v) + losses) with a₀ the tree acceleration at θ̈ = 0
    on the loops (Jc a₀ = −J̇c v, a₀ = 0 on the actuators): the inverse dynamics of §13 split
    into its part linear in θ̈ and the rest. ``losses``: friction (and rotor inertia) beyond
    ``robot.model.armature``. ``Jc`` (6 × 12) and ``N`` (12 × 6) at ``q``: the constraint
    Jacobian and velocity map if already at hand (sensing computes them)."""
    model, data = robot.model, robot.data
    Jc, N, a0 = _closed_loop(robot, q, v, Jc, N)
    tree = pin.rnea(model, data, q, v, a0).copy()
    if losses is not None:
        tree += losses.torque(v, a0)
    M = _mass_matrix(model, data, q)
    if losses is not None and np.any(losses.armature):
        M = M + np.diag(np.broadcast_to(np.asarray(losses.armature, dtype=float), (model.nv,)))
    return N.T @ M @ N, N.T @ tree


def reduced_inverse_dynamics(robot: Robot, q, v, u, losses: JointLosses | None = None,
                             Jc=None, N=None, a0=None) -> np.ndarray:
    """τ = M_red(q)·u + h_red(q, v) (6,) of :func:`reduced_dynamics` without forming M_red:
    one RNEA at the tree acceleration a = N·u + a₀ (on the loops, θ̈ = u), projected by Nᵀ
    (Jc·N = 0 drops the closure forces; docs/model.md §13, §18). ``Jc``, ``N`` at ``q`` and
    ``a0`` at (q, v) if at hand (:class:`~pollard_pin.kinematics.sensing.LoopSensor`)."""
    model, data = robot.model, robot.data
    if N is None or a0 is None:
        _, N, a0 = _closed_loop(robot, q, v, Jc, N)
    a = N @ u + a0
    if losses is None:
        return N.T @ pin.rnea(model, data, q, v, a)
    return N.T @ (pin.rnea(model, data, q, v, a) + losses.torque(v, a))


def _closed_loop(robot: Robot, q, v, Jc=None, N=None):
    """(Jc, N, a₀) at a closed state: the constraint Jacobian and velocity map (those given,
    else built) and the tree acceleration at θ̈ = 0 on the loops (Jc a₀ = −J̇c v, a₀ = 0 on the
    actuators)."""
    ia, ip = robot.actuated_v, robot.passive_v
    if Jc is None:
        Jc = constraint_jacobian(robot.model, robot.data, robot.constraint_models,
                                 robot.constraint_datas, q)
    if N is None:
        N = actuator_velocity_map(Jc, ia, ip)
    a0 = np.zeros(robot.model.nv)
    a0[ip] = -solve_small(Jc[:, ip], closure_drift(robot, q, v))
    return Jc, N, a0
