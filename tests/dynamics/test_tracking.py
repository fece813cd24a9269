"""The control laws and what they see (docs/model.md §18): the classical computed torque
imposes the commanded actuator acceleration wherever the robot is, its error dynamics are the
designed ones up to the zero-order hold, the controller sees actuator encoders and forward
kinematics, tracking RMS is time-weighted, and the step checks of the integrator."""
import numpy as np
import pytest
from thesis_curves import thesis_head

from pollard_pin.dynamics.control import (
    ComputedTorque,
    ControlError,
    FeedforwardPD,
    Gains,
    desired_trajectory,
)
from pollard_pin.dynamics.plant import Plant
from pollard_pin.dynamics.tracking import (
    MeasurementNoise,
    TrackingOptions,
    check_steps,
    integration_steps,
    sensed_state,
    simulate_tracking,
    step_used,
)
from pollard_pin.errors import InputError
from pollard_pin.kinematics.closure import solve_closure
from pollard_pin.kinematics.singularity import actuator_velocity_map
from pollard_pin.model.build import constraint_jacobian
from pollard_pin.paths.curves import thesis_trajectory
from pollard_pin.paths.trajectory import Trajectory

OFFSET = np.array([0.005, -0.004, 0.003, 0.02, -0.01, 0.02])  # m, rad: a pose step


def _rest(pose, seconds: float = 0.2, step: float = 1e-3) -> Trajectory:
    t = np.linspace(0.0, seconds, int(round(seconds / step)) + 1)
    poses = np.tile(pose, (len(t), 1))
    return Trajectory(t, poses, np.zeros_like(poses), np.zeros_like(poses), name="rest")


def _closed_state(robot, theta, dtheta, guess):
    q = solve_closure(robot, theta, guess)
    Jc = constraint_jacobian(robot.model, robot.data, robot.constraint_models,
                             robot.constraint_datas, q)
    return q, actuator_velocity_map(Jc, robot.actuated_v, robot.passive_v) @ dtheta


def test_computed_torque_imposes_the_commanded_acceleration(robot):
    """At closed states off the reference (actuators 0.02 rad and 0.1 rad/s off), the exact
    plant (no Baumgarte term) under the computed torque accelerates its actuators by exactly
    θ̈_d + ω²e + 2ζωė: 2.1e-13 relative to the largest command (round-off through the light
    wrist's inertia; asserted 2e-11). The feedforward-PD law does not (3.8e-2): it cancels
    the dynamics along the reference only."""
    desired = desired_trajectory(robot, thesis_trajectory(samples=201))
    plant = Plant(robot, baumgarte=(0.0, 0.0))
    ia = robot.actuated_v
    rng = np.random.default_rng(0)
    worst = {}
    for law in (ComputedTorque, FeedforwardPD):
        control, worst[law] = law(robot, desired), 0.0
        for k in rng.integers(0, len(desired.t) - 1, 8):
            q, v = _closed_state(robot, desired.q[k, ia] + rng.normal(0, 0.02, 6),
                                 desired.v[k, ia] + rng.normal(0, 0.1, 6), desired.q[k])
            a = plant.acceleration(q, v, control(desired.t[k], q, v))[ia]
            g = control.gains
            command = (0.5 * (desired.a[k, ia] + desired.a[k + 1, ia])
                       + g.kp * (desired.q[k, ia] - q[ia]) + g.kd * (desired.v[k, ia] - v[ia]))
            worst[law] = max(worst[law], np.abs(a - command).max() / np.abs(command).max())
    assert worst[ComputedTorque] <= 2e-11
    assert worst[FeedforwardPD] > 1e-2


def _deviation(robot, law, period: float) -> float:
    """Start at rest at the thesis start, reference a step OFFSET away at rest: the largest
    gap between the actuator errors and the designed error dynamics (the double integrator
    under the held command ω²e + 2ζωė, one recursion per actuator), relative to |e(0)|."""
    pose = thesis_trajectory(samples=3).poses[0]
    start, goal = _rest(pose), _rest(pose + OFFSET)
    d_start, d_goal = (desired_trajectory(robot, tr, period) for tr in (start, goal))
    g = Gains()
    res = simulate_tracking(robot, start, TrackingOptions(law(robot, d_goal, g), desired=d_start,
                                                          control_period=period))
    e = d_goal.q[0, robot.actuated_v] - res.q[:, robot.actuated_v]
    ek, ed, model = e[0].copy(), np.zeros(6), [e[0].copy()]
    for _ in range(len(e) - 1):
        for _ in range(int(round(1e-3 / period))):  # output every 1 ms
            u = g.kp * ek + g.kd * ed
            ek, ed = ek + period * ed - 0.5 * period**2 * u, ed - period * u
        model.append(ek.copy())
    return float(np.abs(e - np.array(model)).max() / np.abs(e[0]).max())


def test_error_dynamics_are_the_designed_ones(robot):
    """Computed torque's actuator errors follow ë + 2ζωė + ω²e = 0 (zero-order held) up to a
    gap proportional to the hold T: 1.07e-4 at 1 ms, 5.34e-5 at 0.5 ms (ratio 2.00); the
    extrapolation to T → 0 (2·gap(T/2) − gap(T)) is 1.2e-7 (asserted 1e-5). Feedforward-PD's
    gap is model error, not hold: 7.35e-3 at both periods."""
    ct = [_deviation(robot, ComputedTorque, p) for p in (1e-3, 5e-4)]
    ff = [_deviation(robot, FeedforwardPD, p) for p in (1e-3, 5e-4)]
    assert 1.9 <= ct[0] / ct[1] <= 2.1
    assert abs(2 * ct[1] - ct[0]) <= 1e-5
    assert min(ff) > 5e-3 and abs(ff[0] / ff[1] - 1) < 0.05


@pytest.fixture(scope="module")
def seen(robot):
    """What a controller is given at every tick (t, q, v), with and without noise."""
    traj = thesis_head(0.3)
    desired = desired_trajectory(robot, traj)
    out = {}
    for label, noise in (("exact", None), ("noisy", MeasurementNoise(1e-4, 1e-2, 3))):
        calls = []
        inner = ComputedTorque(robot, desired)

        def recording(t, q, v, calls=calls, inner=inner):
            calls.append((t, q.copy(), v.copy()))
            return inner(t, q, v)

        res = simulate_tracking(robot, traj,
                                TrackingOptions(recording, desired=desired, noise=noise))
        out[label] = (res, calls)
    return out


def test_controller_sees_encoders_and_forward_kinematics(robot, seen):
    """Without noise the controller gets the plant's actuator angles and rates exactly, and
    passive joints that are the plant's true ones moved onto exactly closed loops: the plant
    holds its loops to 1e-11 m only (Baumgarte), forward kinematics closes them to 1e-12 m, so
    q̂_p − q_p = Jc_p⁻¹ (c(q̂) − c(q)) to first order and v̂_p − v_p = −Jc_p(q̂)⁻¹ Jc(q̂) v
    exactly. Sizes 4.7e-11 rad and 1.7e-9 rad/s; the predictions hold to 7.5e-16 rad and
    1.2e-15 rad/s (asserted 1e-13)."""
    from pollard_pin.model.build import constraint_residual

    model, data = robot.model, robot.data
    cms, cds = robot.constraint_models, robot.constraint_datas
    ia, ip = robot.actuated_v, robot.passive_v
    res, calls = seen["exact"]
    on_sample = {round(t, 9): (q, v) for t, q, v in calls}
    size = gap_q = gap_v = 0.0
    for k, t in enumerate(res.t):
        q, v = on_sample[round(t, 9)]
        assert np.array_equal(q[ia], res.q[k, ia]) and np.array_equal(v[ia], res.v[k, ia])
        Jp = constraint_jacobian(model, data, cms, cds, res.q[k])[:, ip]
        c = (constraint_residual(model, data, cms, cds, q)
             - constraint_residual(model, data, cms, cds, res.q[k]))
        gap_q = max(gap_q, np.abs(q[ip] - res.q[k, ip] - np.linalg.solve(Jp, c)).max())
        Jc = constraint_jacobian(model, data, cms, cds, q)
        gap_v = max(gap_v, np.abs(v[ip] - res.v[k, ip]
                                  + np.linalg.solve(Jc[:, ip], Jc @ res.v[k])).max())
        size = max(size, np.abs(q[ip] - res.q[k, ip]).max())
    assert 1e-12 < size <= 1e-10  # the loops' own error moved through Jc_p⁻¹
    assert gap_q <= 1e-13 and gap_v <= 1e-13


def test_noisy_encoders_move_the_passive_joints_by_kinematics(robot, seen):
    """With encoder noise the passive joints follow the noisy actuator angles through the
    loops: each state given to the controller closes its loops (≤ 1e-12 m) and is the forward
    kinematics of its own actuator angles; the plant's true passive angles are not given."""
    from pollard_pin.model.build import constraint_residual

    res, calls = seen["noisy"]
    ia, ip = robot.actuated_v, robot.passive_v
    k = len(res) // 2
    _, q, v = next(c for c in calls if abs(c[0] - res.t[k]) < 1e-9)
    assert 1e-6 < np.abs(q[ia] - res.q[k, ia]).max() < 1e-3  # the noise, σ = 1e-4 rad
    assert np.abs(q[ip] - res.q[k, ip]).max() > 1e-6  # not the plant's truth
    r = constraint_residual(robot.model, robot.data, robot.constraint_models,
                            robot.constraint_datas, q)
    assert np.abs(r).max() <= 1e-12
    q_fk, _ = sensed_state(robot, q[ia], v[ia], res.q[k])
    assert np.abs(q_fk - q).max() <= 1e-10


def test_steps_are_counted_and_checked(robot):
    res = simulate_tracking(robot, thesis_head(0.1),
                            TrackingOptions("pd", dt=4e-4, control_period=1e-3))
    assert res.steps == integration_steps(0.1, 4e-4, 1e-3) == 300
    assert step_used(4e-4, 1e-3) == pytest.approx(1e-3 / 3, rel=1e-15)
    assert res.settings["dt"] == step_used(4e-4, 1e-3)
    with pytest.raises(ControlError, match="time step 100 s is longer than the control "
                                           "period 0.001 s"):
        check_steps(100.0, 1e-3)
    with pytest.raises(ControlError, match="control period must be > 0 s"):
        check_steps(1e-3, float("nan"))


def _outside(robot, q) -> float:
    """Largest excess [deg] of a tree joint beyond its [limits], by direct comparison in degrees
    (the stacks here stay within a turn of home: no 2π wrap to consider)."""
    worst = 0.0
    for j, name in enumerate(robot.joint_names):
        lim = robot.params.joint_limits(name)
        deg = np.degrees(q[:, j])
        worst = max(worst, float(np.max(np.maximum(np.degrees(lim.lower) - deg,
                                                   deg - np.degrees(lim.upper)))))
    return worst


def test_a_saturated_robot_that_falls_out_of_its_limits_stops(robot):
    """At 0.8 N·m (the reference needs 1.2) the robot sags off the path and out of its joint
    limits: the run stops, naming the joint, the time and since when it is saturated. Waived,
    the same run completes and its rows do leave the limits (checked in degrees, independently
    of kinematics.limits)."""
    from pollard_pin.dynamics.forward import SimulationError

    traj = thesis_head(2.0)
    desired = desired_trajectory(robot, traj, 5e-3)
    with pytest.raises(SimulationError, match=r"stopped at t = 1\.\d+ s: the plant left its "
                                              r"joint limits: joint theta\w+ at .* by .*°; the "
                                              r"torque has been saturated since t = 0\.6"):
        simulate_tracking(robot, traj, TrackingOptions(
            "feedforward-pd", control_period=5e-3, torque_limit=0.8, desired=desired))
    free = simulate_tracking(robot, traj, TrackingOptions(
        "feedforward-pd", control_period=5e-3, torque_limit=0.8, desired=desired,
        joint_limits=False, loop_tolerance=np.inf))
    assert _outside(robot, free.q) > 0.1  # 0.3° at the stop, further later
    assert free.saturation_time > 0.5


def test_loops_that_open_beyond_the_tolerance_stop_the_run(robot):
    """The thesis curve squeezed into 1 s: at 4 ms RK4 steps the loops open to 3.6e-4 m, and
    the run stops at LOOP_TOLERANCE; at 0.5 ms they hold to 7.5e-8 m, 100× below it."""
    from pollard_pin.dynamics.forward import SimulationError
    from pollard_pin.dynamics.tracking import LOOP_TOLERANCE

    traj = thesis_trajectory(duration=1.0, samples=51)
    desired = desired_trajectory(robot, traj, 4e-3)
    kw = dict(control_period=4e-3, desired=desired)
    with pytest.raises(SimulationError, match=r"the plant's loops opened to .* m \(loop "
                                              r"tolerance 1e-05 m.*reduce the time step"):
        simulate_tracking(robot, traj, TrackingOptions("feedforward-pd", dt=4e-3, **kw))
    free = simulate_tracking(robot, traj, TrackingOptions("feedforward-pd", dt=4e-3,
                                                          loop_tolerance=np.inf, **kw))
    assert np.abs(free.closure_residual).max() > LOOP_TOLERANCE
    fine = simulate_tracking(robot, traj, TrackingOptions("feedforward-pd", dt=5e-4, **kw))
    assert fine.max_closure_residual <= LOOP_TOLERANCE / 100


def test_sensing_hands_its_jacobian_and_velocity_map_to_the_controllers(robot):
    """sensed_kinematics' Jc and N are those built afresh at its q (bit for bit), and every
    built-in controller gives the same torque with them as building its own (what a tick
    saves: Jc and N built once, not two and three times)."""
    from pollard_pin.dynamics.control import make_controller
    from pollard_pin.dynamics.tracking import sensed_kinematics

    traj = thesis_head(0.05)
    desired = desired_trajectory(robot, traj)
    ia, ip = robot.actuated_v, robot.passive_v
    k = 20
    theta = desired.q[k, ia] + 1e-4
    q, v, Jc, N = sensed_kinematics(robot, theta, desired.v[k, ia], desired.q[k])
    q2, v2 = sensed_state(robot, theta, desired.v[k, ia], desired.q[k])
    np.testing.assert_array_equal(q, q2)
    np.testing.assert_array_equal(v, v2)
    J = constraint_jacobian(robot.model, robot.data, robot.constraint_models,
                            robot.constraint_datas, q)
    np.testing.assert_array_equal(Jc, J)
    np.testing.assert_array_equal(N, actuator_velocity_map(J, ia, ip))
    for name in ("computed-torque", "feedforward-pd"):
        c = make_controller(name, robot, desired)
        np.testing.assert_array_equal(c(desired.t[k], q, v, Jc, N), c(desired.t[k], q, v))
    # pd with N: gravity as Nᵀ g_tree instead of the [Sᵀ Jcᵀ] solve of the closure forces;
    # achieved 2.2e-16 N·m (torques ≈ 0.44 N·m); g_tree on the actuators, unprojected, is
    # 0.6 N·m off
    c = make_controller("pd", robot, desired)
    np.testing.assert_allclose(c(desired.t[k], q, v, Jc, N), c(desired.t[k], q, v), rtol=0,
                               atol=2e-14)


def test_compiled_sensing_tracks_as_pinocchio_sensing(robot, monkeypatch):
    """The simulation senses by one compiled call per tick (kinematics/sensing.py); with
    Pinocchio's sensing instead (close_loops, the velocity map, the drift: the reference path)
    every output column agrees to round-off, and so does the controller's torque with the
    sensed a₀ and without it."""
    from pollard_pin.dynamics.plant import ModelMismatch
    from pollard_pin.kinematics.sensing import LoopSensor, reference_state

    traj = thesis_head(0.05)
    desired = desired_trajectory(robot, traj)
    kw = dict(errors=ModelMismatch(0.05, 0.1), desired=desired,
              noise=MeasurementNoise(1e-5, 1e-4, 3))
    fast = simulate_tracking(robot, traj, TrackingOptions("computed-torque", **kw)).columns()
    ia = robot.actuated_v
    theta, dtheta = desired.q[20, ia] + 1e-4, desired.v[20, ia] - 0.1
    q, v, Jc, N, a0 = LoopSensor(robot)(theta, dtheta, desired.q[20])
    c, t = ComputedTorque(robot, desired), desired.t[20]
    # achieved 7e-16 N·m (torques ≈ 1 N·m); twice a₀ would change it by 0.17 N·m
    np.testing.assert_allclose(c(t, q, v, Jc, N, a0), c(t, q, v), rtol=0, atol=1e-13)
    monkeypatch.setattr(LoopSensor, "__call__",
                        lambda self, th, dth, g=None: reference_state(self.robot, th, dth, g))
    ref = simulate_tracking(robot, traj, TrackingOptions("computed-torque", **kw)).columns()
    # achieved, relative to the column's largest entry (or 1): 3e-13 for dd_theta1817 (the
    # nearly massless last wrist joint), ≤ 2e-14 for the others
    for name, col in ref.items():
        assert np.abs(fast[name] - col).max() <= 3e-11 * max(np.abs(col).max(), 1.0), name


def test_simulate_tracking_refuses_what_is_not_a_trajectory(robot):
    """A string for the trajectory, None for the robot: one InputError line, not an
    AttributeError from inside."""
    with pytest.raises(ControlError, match=r"^trajectory = 'x': expected a Trajectory \(t, "):
        simulate_tracking(robot, "x")
    with pytest.raises(InputError, match="^robot = None: expected a Robot"):
        simulate_tracking(None, thesis_trajectory(samples=11))
