"""Closed-loop simulation (docs/model.md §18): tracking, the plant against its own inverse
dynamics and against MuJoCo, energy conservation to RK4's order, bad API inputs. (The
command, ``pollard-pin simulate``: tests/cli/test_simulate.py.)"""
from pathlib import Path

import numpy as np
import pytest
from thesis_curves import thesis_head

from pollard_pin.dynamics.control import ControlError, FeedforwardPD, Gains, desired_trajectory
from pollard_pin.dynamics.forward import forward_dynamics
from pollard_pin.dynamics.inverse import JointLosses, inverse_dynamics_sample
from pollard_pin.dynamics.plant import ModelMismatch, Plant, PlantError
from pollard_pin.dynamics.tracking import MeasurementNoise, TrackingOptions, simulate_tracking
from pollard_pin.paths.curves import thesis_trajectory

PERTURBED = ModelMismatch(payload=0.05, mass_error=0.1)
MOTORS = Path(__file__).resolve().parents[2] / "examples" / "actuators.toml"


@pytest.fixture(scope="module")
def traj():
    return thesis_head(2.0)


@pytest.fixture(scope="module")
def desired(robot, traj):
    return desired_trajectory(robot, traj)


@pytest.fixture(scope="module")
def runs(robot, traj, desired):
    """The built-in controllers on the exact and on the perturbed plant."""
    return {(c, e): simulate_tracking(robot, traj, TrackingOptions(c, errs, desired=desired))
            for c in ("computed-torque", "feedforward-pd", "pd")
            for e, errs in (("exact", None), ("perturbed", PERTURBED))}


def test_exact_model_tracking_and_the_zero_order_hold(runs):
    """Exact model, no noise, 1 ms zero-order hold. feedforward-pd holds the interval mean of
    the reference torque (error O(T²)): 8.9e-8 m. computed-torque holds M(q_k), h(q_k, v_k)
    of the tick over the period, a T/2 lag (error O(T), tests/dynamics/test_tracking.py):
    3.2e-6 m. The loops stay closed to 1.0e-11 m."""
    ff, ct = runs["feedforward-pd", "exact"], runs["computed-torque", "exact"]
    assert ff.tip_position_error.max() <= 1.2e-7  # achieved 8.87e-08
    assert ff.tip_orientation_error.max() <= 3.5e-7  # 2.75e-07
    assert ct.tip_position_error.max() <= 4e-6  # 3.22e-06
    assert ct.tip_orientation_error.max() <= 2.2e-5  # 1.82e-05
    for res in (ff, ct):
        assert res.max_closure_residual <= 1.2e-11  # 1.01e-11, the Baumgarte floor
        assert res.closure_residual.max() <= res.max_closure_residual


def test_payload_and_mass_error_stay_bounded_and_pd_is_worse(runs):
    """Payload 50 g + masses +10 %: both model-based laws settle to the same offset (same
    gains; they differ only at second order in the error), 3.38 mm, with no drift (the second
    second as large as the first, to 1e-3); PD + gravity lags the moving reference too."""
    ct, ff = runs["computed-torque", "perturbed"], runs["feedforward-pd", "perturbed"]
    for res in (ct, ff):
        e = res.tip_position_error
        assert 3.2e-3 <= e.max() <= 3.55e-3  # achieved 3.376e-03 (ct), 3.371e-03 (ff)
        half = len(res) // 2
        assert e[half:].max() <= 1.001 * e[:half].max()  # 3.3758 vs 3.3760 mm (ct)
        s = res.summary()
        assert s["rms_tip_position_error"] <= s["max_tip_position_error"]
    assert abs(ct.tip_position_error.max() / ff.tip_position_error.max() - 1) <= 0.01  # 1.6e-3
    for model in ("exact", "perturbed"):
        assert (runs["pd", model].tip_position_error.max()
                > 1.5 * runs["computed-torque", model].tip_position_error.max())
    # PD lags the moving reference by ~2ζθ̇_d/ω: 1.67 mm on the exact model.
    assert 1.5e-3 <= runs["pd", "exact"].tip_position_error.max() <= 1.85e-3


def test_plant_obeys_its_inverse_dynamics(robot, traj, desired):
    """ID(q, v, a) of the simulated states (payload, mass error, rotor inertia, friction)
    returns the applied torque: 2.9e-15 relative (asserted 3e-13)."""
    losses = JointLosses(viscous=np.full(12, 2e-3), coulomb=np.full(12, 1e-3),
                         armature=np.full(12, 1e-4))
    errors = ModelMismatch(payload=0.05, mass_error=0.1, losses=losses)
    res = simulate_tracking(robot, traj,
                            TrackingOptions("computed-torque", errors, desired=desired))
    plant = Plant(robot, errors)
    worst = 0.0
    for k in range(0, len(res), 10):
        tau = plant.actuator_torque(res.q[k], res.v[k], res.a[k])
        worst = max(worst, np.abs(tau - res.tau[k]).max() / np.abs(res.tau[k]).max())
    assert worst <= 3e-13
    # The nominal model's ID does not match: the check can fail.
    k = len(res) // 2
    nominal = inverse_dynamics_sample(robot, res.q[k], res.v[k], res.a[k])[0]
    assert np.abs(nominal - res.tau[k]).max() > 1e-3 * np.abs(res.tau[k]).max()


@pytest.mark.parametrize("controller", ["computed-torque", "feedforward-pd"])
def test_known_motors_are_compensated(robot, traj, controller):
    """The example motors (reflected rotor inertia N²·Jm, friction) in the plant: unknown to
    the controller they leave the spray-gun roll 0.49 rad behind; known, both model-based laws
    track to a few µm again (computed-torque 2.6e-6 m, feedforward-pd 1.6e-6 m)."""
    from pollard_pin.dynamics.motors import load_actuators

    motors = load_actuators(MOTORS)
    losses = motors.joint_losses(robot.joint_names)
    blind, known = (simulate_tracking(robot, traj, TrackingOptions(
        controller, ModelMismatch(losses=losses), known_losses=k)) for k in (None, losses))
    assert known.tip_position_error.max() <= 3.5e-6
    assert known.tip_orientation_error.max() <= 4e-5  # 3.3e-05 (ct), 7.8e-06 (ff)
    assert blind.tip_orientation_error.max() > 0.4  # 0.487 rad
    plant = Plant(robot, ModelMismatch(losses=losses))
    k = len(known) // 2
    tau = plant.actuator_torque(known.q[k], known.v[k], known.a[k])
    assert np.abs(tau - known.tau[k]).max() <= 2e-14 * np.abs(known.tau[k]).max()  # 1.8e-16


def test_forward_dynamics_honours_armature(robot, desired):
    q, v = desired.q[50], desired.v[50]
    tau = desired.tau_exact[50]
    losses = JointLosses(viscous=0.01, coulomb=0.02, armature=np.linspace(1e-4, 1e-3, 12))
    a = forward_dynamics(robot, q, v, tau, losses=losses)
    assert np.abs(inverse_dynamics_sample(robot, q, v, a, losses)[0] - tau).max() < 1e-10
    assert not np.any(robot.model.armature)  # restored
    assert np.abs(a - forward_dynamics(robot, q, v, tau)).max() > 1e-3


def test_mujoco_peer_forward_dynamics_agrees(robot, runs):
    """KKT solve with MuJoCo's mass matrix, bias forces and connect Jacobian (J̇v by central
    differences of MuJoCo's efc_J) against the plant's accelerations at simulated states."""
    mujoco = pytest.importorskip("mujoco")
    from pollard_pin.crosscheck.mujoco import JOINTS, build_mujoco

    model, data, info = build_mujoco()
    assert tuple(JOINTS) == robot.joint_names
    qadr, dadr, rows = info["qpos_adr"], info["dof_adr"], info["efc_rows"].reshape(-1)
    ia = robot.actuated_v
    res = runs["computed-torque", "perturbed"]  # states off the reference, nominal plant below
    plant = Plant(robot)

    def jacobian(q):
        data.qpos[qadr] = q
        mujoco.mj_forward(model, data)
        return data.efc_J.reshape(data.nefc, model.nv)[rows][:, dadr].copy()

    worst = 0.0
    for k in (0, 57, 133, 200):
        q, v, tau = res.q[k], res.v[k], res.tau[k]
        h = 1e-6
        jdot_v = (jacobian(q + h * v) - jacobian(q - h * v)) / (2 * h) @ v
        J = jacobian(q)
        data.qvel[dadr] = v
        mujoco.mj_forward(model, data)
        M = np.zeros((model.nv, model.nv))
        mujoco.mj_fullM(model, data, M)  # MuJoCo 4 signature
        M, bias = M[np.ix_(dadr, dadr)], data.qfrc_bias[dadr]
        f = -bias
        f[ia] += tau
        kkt = np.block([[M, J.T], [J, np.zeros((6, 6))]])
        a_mj = np.linalg.solve(kkt, np.concatenate([f, -jdot_v]))[:12]
        a = plant.acceleration(q, v, tau)
        worst = max(worst, np.abs(a - a_mj).max() / np.abs(a).max())
    assert worst < 1e-8  # seen 5.6e-10: the central difference for J̇v


def test_energy_is_conserved_to_fourth_order(robot):
    """Controller off, no friction: the energy drift falls ~16× per halving of dt (RK4)."""
    traj = thesis_head(0.3)
    plant = Plant(robot)

    def off(t, q, v):
        return np.zeros(6)

    drift = []
    for dt in (5e-3, 2.5e-3, 1.25e-3):
        # a free fall at coarse steps opens the loops to 1.2e-8 m at dt = 5 ms: allowed here
        res = simulate_tracking(robot, traj, TrackingOptions(off, dt=dt, control_period=0.01,
                                                             loop_tolerance=1e-6))
        e = np.array([plant.energy(q, v) for q, v in zip(res.q, res.v)])
        drift.append(np.abs(e - e[0]).max())
    rates = [drift[0] / drift[1], drift[1] / drift[2]]
    assert all(15.0 < r < 17.0 for r in rates), (drift, rates)  # 15.9, 16.0: 2⁴
    assert drift[-1] <= 2e-9  # 2.2e-11 J


def test_zero_order_hold_saturation_and_user_controller(robot, traj, desired):
    calls = []
    inner = FeedforwardPD(robot, desired, Gains(60.0, 1.0))

    def mine(t, q, v):
        calls.append(t)
        return inner(t, q, v)

    # 1.1 N·m (peak reference 1.2): saturated 0.48 s, the robot kept within its joint limits
    # (at 0.8 N·m it falls out of them: tests/dynamics/test_tracking.py)
    res = simulate_tracking(robot, traj, TrackingOptions(
        mine, control_period=5e-3, torque_limit=1.1,
        desired=desired_trajectory(robot, traj, 5e-3)))
    assert np.allclose(np.diff(calls), 5e-3)
    assert np.abs(res.tau).max() <= 1.1 + 1e-15
    assert res.saturation_time > 0
    assert len(res) == len(traj) and np.array_equal(res.t, traj.t)


def test_output_samples_off_the_control_grid(robot, traj):
    """Sample times (10 ms) that are not ticks (3 ms) nor RK4 steps (0.7 ms) are inserted as
    breakpoints: every output row is at its own time, tracking unchanged (feedforward-pd at a
    3 ms hold: 8.0e-7 m, (3 ms / 1 ms)² × 8.9e-8 m)."""
    res = simulate_tracking(robot, traj,
                            TrackingOptions("feedforward-pd", dt=7e-4, control_period=3e-3))
    assert np.array_equal(res.t, traj.t)
    assert res.tip_position_error.max() <= 1e-6  # 8.01e-07
    plant = Plant(robot)
    k = 77
    assert np.abs(plant.actuator_torque(res.q[k], res.v[k], res.a[k]) - res.tau[k]).max() \
        <= 4e-14 * np.abs(res.tau[k]).max()  # 3.9e-16


def test_noise_is_seeded(robot, traj, desired):
    runs = [simulate_tracking(robot, traj, TrackingOptions(
        "computed-torque", desired=desired, noise=MeasurementNoise(1e-4, 1e-2, seed)))
        for seed in (1, 1, 2)]
    assert np.array_equal(runs[0].tau, runs[1].tau)
    assert not np.array_equal(runs[0].tau, runs[2].tau)
    # σ = 1e-4 rad on the encoders: 6.9e-5 m (seeds 2, 3: 4.4e-5, 5.1e-5 m)
    assert 5e-5 <= runs[0].tip_position_error.max() <= 8e-5


@pytest.mark.parametrize("kwargs, says", [
    (dict(controller="lqr"), "unknown controller 'lqr'"),
    (dict(gains=None), "natural frequency ω \\[rad/s\\] must be"),
    (dict(dt=0.0), "time step must be > 0 s"),
    (dict(dt=2e-3), "time step 0.002 s is longer than the control period 0.001 s"),
    (dict(start="home"), "trajectory starts off the path"),
    (dict(errors=None, torque_limit=[1, 2]), "give one value or 6"),
])
def test_bad_api_inputs(robot, traj, desired, kwargs, says):
    if "gains" in kwargs:
        with pytest.raises(ControlError, match=says):
            Gains(-1.0, 1.0)
        return
    if kwargs.get("start") == "home":
        kwargs["start"] = robot.home()
    with pytest.raises(ControlError, match=says):
        simulate_tracking(robot, traj, TrackingOptions(desired=desired, **kwargs))
    with pytest.raises(PlantError, match="fraction > -1"):
        ModelMismatch(mass_error=-1.5)


def test_the_reference_follows_the_trajectorys_own_curve(robot):
    """Between samples the reference is the trajectory's own ``curve`` (the thesis curve
    here, docs/model.md §9), not a spline through the samples: on 41 samples 0.5 s apart the
    quintic Hermite through them is off the curve by 1e-2 rad in the joints (the old reference
    ignored the curve: 0.0096 rad)."""
    from dataclasses import replace

    from pollard_pin.paths.curves import thesis_curve

    coarse = thesis_trajectory(samples=41)
    own = desired_trajectory(robot, coarse, period=0.05)
    exact = desired_trajectory(robot, coarse, period=0.05, curve=thesis_curve)
    spline = desired_trajectory(robot, replace(coarse, curve=None), period=0.05)
    np.testing.assert_array_equal(own.q, exact.q)
    np.testing.assert_array_equal(own.a, exact.a)
    assert np.abs(spline.q - exact.q).max() > 1e-4
