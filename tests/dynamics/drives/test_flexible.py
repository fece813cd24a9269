"""Flexible drives in the closed-loop simulation (docs/model.md §28): stiff springs give back
the rigid simulation, the energy of links, rotors and springs balances the controller's work
and the friction, the free vibration has the frequencies of the linearised model, and bad
drives are refused in one line."""
import dataclasses

import numpy as np
import pinocchio as pin
import pytest
import scipy.linalg
from motor_model import EXAMPLE  # examples/actuators.toml
from thesis_curves import painting_trajectory

from pollard_pin.dynamics.control import ControlError, Gains
from pollard_pin.dynamics.drives.flexible import FlexibleDrives, FlexiblePlant, flexible_step
from pollard_pin.dynamics.drives.stiffness import stiffness_at
from pollard_pin.dynamics.forward import robot_copy
from pollard_pin.dynamics.motors import ActuatorError, load_actuators
from pollard_pin.dynamics.plant import ModelMismatch, PlantError
from pollard_pin.dynamics.tracking import TrackingOptions, simulate_tracking
from pollard_pin.kinematics.singularity import actuator_velocity_map
from pollard_pin.model.build import constraint_jacobian
from pollard_pin.paths.trajectory import Trajectory

K0 = np.array([3e3, 3e3, 3e3, 1e2, 1e2, 1e2])  # N·m/rad: base drives, wrist drives


@pytest.fixture(scope="module")
def drives():
    """The example motors (reflected to the joints) behind springs K0."""
    a = load_actuators(EXAMPLE)
    n = a.column("gear_ratio")
    return FlexibleDrives(stiffness=K0, inertia=n * n * a.column("rotor_inertia"),
                          viscous=n * n * a.column("viscous"), coulomb=n * a.column("coulomb"))


def _slice(robot, t0: float, seconds: float, step: float) -> Trajectory:
    """The thesis curve (docs/model.md §9) on [t0, t0 + seconds], sampled every ``step``."""
    t = t0 + step * np.arange(int(round(seconds / step)) + 1)
    return Trajectory(*painting_trajectory(robot.params, t=t), name="slice")


def _mass_matrix(model, data, q):
    M = pin.crba(model, data, q)
    return np.triu(M) + np.triu(M, 1).T


def test_stiff_springs_give_the_rigid_simulation(robot, drives):
    """The flexible simulation against the rigid one with the rotors on the joints (same
    controller, same motors), as every k grows ×100: max tool-tip distance between the two
    over 20 ms of the thesis curve. Open loop (ω = 0: the feedforward alone) the joints' gap
    falls as 1/k once k is large: 1.5e-8, 2.0e-9, 2.1e-11 rad (ratios 7.5 and 97, asserted 5
    and 50). Closed loop the drive modes, sampled at 1 kHz by the PD, alias; the gap falls
    once the modes are far above the sampling: 2.3e-8, 2.8e-8, 2.9e-10 m (asserted: a 10×
    fall, to under 1e-8 m)."""
    traj = _slice(robot, 5.0, 0.02, 1e-3)
    losses = drives.losses(robot.model.nv, robot.actuated_v)
    for gains, name in ((Gains(0.0, 0.0), "open"), (Gains(), "closed")):
        base = TrackingOptions(controller="feedforward-pd", gains=gains, known_losses=losses)
        rigid = simulate_tracking(robot, traj, dataclasses.replace(
            base, errors=ModelMismatch(losses=losses)))
        gaps, joint_gaps = [], []
        for scale in (1.0, 1e2, 1e4):
            flex = simulate_tracking(robot, traj, dataclasses.replace(
                base, drives=dataclasses.replace(drives, stiffness=K0 * scale)))
            gaps.append(np.abs(flex.tip - rigid.tip).max())
            joint_gaps.append(np.abs(flex.q - rigid.q).max())
        if name == "open":
            assert joint_gaps[1] < joint_gaps[0] / 5 and joint_gaps[2] < joint_gaps[1] / 50, \
                joint_gaps
            assert joint_gaps[2] < 1e-9, joint_gaps
        else:
            assert gaps[2] < gaps[0] / 10 and gaps[2] < 1e-8, gaps


def _move(robot, seconds: float = 0.05, hold: float = 0.05, step: float = 2.5e-4):
    """A rest-to-rest quintic move of the tool by OFFSET from the home pose in ``seconds``,
    then held: jerk jumps at both ends, the springs' pre-deflection changes fast."""
    offset = np.array([0.005, -0.004, 0.003, 0.02, -0.01, 0.02])  # m, rad
    t = step * np.arange(int(round((seconds + hold) / step)) + 1)
    s = np.clip(t / seconds, 0.0, 1.0)
    moving = t < seconds
    rate = (30 * s ** 2 - 60 * s ** 3 + 30 * s ** 4) / seconds * moving
    acc = (60 * s - 180 * s ** 2 + 120 * s ** 3) / seconds ** 2 * moving
    return Trajectory(t, robot.params.home_pose + np.outer(10 * s ** 3 - 15 * s ** 4
                                                            + 6 * s ** 5, offset),
                      np.outer(rate, offset), np.outer(acc, offset), name="move")


def test_the_motor_feedforward_is_the_flexible_inverse_dynamics(robot, drives):
    """Open loop (ω = 0) along a 50 ms move, the feedforward of docs/model.md §28 alone (the
    springs' pre-deflection, B K⁻¹τ̈ₛ and the friction's change on top of the rigid inverse
    dynamics) carries the flexible plant along the reference: the tool-tip error is the hold
    and the finite differences', second order in the control period. Without friction
    1.0e-4, 2.6e-5, 6.4e-6, 1.6e-6 m at T = 2, 1, 0.5, 0.25 ms (ratios 3.96, 3.99, 4.00;
    asserted 4 ± 0.4)."""
    traj = _move(robot)
    frictionless = dataclasses.replace(drives, viscous=0.0, coulomb=0.0)
    losses = frictionless.losses(robot.model.nv, robot.actuated_v)
    errors = [simulate_tracking(robot, traj, TrackingOptions(
        controller="feedforward-pd", gains=Gains(0.0, 0.0), control_period=T,
        known_losses=losses, drives=frictionless)).tip_position_error.max()
        for T in (2e-3, 1e-3, 5e-4, 2.5e-4)]
    ratios = np.array(errors[:-1]) / errors[1:]
    assert np.all(np.abs(ratios - 4) < 0.4), errors


def test_the_controller_knows_its_drives_unless_told(robot, drives):
    """Without ``known_losses`` the controller takes the drives' own motors: the same run,
    bit for bit, as with them given (a 4 s pass without them missed by 66 mm)."""
    traj = _move(robot, seconds=0.02, hold=0.01)
    losses = drives.losses(robot.model.nv, robot.actuated_v)
    given = simulate_tracking(robot, traj, TrackingOptions(known_losses=losses, drives=drives))
    default = simulate_tracking(robot, traj, TrackingOptions(drives=drives))
    assert np.array_equal(given.tip_position_error, default.tip_position_error)


def test_energy_balances_the_controller_work_and_the_friction(robot, drives):
    """Along 20 ms of the thesis curve under computed torque, the motors' Coulomb and viscous
    friction on: the change of kinetic (links: crba, rotors ½Bφ̇²) plus potential (gravity,
    springs ½kδ²) energy equals the controller's work less the friction's loss, at every
    tick. The work is exact for a torque held over each tick, Σ u·Δφ; the loss by Simpson's
    rule over the 16 RK4 steps of each tick. Residual 3.2e-15 J against 0.036 J of work and
    7.8e-3 J lost (8.7e-14 relative; asserted 1e-11); leaving out the springs' energy
    (≈ 6e-5 J) would break it."""
    period, sub = 1e-3, 16
    dt = period / sub
    traj = _slice(robot, 5.0, 0.02, dt)  # an output row at every RK4 step
    losses = drives.losses(robot.model.nv, robot.actuated_v)
    res = simulate_tracking(robot, traj, TrackingOptions(known_losses=losses, drives=drives,
                                                         dt=dt))
    model, data = robot.model, robot.data  # the link side: the nominal model, no rotors
    ia = robot.actuated_v
    energy = np.array([
        0.5 * v @ _mass_matrix(model, data, q) @ v + pin.computePotentialEnergy(model, data, q)
        + 0.5 * drives.inertia @ dphi ** 2 + 0.5 * drives.stiffness @ (phi - q[ia]) ** 2
        for q, v, phi, dphi in zip(res.q, res.v, res.phi, res.d_phi)])
    ticks = np.arange(0, len(res.t), sub)
    work = np.cumsum([res.tau[k] @ (res.phi[k + sub] - res.phi[k]) for k in ticks[:-1]])
    p = np.einsum("ij,ij->i", res.d_phi, drives.friction(res.d_phi))  # dissipated power
    w = np.ones(sub + 1)
    w[1:-1:2], w[2:-1:2] = 4.0, 2.0
    loss = np.cumsum([dt / 3 * w @ p[k:k + sub + 1] for k in ticks[:-1]])
    residual = energy[ticks[1:]] - energy[0] - (work - loss)
    assert np.abs(residual).max() < 1e-11 * np.abs(work).max(), (residual, work, loss)


def _swing(robot, drives, u_link, u_motor, omega: float) -> float:
    """The angular frequency at which the spring deflection of the free plant (no gravity,
    no controller, no friction, no Baumgarte term) swings, started at home with actuated
    rates ``u_link`` (the loops' velocity map gives the rest) and motor rates ``u_motor``:
    zero crossings over six periods of ``omega``, by RK4 at ω·h = 0.05 (or shorter steps, for
    RK4 to stay stable on the fastest mode, which round-off excites)."""
    copy = robot_copy(robot)
    copy.model.gravity = pin.Motion.Zero()
    plant = FlexiblePlant(copy, None, dataclasses.replace(drives, viscous=0.0, coulomb=0.0),
                          baumgarte=(0.0, 0.0))
    f = plant.held(np.zeros(6))
    q0 = robot.home()
    x = np.concatenate((q0, q0[copy.actuated_v]))
    xd = np.concatenate((_velocity_map(copy, q0) @ u_link, u_motor))
    h = min(0.05 / omega, 1.0 / plant.fastest_mode(q0))
    j = int(np.argmax(np.abs(u_motor - u_link)))  # the largest swing
    delta = []
    for _ in range(int(6 * 2 * np.pi / omega / h)):
        delta.append(plant.spring_torque(x)[j])
        k1v, k1a = xd, f(x, xd)
        k2v, k2a = xd + h / 2 * k1a, f(x + h / 2 * k1v, xd + h / 2 * k1a)
        k3v, k3a = xd + h / 2 * k2a, f(x + h / 2 * k2v, xd + h / 2 * k2a)
        k4v, k4a = xd + h * k3a, f(x + h * k3v, xd + h * k3a)
        x = x + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
        xd = xd + h / 6 * (k1a + 2 * k2a + 2 * k3a + k4a)
    d = np.array(delta)
    i = np.nonzero(np.sign(d[1:]) != np.sign(d[:-1]))[0][1:]  # skip t = 0
    crossings = h * (i + d[i] / (d[i] - d[i + 1]))
    return np.pi / np.mean(np.diff(crossings))


def _velocity_map(robot, q):
    Jc = constraint_jacobian(robot.model, robot.data, robot.constraint_models,
                             robot.constraint_datas, q)
    return actuator_velocity_map(Jc, robot.actuated_v, robot.passive_v)


def _links_mass(robot, q):
    """Mₐ = NᵀMN: the links' mass matrix on the actuated angles, from crba."""
    N = _velocity_map(robot, q)
    return N.T @ _mass_matrix(robot.model, robot.data, q) @ N


def test_free_vibration_has_the_linearised_frequencies(robot, drives):
    """No gravity, no controller (u = 0), at home: started along one vibration mode of
    [Mₐ 0; 0 B] ẍ = −[K −K; −K K] x (Mₐ = NᵀMN from crba and the constraint Jacobian; the
    simulation solves the KKT system instead), the plant's spring deflection swings at that
    mode's frequency: the six modes 54–1246 Hz found to 1.7e-7 relative (asserted 2e-5)."""
    K = np.diag(drives.stiffness)
    w2, shapes = scipy.linalg.eigh(np.block([[K, -K], [-K, K]]), scipy.linalg.block_diag(
        _links_mass(robot, robot.home()), np.diag(drives.inertia)))
    worst = 0.0
    for mode in range(6, 12):  # the first six are the rigid motions (ω = 0)
        omega, u = np.sqrt(w2[mode]), shapes[:, mode]
        u = u * 1e-6 * omega / np.abs(u[6:] - u[:6]).max()  # deflection amplitude 1e-6 rad
        worst = max(worst, abs(_swing(robot, drives, u[:6], u[6:], omega) / omega - 1))
    assert worst < 2e-5, worst


def test_motors_held_still_swing_at_the_stiffness_modes(robot):
    """The modes of docs/model.md §27 (``stiffness_at``: rotors held by their loops) are the
    flexible plant's with rotors too heavy to move (B = 10⁶ kg·m²): with the example drives
    (k = 3000, 300 N·m/rad), started along each mode (its shape from K u = ω² Mₐ u here),
    the links swing at §27's f1 … f6 (37.5–2157 Hz at home) to 1.7e-7 relative (asserted
    2e-5)."""
    k = load_actuators(EXAMPLE).stiffness()
    f27 = stiffness_at(robot, robot.home()[None], k).frequencies[0]
    held = FlexibleDrives(stiffness=k, inertia=1e6)
    w2, shapes = scipy.linalg.eigh(np.diag(k), _links_mass(robot, robot.home()))
    measured = np.array([_swing(robot, held, shapes[:, m] * 1e-6 * np.sqrt(w2[m]) / np.abs(
        shapes[:, m]).max(), np.zeros(6), np.sqrt(w2[m])) for m in range(6)]) / (2 * np.pi)
    assert np.abs(measured / f27 - 1).max() < 2e-5, (measured, f27)


@pytest.mark.parametrize("kwargs, says", [
    ({"stiffness": -1.0}, "drive stiffness of actuator 1 must be in (0, 1e+09] N·m/rad"),
    ({"stiffness": [1.0] * 5}, "drive stiffness: give one value or 6"),
    ({"inertia": 0.0}, "drive inertia of actuator 1 must be > 0 kg·m²"),
    ({"viscous": np.nan}, "drive viscous of actuator 1 must be >= 0, got nan"),
    ({"coulomb_speed": 0.0}, "Coulomb smoothing speed must be > 0"),
    ({"coulomb_speed": "fast"}, "Coulomb smoothing speed must be > 0"),
    ({"inertia": "heavy"}, "drive inertia must be numbers, got 'heavy'"),
])
def test_bad_drives_are_refused_in_one_line(kwargs, says):
    args = {"stiffness": K0, "inertia": 1e-3, **kwargs}
    with pytest.raises(PlantError, match=None) as exc:
        FlexibleDrives(**args)
    assert says in str(exc.value) and "\n" not in str(exc.value)


def test_what_the_flexible_simulation_refuses(robot, drives, tmp_path):
    bare = tmp_path / "no_stiffness.toml"
    bare.write_text("".join(line for line in EXAMPLE.read_text().splitlines(True)
                            if not line.startswith("stiffness")))
    with pytest.raises(ActuatorError, match="'theta21.stiffness' is missing"):
        FlexibleDrives.from_actuators(load_actuators(bare))
    with pytest.raises(PlantError, match="give the plant no joint losses"):
        FlexiblePlant(robot, ModelMismatch(losses=drives.losses(12, robot.actuated_v)), drives)
    plant = FlexiblePlant(robot, None, drives)
    # the gun roll's drive: 1.2 kHz (k = 100 N·m/rad on 1.7e-6 kg·m² of link)
    step, hz = flexible_step(plant, robot.home()[None], 1e-3)
    assert step == pytest.approx(1 / (2 * np.pi * hz), rel=1e-12) and 1000 < hz < 1500
    with pytest.raises(ControlError, match=r"time step 0.001 s is too long for the drives' "
                                           r"fastest mode \(12\d\d Hz\): RK4 needs ω·dt <= 2, "
                                           r"here 7\.8"):
        flexible_step(plant, robot.home()[None], 1e-3, dt=1e-3)
