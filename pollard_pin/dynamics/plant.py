"""The simulated robot ("plant") of a closed-loop simulation (docs/model.md §18).

A perturbed copy of the nominal model — a point payload at the tool tip, a relative mass and
inertia error on every link, rotor inertia (armature) and joint friction — whose loops are
closed by ``pin.constraintDynamics`` with Baumgarte stabilisation (docs/model.md §14). The
controller keeps the nominal model; only the plant sees the perturbations.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from functools import partial

import numpy as np
import pinocchio as pin

from ..errors import InputError
from ..model.build import Robot, constraint_residual
from .forward import robot_copy
from .inverse import JointLosses, inverse_dynamics_sample

BAUMGARTE = (400.0, 40.0)  # Kp [1/s²], Kd [1/s]: critically damped 20 rad/s (docs/model.md §14)


class PlantError(InputError):
    """A plant parameter the simulation cannot use (one line: which, what value)."""


@dataclass(frozen=True)
class ModelMismatch:
    """How the plant differs from the controller's (nominal) model.

    Parameters
    ----------
    payload : float, optional
        A point mass at the tool tip (``tip`` frame origin) [kg], ≥ 0 (default 0).
    mass_error : float, optional
        Every link's mass and rotational inertia (about its centre of mass) scaled by
        1 + ``mass_error`` (default 0; > −1).
    losses : pollard_pin.dynamics.inverse.JointLosses or None, optional
        Joint friction and rotor inertia (armature) of the plant; the controller does not
        know them.

    Raises
    ------
    PlantError
        A payload or mass error the simulation cannot use.

    Examples
    --------
    >>> from pollard_pin.dynamics import ModelMismatch
    >>> ModelMismatch(payload=0.05, mass_error=0.1).payload
    0.05
    """

    payload: float = 0.0
    mass_error: float = 0.0
    losses: JointLosses | None = None

    def __post_init__(self):
        if not (math.isfinite(self.payload) and self.payload >= 0):
            raise PlantError(f"payload must be a mass >= 0 kg, got {self.payload}")
        if not (math.isfinite(self.mass_error) and self.mass_error > -1):
            raise PlantError(f"mass error must be a fraction > -1 (every link's mass × "
                             f"(1 + fraction)), got {self.mass_error}")
        if self.losses is not None:
            for name in ("viscous", "coulomb", "armature"):
                value = np.asarray(getattr(self.losses, name), dtype=float)
                if not (np.all(np.isfinite(value)) and np.all(value >= 0)):
                    raise PlantError(f"joint {name} must be finite and >= 0, got {value}")


def perturbed_robot(robot: Robot, errors: ModelMismatch) -> Robot:
    """A copy of ``robot`` with its own model, data and constraint data, perturbed by
    ``errors`` (mass error, payload, armature in ``model.armature``). ``robot`` is untouched."""
    model = pin.Model(robot.model)
    scale = 1.0 + errors.mass_error
    for j in range(1, model.njoints):
        I = model.inertias[j]
        model.inertias[j] = pin.Inertia(I.mass * scale, I.lever.copy(), I.inertia * scale)
    if errors.payload > 0:
        frame = model.frames[robot.tip_frame]
        j = frame.parentJoint
        point = pin.Inertia(errors.payload, frame.placement.translation.copy(), np.zeros((3, 3)))
        model.inertias[j] = model.inertias[j] + point
    if errors.losses is not None:
        model.armature = model.armature + np.broadcast_to(
            np.asarray(errors.losses.armature, dtype=float), (model.nv,))
    return robot_copy(robot, model)


class Plant:
    """Closed-loop forward dynamics of a (perturbed) robot: accelerations under torques.

    ``plant.robot`` holds the perturbed model (armature in ``model.armature``, so Pinocchio's
    ``crba``/``rnea``/``constraintDynamics`` all include it); ``plant.friction`` the viscous and
    Coulomb part of the losses, applied as −(viscous·v + coulomb·tanh(v/v_s)).

    Parameters
    ----------
    robot : Robot
        The nominal model; it is not changed (the plant works on a copy).
    errors : ModelMismatch or None, optional
        How the plant differs from ``robot`` (default: not at all).
    baumgarte : tuple of float, optional
        ``(Kp, Kd)`` [1/s², 1/s] of the loops' Baumgarte stabilisation (default (400, 40)).

    Raises
    ------
    PlantError
        Baumgarte gains that are negative or not finite.
    """

    def __init__(self, robot: Robot, errors: ModelMismatch | None = None,
                 baumgarte: tuple[float, float] = BAUMGARTE):
        self.errors = errors or ModelMismatch()
        kp, kd = (float(x) for x in baumgarte)
        if not (kp >= 0 and kd >= 0 and math.isfinite(kp) and math.isfinite(kd)):
            raise PlantError(f"Baumgarte gains must be finite and >= 0, got {baumgarte}")
        self.nominal = robot
        self.robot = perturbed_robot(robot, self.errors)
        for cm in self.robot.constraint_models:  # its own (perturbed_robot's copies)
            cm.m_baumgarte_parameters.Kp, cm.m_baumgarte_parameters.Kd = kp, kd
        losses = self.errors.losses
        self.friction = None if losses is None else dataclasses.replace(losses, armature=0.0)
        if self.friction is not None and not (np.any(self.friction.viscous)
                                              or np.any(self.friction.coulomb)):
            self.friction = None
        r = self.robot
        pin.initConstraintDynamics(r.model, r.data, r.constraint_models, r.constraint_datas)
        self._settings = pin.ProximalSettings(1e-14, 0.0, 1)
        self._ia, self._passive = r.actuated_v, r.passive_v
        self.sensed_v = r.actuated_v  # the state's entries the encoders read
        self._tau = np.zeros(r.model.nv)

    def acceleration(self, q: np.ndarray, v: np.ndarray, tau_act: np.ndarray) -> np.ndarray:
        """Tree joint accelerations (12,) under actuator torques ``tau_act`` (6,)."""
        r = self.robot
        tau = self._tau
        tau[self._ia] = tau_act  # the passive entries stay 0 unless friction is added
        if self.friction is not None:
            tau[self._passive] = 0.0
            tau -= self.friction.torque(v, 0.0)
        return pin.constraintDynamics(r.model, r.data, q, v, tau, r.constraint_models,
                                      r.constraint_datas, self._settings).copy()

    def held(self, tau_act: np.ndarray):
        """``f(q, v)`` = :meth:`acceleration` (q, v, ``tau_act``), the same bits: the torque of a
        control period, held (zero-order hold, docs/model.md §18), its tree vector built once
        for the period's RK4 stages rather than at each."""
        if self.friction is not None:  # the friction torque depends on v: built per call
            return partial(self.acceleration, tau_act=tau_act)
        r = self.robot
        tau = np.zeros(r.model.nv)
        tau[self._ia] = tau_act
        dynamics, model, data = pin.constraintDynamics, r.model, r.data
        cms, cds, settings = r.constraint_models, r.constraint_datas, self._settings

        def f(q, v):
            return dynamics(model, data, q, v, tau, cms, cds, settings).copy()

        return f

    def actuator_torque(self, q, v, a) -> np.ndarray:
        """The plant's closed-loop inverse dynamics: actuator torques (6,) giving ``a``."""
        return inverse_dynamics_sample(self.robot, q, v, a, self.friction)[0]

    def closure_residual(self, q: np.ndarray) -> float:
        """max |p_A − p_B| component [m] at ``q``."""
        r = self.robot
        return float(np.abs(constraint_residual(r.model, r.data, r.constraint_models,
                                                r.constraint_datas, q)).max())

    def last_closure_residual(self) -> float:
        """:meth:`closure_residual` at the q of the last :meth:`acceleration`, without a
        kinematics pass: ``constraintDynamics`` placed the closures there (same bits; the
        components' max by Python on lists: a numpy reduction costs ≈ 1.5 µs, this runs every
        control tick)."""
        gaps = []
        for _, cd in self.robot.constraint_pairs:
            gaps += (cd.oMc1.translation - cd.oMc2.translation).tolist()
        if not math.isfinite(sum(gaps)):  # a NaN, which Python's max may skip
            return float(np.abs(gaps).max())
        return float(max(map(abs, gaps)))

    def energy(self, q: np.ndarray, v: np.ndarray) -> float:
        """Kinetic (rotor inertia included) plus gravity potential energy [J]."""
        r = self.robot
        M = pin.crba(r.model, r.data, q)
        M = np.triu(M) + np.triu(M, 1).T
        return float(0.5 * v @ M @ v + pin.computePotentialEnergy(r.model, r.data, q))
