"""Motor and gearbox sizing (docs/model.md §19): the motor model recomputed from a ``run`` CSV,
the uniform time scaling against a brute-force scan of durations, the time-optimal traversal
replayed through ``run``, the torque–speed figure, and bad actuator files."""
import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.cli import main
from pollard_pin.dynamics import actuators as A
from pollard_pin.dynamics.inverse import inverse_dynamics
from pollard_pin.io.table import read_result

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "actuators.toml"
RATINGS = tomllib.loads(EXAMPLE.read_text())  # read directly, not through the loader
NAMES = ("theta21", "theta21_1", "theta21_2", "theta1615", "theta1716", "theta1817")
SAMPLES = 801


def _cli(argv, capsys):
    try:
        code = main(argv)
    except SystemExit as exc:
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err


def _motor(cols, name):
    """τm, ωm of one actuator from run-CSV columns, written out from the issue's formula."""
    r = RATINGS[name]
    n, qd, qdd = r["gear_ratio"], cols[f"d_{name}"], cols[f"dd_{name}"]
    friction = np.array([r["coulomb"] * (1 if v > 0 else -1 if v < 0 else 0) for v in qd])
    tau_m = (cols[f"tau_{name}"] / n + r["rotor_inertia"] * n * qdd + r["viscous"] * n * qd
             + friction)
    return tau_m, n * qd


def _rms(t, y):
    return math.sqrt(np.trapezoid(y * y, t) / (t[-1] - t[0]))


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
    path = A.path_dynamics(robot, thesis.ik)
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
    path = A.path_dynamics(robot, thesis.ik)
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
    path = A.PathDynamics(np.linspace(0, 1, n), z, b, c, q_s, z, 1.0)
    uni = A.uniform_min_duration(act, path)
    xs = np.linspace(1e-6, 2.0, 2_000_001)
    worst = np.abs(xs * xs - xs + 0.045) / peak
    assert np.any(worst[xs > 0.95] <= 1)  # feasible again at a shorter duration
    x_first = xs[np.argmax(worst > 1)]
    assert 1 / uni.duration == pytest.approx(x_first, abs=2e-6)
    assert (uni.actuator, uni.limit) == ("theta21", "peak_torque")


def test_time_optimal_replays_within_the_limits_with_one_active(tmp_path, capsys, act):
    retimed, replay, rep = tmp_path / "fast.csv", tmp_path / "replay.csv", tmp_path / "r.json"
    code, _, err = _cli(["size", "--samples", str(SAMPLES), "--quiet", "--actuators",
                         str(EXAMPLE), "--retime", str(retimed), "--format", "json",
                         "--out", str(rep), "--plot", str(tmp_path / "fig")], capsys)
    assert code == 0, err
    assert (tmp_path / "fig" / "torque_speed.png").stat().st_size > 10_000
    assert _cli(["run", "--trajectory", str(retimed), "--quiet", "--out", str(replay)],
                capsys)[0] == 0
    report = json.loads(rep.read_text())
    cols = read_result(replay).columns
    t = cols["t"]
    assert t[-1] == pytest.approx(report["time_optimal_duration"], rel=1e-12)
    assert t[-1] <= report["uniform_min_duration"]
    assert t[-1] <= max(report["uniform_min_duration_by_limit"][k]
                        for k in ("peak_torque", "speed"))
    use = []
    for name in NAMES:
        r = RATINGS[name]
        tau_m, w_m = _motor(cols, name)
        use += [np.abs(tau_m) / r["peak_torque"], np.abs(w_m) / r["max_speed"]]
        got = report["actuators"][name]
        assert got["time_optimal_rms_motor_torque"] == pytest.approx(_rms(t, tau_m), rel=1e-9)
    use = np.max(use, axis=0)
    assert use.max() <= 1.01
    assert np.all(cols[f"d_{NAMES[0]}"][[0, -1]] == 0)  # rest to rest
    # at every interior sample a limit binds to within 2 %, except where the discretised
    # profile turns from one limit to the next: at most two samples in a row
    slack = np.flatnonzero(use[1:-1] < 0.98) + 1
    runs = np.split(slack, np.flatnonzero(np.diff(slack) > 1) + 1) if len(slack) else []
    assert all(len(run) <= 2 for run in runs), runs
    shares = report["time_optimal_binding_shares"]
    assert sum(shares.values()) == pytest.approx(1.0)
    assert shares["switching"] < 0.15  # ≈ 80 switches, 2 % of the time at 2001 samples


@pytest.mark.parametrize("viscous", [5e-5, 1e-4])
def test_time_optimal_with_strong_viscous_friction(robot, thesis, act, viscous):
    # b·ωm at the motors' max speed is half / all of their peak torque: the viscous term,
    # evaluated at the frictionless profile's speed, left no traversal and the sizing
    # claimed the path uncontrollable. Replayed through the pipeline, the limits hold.
    from pollard_pin.viz.sizing import actuator_sizing

    sticky = A.Actuators(act.names, tuple(A.Actuator(**{**u.__dict__, "viscous": viscous})
                                          for u in act.units))
    sized = actuator_sizing(robot, thesis, sticky)
    cols = pp.run_pipeline(robot, sized.retimed).columns()
    use = []
    for name in NAMES:
        r = {**RATINGS[name], "viscous": viscous}
        n, qd = r["gear_ratio"], cols[f"d_{name}"]
        tau_m = (cols[f"tau_{name}"] / n + r["rotor_inertia"] * n * cols[f"dd_{name}"]
                 + viscous * n * qd + r["coulomb"] * np.sign(qd))
        use.append(np.maximum(np.abs(tau_m) / r["peak_torque"], np.abs(n * qd) / r["max_speed"]))
    use = np.max(use, axis=0)
    assert 1.0 - 1e-9 <= use.max() <= 1.0 + 1e-9  # a limit is used, none is exceeded
    assert cols["t"][-1] == pytest.approx(sized.timing.duration, rel=1e-12)
    assert sized.timing.duration < sized.uniform.duration


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


def test_torque_speed_figure_draws_points_and_envelopes(robot, thesis, act):
    from pollard_pin.viz.sizing import actuator_sizing, to_markdown, torque_speed_figure

    sized = actuator_sizing(robot, thesis, act)
    fig = torque_speed_figure(sized)
    lines = {ln.get_gid(): ln for ax in fig.axes for ln in ax.get_lines() if ln.get_gid()}
    for j, name in enumerate(NAMES):
        np.testing.assert_array_equal(lines[f"given_{name}"].get_ydata(),
                                      sized.given.torque[:, j])
        np.testing.assert_array_equal(lines[f"time_optimal_{name}"].get_xdata(),
                                      sized.optimal.speed[:, j])
        env = lines[f"envelope_{name}"]
        assert np.abs(env.get_ydata()).max() == RATINGS[name]["peak_torque"]
        assert np.abs(env.get_xdata()).max() == RATINGS[name]["max_speed"]
    text = to_markdown(sized.report)
    assert "time-optimal" in text and f"{sized.timing.duration:.4g} s" in text


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
     "must be finite"),
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


def test_size_of_a_two_sample_path_is_one_line_and_writes_nothing(tmp_path, capsys):
    # rest to rest over one interval never moves: the retimed CSV had t = inf, the JSON NaN
    code, out, err = _cli(["size", "--actuators", str(EXAMPLE), "--samples", "2", "--quiet",
                           "--format", "json", "--retime", str(tmp_path / "r.csv")], capsys)
    assert code == 2 and out == "", (out, err)
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "needs at least 3 samples of the path, got 2" in lines[0], err
    assert "Traceback" not in err and not list(tmp_path.iterdir())


def test_size_checks_destinations_before_the_work(tmp_path, capsys):
    (tmp_path / "afile").write_text("x")
    for extra in (["--retime", str(tmp_path / "afile" / "x.csv")],
                  ["--plot", str(tmp_path / "afile")],
                  ["--actuators", str(tmp_path / "none.toml")]):
        code, _, err = _cli(["size", "--actuators", str(EXAMPLE), *extra], capsys)
        assert code == 2 and len(err.strip().splitlines()) == 1, err


def test_toppra_missing_gives_one_line(tmp_path):
    import subprocess
    import sys

    code = ("import sys; sys.modules['toppra'] = None\nfrom pollard_pin.cli import main\n"
            f"sys.exit(main(['size', '--samples', '101', '--quiet', '--actuators', "
            f"{str(EXAMPLE)!r}, '--out', {str(tmp_path / 'never.md')!r}]))")
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "pip install 'toppra>=0.6.10,<0.7'" in lines[0], r.stderr
    assert not (tmp_path / "never.md").exists()
