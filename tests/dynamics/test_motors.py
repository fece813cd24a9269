"""Motors and gearboxes (docs/model.md §19): the motor model recomputed from a ``run`` CSV,
breakaway friction at rest, the path's exact dynamics, the uniform time scaling against a
brute-force scan of durations, the motors as joint losses, and bad actuator files."""
import json
import math

import numpy as np
import pytest
from motor_model import EXAMPLE, NAMES, RATINGS
from motor_model import cli as _cli
from motor_model import motor as _motor
from motor_model import rms as _rms

import pollard_pin as pp
from pollard_pin.dynamics import motors as A
from pollard_pin.dynamics.inverse import inverse_dynamics
from pollard_pin.dynamics.path import PathDynamics, path_dynamics
from pollard_pin.io.table import read_result

SAMPLES = 801


@pytest.fixture(scope="module")
def thesis(robot):
    return pp.run_pipeline(robot, pp.thesis_trajectory(samples=SAMPLES))


@pytest.fixture(scope="module")
def act():
    return A.load_actuators(EXAMPLE)


def test_motor_quantities_match_a_run_csv(tmp_path, capsys):
    run_csv, rep = tmp_path / "run.csv", tmp_path / "size.json"
    common = ["--samples", str(SAMPLES), "--quiet"]
    assert _cli(["run", *common, "--out", str(run_csv)], capsys)[0] == 0
    code, _, err = _cli(["size", *common, "--actuators", str(EXAMPLE), "--format", "json",
                         "--out", str(rep)], capsys)
    assert code == 0, err
    cols = read_result(run_csv).columns
    report = json.loads(rep.read_text())
    t = cols["t"]
    for name in NAMES:
        tau_m, w_m = _motor(cols, name)
        r, got = RATINGS[name], report["actuators"][name]
        for key, value, rating in (("peak_motor_torque", np.abs(tau_m).max(), r["peak_torque"]),
                                   ("rms_motor_torque", _rms(t, tau_m),
                                    r["continuous_torque"]),
                                   ("peak_motor_speed", np.abs(w_m).max(), r["max_speed"])):
            assert got[key] == pytest.approx(value, rel=1e-12, abs=1e-15), (name, key)
            assert got[key + "_ratio"] == pytest.approx(value / rating, rel=1e-12, abs=1e-15)
    # the shipped example: the 20 s thesis cycle passes with margin, a limit binds when fast
    assert report["given_within_ratings"]
    ratios = [a[k] for a in report["actuators"].values() for k in a
              if k.endswith("_ratio") and not k.startswith(("time_optimal", "gear"))]
    assert max(ratios) < 0.6
    assert report["time_optimal_duration"] < report["uniform_min_duration"] < 20.0


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


def test_path_torques_are_exact_at_another_duration(robot, thesis):
    path = path_dynamics(robot, thesis.ik)
    D = 7.3
    res = pp.run_pipeline(robot, pp.thesis_trajectory(duration=D, samples=SAMPLES))
    # uniform: ṡ = 1/D, s̈ = 0
    np.testing.assert_allclose(res.dynamics.tau, path.b / D**2 + path.c, rtol=0, atol=1e-12)
    np.testing.assert_allclose(res.ik.v[:, robot.actuated_v], path.q_s / D, atol=1e-12)


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


def _with(name, key, value):
    d = {n: dict(RATINGS[n]) for n in NAMES}
    if value is None:
        del d[name][key]
    else:
        d[name][key] = value
    return d


def _toml(d):
    def val(v):
        if isinstance(v, bool):
            return str(v).lower()
        if isinstance(v, float) and math.isnan(v):
            return "nan"
        return repr(v) if not isinstance(v, str) else f'"{v}"'
    return "\n".join(f"[{n}]\n" + "\n".join(f"{k} = {val(v)}" for k, v in t.items())
                     for n, t in d.items()) + "\n"


BAD = [  # (file text, what the one line must name)
    (_toml(_with("theta21", "gear_ratio", None)), "'theta21.gear_ratio' is missing"),
    (_toml(_with("theta21_1", "peak_torqe", 0.05)), "'theta21_1.peak_torqe'"),
    (_toml(_with("theta21", "gear_ratio", 0.0)), "'theta21.gear_ratio' = 0.0: must be > 0"),
    (_toml(_with("theta1716", "peak_torque", -0.05)), "must be > 0"),
    (_toml(_with("theta1716", "viscous", -1e-6)), "'theta1716.viscous' = -1e-06: must be >= 0"),
    (_toml(_with("theta21", "max_speed", "fast")), "must be a number"),
    (_toml(_with("theta21", "coulomb", True)), "must be a number"),
    (_toml(_with("theta21", "rotor_inertia", math.nan)), "'theta21.rotor_inertia' = nan: "
     "must be a finite number"),
    (_toml(_with("theta21", "continuous_torque", 0.08)), "exceeds theta21.peak_torque"),
    # magnitudes that overflowed the motor model (traceback) or gave an infinite cycle
    (_toml(_with("theta21", "gear_ratio", 1e300)), "'theta21.gear_ratio' = 1e+300: must be "
     "between 1e-06 and 1e+06"),
    (_toml(_with("theta21", "rotor_inertia", 1e300)), "must be at most 1e+06 kg·m²"),
    (_toml(_with("theta21", "max_speed", 1e-300)), "'theta21.max_speed' = 1e-300: must be "
     "between 1e-06 and 1e+06 rad/s"),
    (_toml({**{n: RATINGS[n] for n in NAMES}, "theta22": RATINGS["theta21"]}),
     "[theta22] is not an actuator (did you mean"),
    (_toml({n: RATINGS[n] for n in NAMES[:-1]}), "missing table(s) [theta1817]"),
    ("[theta21\n", "is not valid TOML"),
    (_toml(_with("theta21", "peak_torque", 0.006)).replace("continuous_torque = 0.02",
                                                          "continuous_torque = 0.005"),
     "theta21: the static peak motor torque (gravity and Coulomb friction) 0.009231 N·m "
     "already reaches the rating 0.006 N·m"),
]


@pytest.mark.parametrize("text,message", BAD)
def test_bad_actuator_files_give_one_line(tmp_path, capsys, text, message):
    bad = tmp_path / "bad.toml"
    bad.write_text(text)
    out = tmp_path / "never.md"
    code, _, err = _cli(["size", "--actuators", str(bad), "--out", str(out)], capsys)
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and message in lines[0], err
    assert not out.exists()


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
