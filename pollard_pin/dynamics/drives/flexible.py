"""Flexible drives in the closed-loop simulation (docs/model.md §28): the classic
flexible-joint model (Spong) on the closed-loop mechanism.

Each actuated joint i is driven through a torsional spring kᵢ [N·m/rad] between its motor,
at the joint-side angle φᵢ = θmᵢ/Nᵢ, and the joint angle qᵢ:

* link side: the mechanism, loops closed (:class:`~.plant.Plant`, without the rotor inertia),
  under the spring torques τₛ = K (φ − q_a);
* motor side: B φ̈ = u − τₛ − b φ̇ − c tanh(φ̇ / v_s), B = N²Jm, b = N²b_m, c = N c_m;
* the controller reads the motor angles and rates (collocated) and commands u.

The state is the link's (q, q̇) and the motors' (φ, φ̇), integrated together as one vector
x = (q, φ) by the same RK4 as the rigid plant.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..control import ControlError, DesiredTrajectory
from ..inverse import JointLosses, reduced_mass_matrix
from ..motors import MAX_STIFFNESS, Actuators
from ..plant import BAUMGARTE, ModelMismatch, Plant, PlantError

# ω·dt of the fastest drive mode: RK4 is stable to 2.8 on the imaginary axis; at 1 it damps
# that mode by 0.6 % per step (the default step; the fastest mode is the gun roll's, whose
# link inertia is tiny), at 2 by 25 % (the longest accepted)
STEP_OMEGA, MAX_STEP_OMEGA = 1.0, 2.0
MODE_POSES = 17  # reference configurations over which the fastest mode is sought


@dataclass(frozen=True, eq=False)
class FlexibleDrives:
    """The six flexible drives seen from the joints, docs/model.md §6 order, for
    ``TrackingOptions(drives=...)`` (docs/model.md §28); ``FlexibleDrives.from_actuators(act)``
    reads them from an actuators file. Give the controller the rotors too
    (``known_losses=act.joint_losses(robot.joint_names)``, as ``simulate --actuators`` does):
    without them it does not know the motor side's inertia.

    Attributes
    ----------
    stiffness : numpy.ndarray
        (6,) the springs' k [N·m/rad], joint side.
    inertia : numpy.ndarray
        (6,) the rotors' B = N²Jm [kg·m²], > 0 (the motor side's mass).
    viscous : numpy.ndarray or float
        The motor side's viscous friction N²b [N·m·s/rad].
    coulomb : numpy.ndarray or float
        The motor side's Coulomb friction N·c [N·m], its sign smoothed as
        c·tanh(φ̇ / coulomb_speed) (as :class:`~pollard_pin.dynamics.inverse.JointLosses`).
    coulomb_speed : float
        The smoothing speed [rad/s].
    known : bool
        True: the controller knows the springs and tracks the motors' reference
        (``motor_reference``); False: it tracks the rigid reference with the motors.

    Raises
    ------
    PlantError
        A stiffness or inertia not finite and positive, or a friction negative.
    """

    stiffness: np.ndarray
    inertia: np.ndarray
    viscous: np.ndarray | float = 0.0
    coulomb: np.ndarray | float = 0.0
    coulomb_speed: float = 1e-3
    known: bool = True

    def __post_init__(self):
        for name, low, strict in (("stiffness", 0.0, True), ("inertia", 0.0, True),
                                  ("viscous", 0.0, False), ("coulomb", 0.0, False)):
            raw = getattr(self, name)
            if np.size(raw) not in (1, 6):
                raise PlantError(f"drive {name}: give one value or 6 (one per actuator), got "
                                 f"{np.size(raw)}")
            try:
                value = np.broadcast_to(np.asarray(raw, dtype=float), (6,)).copy()
            except (TypeError, ValueError):
                raise PlantError(f"drive {name} must be numbers, got {raw!r}"[:200]) from None
            bad = ~np.isfinite(value) | ((value <= low) if strict else (value < low))
            if name == "stiffness":
                bad |= value > MAX_STIFFNESS
            if bad.any():
                j = int(np.argmax(bad))
                rule = (f"in (0, {MAX_STIFFNESS:g}] N·m/rad" if name == "stiffness" else
                        "> 0 kg·m² (the motor side's mass)" if strict else ">= 0")
                raise PlantError(f"drive {name} of actuator {j + 1} must be {rule}, got "
                                 f"{value[j]:g}")
            object.__setattr__(self, name, value)
        if not (isinstance(self.coulomb_speed, (int, float)) and math.isfinite(
                self.coulomb_speed) and self.coulomb_speed > 0):
            raise PlantError(f"Coulomb smoothing speed must be > 0 rad/s, got "
                             f"{self.coulomb_speed}")

    def settings(self, mode_hz: float | None) -> dict:
        """JSON-ready, for a result's metadata: the stiffnesses, the fastest mode [Hz]."""
        return {"stiffness": self.stiffness.tolist(), "known": bool(self.known),
                "fastest_mode_hz": mode_hz}

    @classmethod
    def from_actuators(cls, actuators: Actuators, known: bool = True) -> FlexibleDrives:
        """The drives of an actuator file (docs/model.md §19): its ``stiffness`` (one line
        naming the first actuator without one), N²Jm, N²b and N·c."""
        k = actuators.stiffness()
        n = actuators.column("gear_ratio")
        jm = actuators.column("rotor_inertia")
        if not np.all(jm > 0):
            name = actuators.names[int(np.argmin(jm > 0))]
            raise PlantError(f"{actuators.source}: '{name}.rotor_inertia' is 0; the flexible "
                             "simulation needs every rotor's inertia (the motor side's mass)")
        return cls(stiffness=k, inertia=n * n * jm, viscous=n * n * actuators.column("viscous"),
                   coulomb=n * actuators.column("coulomb"), known=known)

    def losses(self, nv: int, actuated_v) -> JointLosses:
        """The same motors as joint losses of a rigid robot (rotor inertia and friction on the
        actuated joints): the rigid simulation these drives tend to as k grows."""
        arm, visc, coul = (np.zeros(nv) for _ in range(3))
        arm[actuated_v], visc[actuated_v], coul[actuated_v] = (
            self.inertia, self.viscous, self.coulomb)
        return JointLosses(viscous=visc, coulomb=coul, armature=arm,
                           coulomb_speed=self.coulomb_speed)

    def friction(self, dphi: np.ndarray) -> np.ndarray:
        """The motor side's friction torque (6,) at joint-side motor rates ``dphi``."""
        return self.viscous * dphi + self.coulomb * np.tanh(dphi / self.coulomb_speed)


class FlexiblePlant:
    """The link side (:class:`~.plant.Plant` with the payload and mass error of ``errors``, no
    joint losses: the motors are the drives') coupled to the motor side by the springs.

    Its state is x = (q (12), φ (6)), ẋ = (q̇, φ̇): :meth:`held` gives ẍ = f(x, ẋ) under a held
    motor torque u; ``sensed_v`` are the indices of x that the encoders read (the motors)."""

    def __init__(self, robot, errors: ModelMismatch | None, drives: FlexibleDrives,
                 baumgarte: tuple[float, float] = BAUMGARTE):
        errors = errors or ModelMismatch()
        if errors.losses is not None:
            raise PlantError("with flexible drives the motors' inertia and friction are the "
                             "drives' (FlexibleDrives): give the plant no joint losses")
        if not isinstance(drives, FlexibleDrives):
            raise PlantError(f"drives must be a FlexibleDrives, got {type(drives).__name__}")
        self.link = Plant(robot, errors, baumgarte)
        self.robot, self.nominal, self.errors = self.link.robot, robot, self.link.errors
        self.drives = drives
        self.nv = nv = self.robot.model.nv
        self.actuated_v = np.asarray(self.robot.actuated_v)
        self.sensed_v = np.arange(nv, nv + 6)

    def spring_torque(self, x: np.ndarray) -> np.ndarray:
        """τₛ = K (φ − q_a) (6,) [N·m], on the joints (and −τₛ on the motors)."""
        return self.drives.stiffness * (x[self.nv:] - x[self.actuated_v])

    def held(self, u: np.ndarray):
        """``f(x, ẋ)`` → ẍ (18,) under the motor torque ``u`` (6,) held (docs/model.md §28)."""
        nv, ia, link = self.nv, self.actuated_v, self.link.acceleration
        d = self.drives
        k, inv_b, visc, coul, vs = (d.stiffness, 1.0 / d.inertia, d.viscous, d.coulomb,
                                    d.coulomb_speed)
        u = np.array(u, dtype=float)

        def f(x, xd):
            q, dphi = x[:nv], xd[nv:]
            tau_s = k * (x[nv:] - q[ia])
            a = link(q, xd[:nv], tau_s)
            dd = (u - tau_s - visc * dphi - coul * np.tanh(dphi / vs)) * inv_b
            return np.concatenate((a, dd))

        return f

    def closure_residual(self, q: np.ndarray) -> float:
        return self.link.closure_residual(q[:self.nv])

    def last_closure_residual(self) -> float:
        return self.link.last_closure_residual()

    def energy(self, x: np.ndarray, xd: np.ndarray) -> float:
        """Kinetic (links and rotors) plus gravity and spring potential energy [J]."""
        nv, d = self.nv, self.drives
        dphi, delta = xd[nv:], x[nv:] - x[self.actuated_v]
        return (self.link.energy(x[:nv], xd[:nv]) + 0.5 * float(d.inertia @ dphi ** 2)
                + 0.5 * float(d.stiffness @ delta ** 2))

    def start(self, q0, v0, motor: DesiredTrajectory, at_rest: bool):
        """(x0, ẋ0): the link at (q0, v0), the motors at the reference's first motor state
        (its angle only when the robot starts ``at_rest``)."""
        ia = self.actuated_v
        dphi = np.zeros(6) if at_rest else motor.v[0, ia]
        return np.concatenate((q0, motor.q[0, ia])), np.concatenate((v0, dphi))

    def fastest_mode(self, configurations) -> float:
        """The highest natural frequency ω [rad/s] of the drives (links and rotors coupled
        by the springs, no controller, linearised at rest) over ``configurations`` (q, 12)."""
        d = self.drives
        K = np.diag(d.stiffness)
        stiff = np.block([[K, -K], [-K, K]])
        highest = 0.0
        for q in np.atleast_2d(configurations):
            M = np.zeros((12, 12))
            M[:6, :6] = reduced_mass_matrix(self.robot, q)
            M[6:, 6:] = np.diag(d.inertia)
            L = np.linalg.cholesky(M)
            A = np.linalg.solve(L, np.linalg.solve(L, stiff).T)  # L⁻¹ K L⁻ᵀ (K symmetric)
            highest = max(highest, float(np.linalg.eigvalsh(0.5 * (A + A.T))[-1]))
        return math.sqrt(highest)


def flexible_step(plant: FlexiblePlant, configurations, longest: float,
                  dt: float | None = None) -> tuple[float, float]:
    """(longest RK4 step [s], fastest drive mode [Hz]) over ``configurations``: a given ``dt``
    if ω·dt ≤ :data:`MAX_STEP_OMEGA` (else a :class:`ControlError`), by default the shorter of
    ``longest`` (the rigid default step) and :data:`STEP_OMEGA`/ω (docs/model.md §28)."""
    w = plant.fastest_mode(configurations)
    hz = w / (2 * math.pi)
    if dt is None:
        return min(longest, STEP_OMEGA / w), hz
    if w * dt > MAX_STEP_OMEGA:
        raise ControlError(f"time step {dt:g} s is too long for the drives' fastest mode "
                           f"({hz:.4g} Hz): RK4 needs ω·dt <= {MAX_STEP_OMEGA:g}, here "
                           f"{w * dt:.3g}; give a time step <= {MAX_STEP_OMEGA / w:.3g} s, or "
                           f"none ({STEP_OMEGA / w:.3g} s)")
    return dt, hz


def mode_configurations(q: np.ndarray) -> np.ndarray:
    """Up to :data:`MODE_POSES` rows of ``q`` (K, 12), evenly spread, ends included."""
    return q[np.unique(np.linspace(0, len(q) - 1, MODE_POSES).round().astype(int))]


def motor_reference(robot, desired: DesiredTrajectory, drives: FlexibleDrives,
                    known: JointLosses | None) -> DesiredTrajectory:
    """The controller's reference for the motors (docs/model.md §28): where they must be for
    the springs to carry the link side's torque along ``desired``, and the feedforward.

    The link side's torque is the rigid inverse dynamics less the motor terms the controller
    knows (``known``, as in ``desired``): τₛ = τ − (B q̈ + b q̇ + c tanh q̇/v_s) on the actuated
    joints. Then φ_d = q_d + K⁻¹τₛ (the spring's pre-deflection), φ̇_d, φ̈_d with τ̇ₛ, τ̈ₛ by
    finite differences over the ticks, and u_ff = τₛ + B φ̈_d + b φ̇_d + c tanh(φ̇_d/v_s), the
    exact motor-side inverse dynamics, held as the mean of each tick's ends. Drives not
    ``known`` to the controller: ``desired`` itself (the rigid reference and feedforward)."""
    if not drives.known:
        return desired
    ia = np.asarray(robot.actuated_v)
    t, qd, vd, ad = desired.t, desired.q[:, ia], desired.v[:, ia], desired.a[:, ia]
    nv = robot.model.nv
    motor_losses = (lambda v, a: 0.0) if known is None else (
        lambda v, a: known.torque(_pad(v, ia, nv), _pad(a, ia, nv))[:, ia])
    tau_s = desired.tau_exact - motor_losses(vd, ad)
    inv_k = 1.0 / drives.stiffness
    dtau = np.gradient(tau_s, t, axis=0, edge_order=2)
    ddtau = np.gradient(dtau, t, axis=0, edge_order=2)
    q, v, a = desired.q.copy(), desired.v.copy(), desired.a.copy()
    q[:, ia], v[:, ia], a[:, ia] = qd + tau_s * inv_k, vd + dtau * inv_k, ad + ddtau * inv_k
    u = tau_s + motor_losses(v[:, ia], a[:, ia])
    held = u.copy()
    held[:-1] = 0.5 * (u[:-1] + u[1:])
    return DesiredTrajectory(t=t, q=q, v=v, a=a, tau=held, tau_exact=u)


def _pad(x: np.ndarray, ia, nv: int) -> np.ndarray:
    """Actuated columns (K, 6) spread into tree columns (K, nv) for ``JointLosses.torque``."""
    out = np.zeros((len(x), nv))
    out[:, ia] = x
    return out


def flexible_columns(actuated, joint_names, q: np.ndarray, phi: np.ndarray,
                     d_phi: np.ndarray) -> dict:
    """Output columns of the motors (docs/model.md §28): ``phi_<a>`` φ [rad], ``d_phi_<a>``
    φ̇ [rad/s] (joint side) and ``deflection_<a>`` φ − q_a [rad] of each actuator ``a``
    (``q``: the tree joints ``joint_names``, (N, 12))."""
    delta = phi - q[:, [list(joint_names).index(n) for n in actuated]]
    cols = {f"phi_{n}": phi[:, i] for i, n in enumerate(actuated)}
    cols.update({f"d_phi_{n}": d_phi[:, i] for i, n in enumerate(actuated)})
    cols.update({f"deflection_{n}": delta[:, i] for i, n in enumerate(actuated)})
    return cols


def max_deflection(actuated, joint_names, q: np.ndarray, phi: np.ndarray) -> dict:
    """max |φ − q_a| [rad] per actuator name, over the rows."""
    delta = phi - q[:, [list(joint_names).index(n) for n in actuated]]
    return dict(zip(actuated, np.abs(delta).max(axis=0).tolist()))


__all__ = ["FlexibleDrives", "FlexiblePlant", "flexible_columns", "flexible_step",
           "max_deflection",
           "mode_configurations", "motor_reference", "MAX_STEP_OMEGA", "STEP_OMEGA"]
