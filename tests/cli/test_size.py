"""``pollard-pin size`` (cli/size.py, docs/model.md §19): its motor figures are those of a
``run`` CSV through the motor model written out here, the time-optimal cycle it writes replays
within the ratings, it reports a failed cycle and still the rest, a missing toppra or a bad
actuator file is one line, and it checks every destination before the work. (The numbers:
tests/dynamics/test_sizing.py, test_motors.py, test_timeopt.py.) SIGTERM and Ctrl-C stop it
promptly with one line and nothing written, an interrupt inside a ctypes call too (cli/main.py;
below)."""
import ctypes
import json
import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from cli_run import ctrl_c_as_at_a_terminal
from examples_planned import THESIS_SAMPLES
from motor_model import EXAMPLE, NAMES, RATINGS, ROOT
from motor_model import cli as _cli
from motor_model import motor as _motor
from motor_model import rms as _rms

import pollard_pin as pp
from pollard_pin.cli import size as size_cli
from pollard_pin.dynamics import timeopt as TO
from pollard_pin.io.table import read_result
from pollard_pin.paths.curves import wait_then_strokes

SAMPLES = THESIS_SAMPLES  # the session's thesis_sized (tests/examples_planned.py)


@pytest.mark.parametrize("extra", [["--retime", "{d}/afile/x.csv"], ["--plot", "{d}/afile"],
                                   ["--actuators", "{d}/none.toml"]])
def test_size_checks_destinations_before_the_work(tmp_path, capsys, extra):
    (tmp_path / "afile").write_text("x")
    extra = [x.format(d=tmp_path) for x in extra]
    code, _, err = _cli(["size", "--actuators", str(EXAMPLE), *extra], capsys)
    assert code == 2 and len(err.strip().splitlines()) == 1, err


def test_motor_quantities_match_a_run_csv(tmp_path, capsys, thesis_sized):
    run_csv = tmp_path / "run.csv"
    common = ["--samples", str(SAMPLES), "--quiet"]
    assert _cli(["run", *common, "--out", str(run_csv)], capsys)[0] == 0
    code, err, folder = thesis_sized  # size, same samples: its report (--format json)
    assert code == 0, err
    rep = folder / "r.json"
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


def test_time_optimal_replays_within_the_limits_with_one_active(tmp_path, capsys,
                                                                thesis_sized):
    code, err, folder = thesis_sized  # size --samples 801 --retime … --plot …
    retimed, replay, rep = folder / "fast.csv", tmp_path / "replay.csv", folder / "r.json"
    assert code == 0, err
    assert (folder / "fig" / "torque_speed.png").stat().st_size > 10_000
    assert _cli(["run", "--trajectory", str(retimed), "--quiet", "--out", str(replay)],
                capsys)[0] == 0
    report = json.loads(rep.read_text())
    cols = read_result(replay).columns
    t = cols["t"]
    assert t[-1] == pytest.approx(report["time_optimal_duration"], rel=1e-12)
    assert t[-1] <= report["uniform_min_duration"]
    use = []
    for name in NAMES:
        r = RATINGS[name]
        tau_m, w_m = _motor(cols, name)
        use += [np.abs(tau_m) / r["peak_torque"], np.abs(w_m) / r["max_speed"]]
        got = report["actuators"][name]
        assert got["time_optimal_rms_motor_torque"] == pytest.approx(_rms(t, tau_m), rel=1e-9)
    use = np.max(use, axis=0)
    # at the samples the limits hold to TOPP-RA's absolute 1e-8 on ṡ² (seen: 1 + 2.6e-6 where
    # the arc-length path is slowest in a bend, ṡ² = 1.7e-4)
    assert use.max() <= 1 + 1e-4
    between = report["time_optimal_between_samples"]
    assert use.max() <= between["worst_utilisation"] + 1e-12 <= TO.TARGET + 1e-12
    assert np.all(cols[f"d_{NAMES[0]}"][[0, -1]] == 0)  # rest to rest
    shares = report["time_optimal_binding_shares"]
    assert sum(shares.values()) == pytest.approx(1.0)
    assert shares["switching"] < 0.15


def test_a_paint_program_keeps_its_passes_and_its_spray_column(panel_painted, panel_sized):
    """examples/paint.toml's program (`paint`'s path.csv: tests/examples_planned.py) sprays
    throughout (its turnarounds too): ``--retime`` keeps every row, the spray column with it,
    at the planned times (seen: exact), and the report's time-optimal cycle is the planned
    one, saying why (the gun-off stretches retimed: tests/dynamics/test_passes.py). The
    session's `size --retime … --format json --out …` of it (tests/examples_planned.py)."""
    src = pp.from_csv(panel_painted / "path.csv")
    code, err, folder = panel_sized
    out, rep = folder / "rt.csv", folder / "r.json"
    assert code == 0, err
    got = pp.from_csv(out)
    for key in ("poses", "d_poses", "dd_poses", "spray"):
        assert np.array_equal(getattr(got, key), getattr(src, key)), key
    assert np.abs((got.t - got.t[0]) - (src.t - src.t[0])).max() < 1e-12
    report = json.loads(rep.read_text())
    assert report["time_optimal_duration"] == pytest.approx(src.t[-1] - src.t[0], abs=1e-12)
    assert report["time_optimal_start_end"] == "rest to rest, the passes (gun on) as planned"
    assert report["time_optimal_film"]["gun_off_stretches"] == 0


def test_size_reports_when_the_time_optimal_cycle_fails(tmp_path, capsys):
    """Rest to rest over one interval never moves: TOPP-RA has no answer, the given
    trajectory's ratios and the uniform scaling are still reported, the failure in one line."""
    out, retime = tmp_path / "r.json", tmp_path / "r.csv"
    code, _, err = _cli(["size", "--actuators", str(EXAMPLE), "--samples", "2", "--quiet",
                         "--format", "json", "--out", str(out)], capsys)
    assert code == 0, err
    lines = err.strip().splitlines()
    assert len(lines) == 2 and "needs at least 3 samples of the path, got 2" in lines[1], err
    report = json.loads(out.read_text())
    assert report["time_optimal_duration"] is None
    assert "needs at least 3 samples" in report["time_optimal_error"]
    assert report["uniform_min_duration"] > 0
    assert report["actuators"]["theta21"]["peak_motor_torque_ratio"] > 0
    code, text, err = _cli(["size", "--actuators", str(EXAMPLE), "--samples", "2", "--quiet",
                            "--retime", str(retime)], capsys)
    assert code == 2 and "uniform time scaling" in text and "**failed**" in text
    assert "Traceback" not in err and not retime.exists()
    assert len(err.strip().splitlines()) == 1 and "not written" in err


def test_toppra_missing_gives_one_line(tmp_path):

    code = ("import sys; sys.modules['toppra'] = None\nfrom pollard_pin.cli import main\n"
            f"sys.exit(main(['size', '--samples', '101', '--quiet', '--actuators', "
            f"{str(EXAMPLE)!r}, '--out', {str(tmp_path / 'never.md')!r}]))")
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "pip install 'toppra>=0.6.10,<0.7'" in lines[0], r.stderr
    assert not (tmp_path / "never.md").exists()


def catches_term(proc, within=120.0):
    """Wait until the process catches SIGTERM (the command line's handlers are installed, so
    the imports are done), then a moment more; on a busy machine the imports alone may take
    seconds. Without /proc, a fixed 2 s."""
    status = Path(f"/proc/{proc.pid}/status")
    if not status.exists():
        time.sleep(2.0)
        return
    end = time.monotonic() + within
    while time.monotonic() < end and proc.poll() is None:
        caught = next((int(line.split()[1], 16) for line in status.read_text().splitlines()
                       if line.startswith("SigCgt:")), 0)
        if caught >> (signal.SIGTERM - 1) & 1:
            break
        time.sleep(0.05)
    time.sleep(0.3)


@pytest.mark.parametrize("signum, code, word", [(signal.SIGTERM, 143, "terminated"),
                                                (signal.SIGINT, 130, "interrupted")])
def test_size_stops_on_a_signal_with_one_line(tmp_path, signum, code, word):
    pp.to_csv(wait_then_strokes(40_000), tmp_path / "long.csv")  # size takes ≈ 8 s here
    out = tmp_path / "out"
    out.mkdir()
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.Popen(
        [sys.executable, "-m", "pollard_pin.cli", "size", "--trajectory", str(tmp_path /
         "long.csv"), "--actuators", str(EXAMPLE), "--quiet", "--out", str(out / "r.md"),
         "--retime", str(out / "fast.csv")], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
        env=env, start_new_session=True,  # Ctrl-C goes to the process alone
        preexec_fn=ctrl_c_as_at_a_terminal)
    catches_term(proc)  # past the imports (the command's handlers are in), into the work
    assert proc.poll() is None, proc.communicate()
    sent = time.monotonic()
    proc.send_signal(signum)
    try:
        _, err = proc.communicate(timeout=30)
    finally:
        proc.kill()
    # a hang guard, not a timing claim (the suite holds none): the stop takes 0.07-0.47 s
    # here, depending on where the signal lands; scripts/benchmark.py measures it
    assert time.monotonic() - sent < 20.0
    assert proc.returncode == code
    assert err.decode().splitlines() == [f"pollard-pin size: {word}, nothing written"]
    assert list(out.iterdir()) == []


def test_an_interrupt_inside_a_ctypes_call_is_one_line(monkeypatch, capsys):
    class Slow:  # a ctypes argument whose conversion is interrupted (as rtree's are)
        @classmethod
        def from_param(cls, value):
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(5)  # the handler raises here, within the call
            return ctypes.c_int(value)

    labs = ctypes.CDLL(None).labs
    labs.argtypes = [Slow]

    monkeypatch.setattr(size_cli, "run", lambda args: labs(1))
    previous = signal.signal(signal.SIGTERM, lambda *_: (_ for _ in ()).throw(
        KeyboardInterrupt))
    try:  # what the command sees: ctypes wraps the interrupt
        with pytest.raises(ctypes.ArgumentError):
            labs(1)
    finally:
        signal.signal(signal.SIGTERM, previous)
    code, out, err = _cli(["size", "--actuators", str(EXAMPLE)], capsys)
    assert (code, out, err) == (143, "", "pollard-pin size: terminated, nothing written\n")


def test_retime_carries_the_trajectorys_gravity_and_robot(robot, tmp_path, capsys):
    """A hung robot's path (gravity +z in its base, written by hand in the sidecar as a cell
    writes it, with its frame and robot): ``size --retime`` writes them into the retimed
    file's sidecar, and ``size`` of the retimed file sizes it under +z: its peak motor
    torques are the library's on a model with that gravity (equal to 1e-12 relative; seen
    identical) and far from a standard-gravity sizing of the same file (which is what the
    retimed file used to get)."""
    from pollard_pin.dynamics.motors import load_actuators, motor_load_of
    from pollard_pin.model.gravity import with_gravity

    path = tmp_path / "p.csv"
    # the figure eight: its time-optimal grid, the cost, is shorter than the thesis curve's
    pp.to_csv(pp.from_csv(ROOT / "examples" / "figure8.csv"), path)
    side = path.with_name("p.units.json")
    meta = json.loads(side.read_text())
    carried = {"frame": "robot 'under' base frame", "robot": {"name": "under"},
               "gravity_base": [0.0, 0.0, 9.81]}
    meta["metadata"].update(carried)
    side.write_text(json.dumps(meta))
    fast = tmp_path / "fast.csv"
    code, _, err = _cli(["size", "--trajectory", str(path), "--actuators", str(EXAMPLE),
                         "--retime", str(fast), "--out", str(tmp_path / "a.md"), "--quiet"],
                        capsys)
    assert code == 0, err
    got = json.loads(fast.with_name("fast.units.json").read_text())["metadata"]
    assert {k: got[k] for k in carried} == carried
    reports = {}
    for name, keep in (("fast", True), ("bare", False)):
        if not keep:  # the retimed file without the carried keys: standard gravity
            (tmp_path / "bare.csv").write_bytes(fast.read_bytes())
            side = {**json.loads(fast.with_name("fast.units.json").read_text())}
            side["metadata"] = {k: v for k, v in side["metadata"].items() if k not in carried}
            (tmp_path / "bare.units.json").write_text(json.dumps(side))
        code, out, err = _cli(["size", "--trajectory", str(tmp_path / f"{name}.csv"),
                               "--actuators", str(EXAMPLE), "--format", "json", "--quiet"],
                              capsys)
        assert code == 0, err
        assert ("gravity (0, 0, 9.81)" in err) is keep, err
        reports[name] = json.loads(out)["actuators"]
    hung = with_gravity(robot, [0.0, 0.0, 9.81])
    act = load_actuators(EXAMPLE)
    run = pp.run_pipeline(hung, pp.from_csv(fast))
    # the library's peak motor torques on that model (what actuator_sizing reports of the
    # given motion: its motor_load_of, without solving the time-optimal cycle again)
    lib = dict(zip(act.names, motor_load_of(hung, act, run.ik, run.dynamics).peak_torque))
    for n in NAMES:
        want = float(lib[n])
        assert reports["fast"][n]["peak_motor_torque"] == pytest.approx(want, rel=1e-12)
    gap = max(abs(reports["bare"][n]["peak_motor_torque"] / lib[n] - 1) for n in NAMES)
    assert gap > 0.1, gap
