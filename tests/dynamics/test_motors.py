"""Motors and gearboxes (docs/model.md §19): breakaway friction at rest, the uniform time
scaling against a brute-force scan of durations, and the motors as joint losses. (The motor
model against a ``run`` CSV and bad actuator files, through ``size``: tests/cli/test_size.py;
the path's exact dynamics: tests/dynamics/test_path.py.)"""

from pathlib import Path

import numpy as np
import pytest
from motor_model import EXAMPLE, NAMES, RATINGS
from motor_model import motor as _motor
from motor_model import rms as _rms
from refusals import WRONG, refused

import pollard_pin as pp
from pollard_pin.dynamics import motors as A
from pollard_pin.dynamics.inverse import inverse_dynamics
from pollard_pin.dynamics.path import PathDynamics, path_dynamics

SAMPLES = 801


@pytest.fixture(scope="module")
def thesis(robot):
    return pp.run_pipeline(robot, pp.thesis_trajectory(samples=SAMPLES))


@pytest.fixture(scope="module")
def act():
    return A.load_actuators(EXAMPLE)


def _feasible(robot, duration, samples=SAMPLES):
    """Brute force: solve the thesis curve at ``duration`` from scratch, check all limits."""
    res = pp.run_pipeline(robot, pp.thesis_trajectory(duration=duration, samples=samples))
    cols = res.columns()
    worst = 0.0
    for name in NAMES:
        r = RATINGS[name]
        tau_m, w_m = _motor(cols, name)
        worst = max(worst, np.abs(tau_m).max() / r["peak_torque"],
                    _rms(cols["t"], tau_m) / r["continuous_torque"],
                    np.abs(w_m).max() / r["max_speed"])
    return worst


def test_uniform_min_duration_matches_a_brute_force_scan(robot, thesis, act):
    path = path_dynamics(robot, thesis.ik)
    uni = A.uniform_min_duration(act, path)
    d = uni.duration
    assert uni.limit in A.LIMITS and uni.actuator in NAMES
    assert _feasible(robot, d) == pytest.approx(1.0, abs=1e-9)  # exactly at a limit
    assert _feasible(robot, d * (1 - 1e-4)) > 1.0
    scan = np.concatenate([np.linspace(d * 1.0001, 3 * d, 30), [25.0, 60.0]])
    assert all(_feasible(robot, D) <= 1.0 for D in scan)
    # below D the scan finds the first failure where the exact scaling says
    below = np.linspace(0.3 * d, d * 0.9999, 12)
    assert all(_feasible(robot, D) > 1.0 for D in below)
    # each limit alone: the binding one gives D, the others no more
    assert uni.by_limit[uni.limit] == d and max(uni.by_limit.values()) == d


def test_uniform_holds_at_every_longer_duration_when_feasibility_is_not_monotone():
    """A synthetic load whose motor torque τm = x² − x + 0.045 (x = 1/D) dips below −peak and
    comes back: feasible at long and again at some short durations, infeasible between. The
    answer is the longest failing duration, found here by a fine scan."""
    n, peak = 3, 0.05
    units = (A.Actuator(gear_ratio=100.0, rotor_inertia=0.0, viscous=0.01, coulomb=0.0,
                        peak_torque=peak, continuous_torque=peak, max_speed=1e9),)
    act = A.Actuators(NAMES, units * 6, "synthetic")
    z = np.zeros((n, 6))
    b, c, q_s = z.copy(), z.copy(), z.copy()
    b[:, 0], c[:, 0], q_s[:, 0] = 100.0, 4.5, -1.0  # β = 1, γ = 0.045, δ = b·N·q_s = −1
    path = PathDynamics(np.linspace(0, 1, n), z, b, c, q_s, z, 1.0)
    uni = A.uniform_min_duration(act, path)
    xs = np.linspace(1e-6, 2.0, 2_000_001)
    worst = np.abs(xs * xs - xs + 0.045) / peak
    assert np.any(worst[xs > 0.95] <= 1)  # feasible again at a shorter duration
    x_first = xs[np.argmax(worst > 1)]
    assert 1 / uni.duration == pytest.approx(x_first, abs=2e-6)
    assert (uni.actuator, uni.limit) == ("theta21", "peak_torque")


def test_reflected_inertia_as_joint_losses(robot, thesis, act):
    """JointLosses from the actuators put N²Jm, N²b on the joints: with Coulomb set aside,
    the joint torque with losses over N is the motor torque of the motor model."""
    no_dry = A.Actuators(act.names, tuple(A.Actuator(**{**u.__dict__, "coulomb": 0.0})
                                          for u in act.units))
    losses = no_dry.joint_losses(robot.joint_names)
    ia = robot.actuated_v
    assert np.count_nonzero(losses.armature) == 6
    np.testing.assert_array_equal(losses.armature[ia], act.column("gear_ratio") ** 2
                                  * act.column("rotor_inertia"))
    with_losses = inverse_dynamics(robot, thesis.ik, losses=losses, energies=False).tau
    ik = thesis.ik
    expected = A.motor_torque(no_dry, thesis.dynamics.tau, ik.v[:, ia], ik.a[:, ia])
    np.testing.assert_allclose(with_losses / act.column("gear_ratio"), expected, rtol=0,
                               atol=1e-14)
    full = act.joint_losses(robot.joint_names)
    np.testing.assert_array_equal(full.coulomb[ia], act.column("gear_ratio")
                                  * act.column("coulomb"))
    # forward dynamics with the motors as losses gives back the motion (reflected inertia)
    tau_full = inverse_dynamics(robot, thesis.ik, losses=full, energies=False).tau
    for k in (50, 400, 700):
        a = pp.forward_dynamics(robot, ik.q[k], ik.v[k], tau_full[k], losses=full)
        np.testing.assert_allclose(a, ik.a[k], rtol=0, atol=1e-8 * np.abs(ik.a[k]).max())


def test_breakaway_friction_at_rest_counts_plus_or_minus_c(act):
    """At q̇ = 0 the Coulomb term is ±c with the sign of the rest of τm (|τm| = |rest| + c),
    not sign(0)·c = 0; moving, it is c·sign(q̇)."""
    c, n = act.column("coulomb"), act.column("gear_ratio")
    tau = np.array([[0.3, -0.2, 0.0, 0.01, -0.01, 0.0]])
    got = A.motor_torque(act, tau, np.zeros((1, 6)), np.zeros((1, 6)))
    np.testing.assert_array_equal(got, tau / n + np.array([1, -1, 1, 1, -1, 1]) * c)
    moving = A.motor_torque(act, tau, np.full((1, 6), -1e-9), np.zeros((1, 6)))
    np.testing.assert_allclose(moving, tau / n - c - act.column("viscous") * n * 1e-9,
                               rtol=0, atol=1e-18)
    # along a path: a joint that stands or turns back counts ±c (breakaway)
    q_s = np.array([[0.0, 1.0], [1.0, 1.0], [-1.0, 1.0], [-2.0, 1.0]])
    np.testing.assert_array_equal(A.breakaway(q_s), [[1, 0], [1, 0], [1, 0], [0, 0]])
    np.testing.assert_array_equal(A.breakaway(q_s, at_rest=[0, 0, 0, 1])[:, 1], [0, 0, 0, 1])


@pytest.mark.parametrize("wrong", [v for v in WRONG if v is not None and not isinstance(v, str)],
                         ids=repr)
def test_load_actuators_refuses_what_is_not_a_path(wrong):
    refused(lambda: pp.load_actuators(wrong), "path")
    refused(lambda: pp.load_actuators(None, names=wrong), "names")


def test_as_actuators_reads_a_path_and_refuses_the_rest():
    """An entry point's ``actuators``: None as is, Actuators as is, a path read by
    load_actuators (str or Path), anything else one line naming the argument."""
    act = pp.load_actuators(EXAMPLE)
    assert A.as_actuators(None) is None and A.as_actuators(act) is act
    assert A.as_actuators(str(EXAMPLE)) == act == A.as_actuators(Path(EXAMPLE))
    for wrong in (3, float("nan"), [1, 2], {"a": 1}, b"bytes"):
        refused(lambda w=wrong: A.as_actuators(w), "actuators")


@pytest.mark.parametrize("k, ok", [("1e-3", True), ("1e9", True), ("9e-4", False),
                                   ("1e-300", False), ("1.5e9", False)])
def test_an_actuator_file_stiffness_is_within_its_range(tmp_path, k, ok):
    # the old loader took 1e-300 (> 0), and the stiffness model refused it later without
    # naming the file or the key: "stiffness of actuator 1 = 1e-300: must be 0.001 to 1e+12"
    path = tmp_path / "act.toml"
    path.write_text(EXAMPLE.read_text().replace("stiffness = 3000.0", f"stiffness = {k}", 1))
    if ok:
        assert A.load_actuators(path).units[0].stiffness == float(k)
        return
    with pytest.raises(A.ActuatorError) as info:
        A.load_actuators(path)
    assert str(info.value) == (f"{path}: 'theta21.stiffness' = {float(k)!r}: must be between "
                               "0.001 and 1e+09 N·m/rad (joint side)"), str(info.value)
