"""The sizing report and cross-checks (viz/report.py): its numbers are the run's columns (what
``run`` writes), recomputed here with the trapezoid rule; the engines agree; Markdown carries
the same numbers; without MuJoCo it says so. (The command: tests/cli/test_report.py.)"""
import json
import sys

import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.run import run_pipeline
from pollard_pin.viz.report import SIZING_FIELDS, report, to_json, to_markdown

SAMPLES = 401
# typed in (docs/model.md §6), not imported: the report's order is checked against it
ACTUATED = ("theta21", "theta21_1", "theta21_2", "theta1615", "theta1716", "theta1817")


@pytest.fixture(scope="module")
def result(robot):
    return run_pipeline(robot, pp.thesis_trajectory(samples=SAMPLES))


@pytest.fixture(scope="module")
def run_csv(result):
    """The columns ``run`` writes for the same trajectory."""
    return result.columns()


@pytest.fixture(scope="module")
def full(robot, result):
    """The report with its cross-checks, through JSON as the CLI writes it."""
    return json.loads(to_json(report(robot, result)))


def _trapz(y, t):
    return float(np.sum((y[1:] + y[:-1]) * np.diff(t)) / 2)


def test_report_numbers_equal_the_run_csv(run_csv, full):
    rep = full
    t = run_csv["t"]
    T = t[-1] - t[0]
    assert rep["trajectory"]["samples"] == len(t) == SAMPLES
    acts = rep["sizing"]["actuators"]
    assert list(acts) == list(ACTUATED)
    for n in ACTUATED:
        tau, qd, p = run_csv[f"tau_{n}"], run_csv[f"d_{n}"], run_csv[f"power_{n}"]
        np.testing.assert_allclose(p, tau * qd, rtol=1e-12, atol=1e-15)
        expected = {
            "peak_torque": np.abs(tau).max(),
            "rms_torque": np.sqrt(_trapz(tau ** 2, t) / T),
            "peak_speed": np.abs(qd).max(),
            "peak_power": np.abs(p).max(),
            "energy": _trapz(np.abs(p), t),
            "net_work": run_csv[f"work_{n}"][-1],
        }
        assert set(acts[n]) == {k for k, _, _ in SIZING_FIELDS}
        for key, value in expected.items():
            assert acts[n][key] == pytest.approx(value, rel=1e-12, abs=1e-18), (n, key)
    # Net work is also ∫P dt of the CSV's power column.
    for n in ACTUATED[:3]:
        # Achieves 3.6e-13 relative.
        assert acts[n]["net_work"] == pytest.approx(_trapz(run_csv[f"power_{n}"], t), rel=5e-11)
    for i in (1, 2):
        f = np.sqrt(sum(run_csv[f"f{i}_{c}"] ** 2 for c in "xyz"))
        j = rep["sizing"]["spherical_joints"][f"spherical_{i}"]
        assert j["peak_force"] == pytest.approx(f.max(), rel=1e-12)
        assert j["peak_time"] == t[np.argmax(f)]
        assert j["rms_force"] == pytest.approx(np.sqrt(_trapz(f ** 2, t) / T), rel=1e-12)
    # The base actuators carry the load (docs/model.md §6): 1.2121 N·m at 401 samples (the
    # peak docs/model.md §18 quotes as 1.21 N·m).
    assert acts["theta21"]["peak_torque"] == pytest.approx(1.2120663, abs=1e-7)


def test_report_cross_checks_agree(full):
    cc = full["cross_check"]
    th = cc["thesis"]
    # Achieved: 2.7e-15 rad, 5.6e-15 relative, MuJoCo 2.1e-15 relative.
    assert th["joint_position_rad"]["max_abs_diff"] < 5e-13
    for key in ("joint_velocity", "joint_acceleration", "torque"):
        assert th[key]["relative"] < 1e-12, key
        assert th[key]["reference_peak"] > 0
    mj = cc["mujoco"]
    try:
        import mujoco  # noqa: F401
    except ImportError:
        assert mj["available"] is False and "not installed" in mj["reason"]
    else:
        assert mj["available"] is True
        assert mj["torque"]["relative"] < 5e-13
        assert mj["closure_force"]["relative"] < 5e-13


def test_report_without_mujoco_says_so(robot, result, monkeypatch):
    monkeypatch.setitem(sys.modules, "mujoco", None)  # import mujoco → ImportError
    rep = report(robot, result)
    assert rep["cross_check"]["mujoco"]["available"] is False
    md = to_markdown(rep)
    assert "MuJoCo cross-check skipped" in md and "not installed" in md
    assert "actuator torques, thesis Euler–Lagrange" in md


def test_report_markdown_table(robot, result):
    md = to_markdown(report(robot, result))
    rep = report(robot, result, cross_check=False)
    lines = md.splitlines()
    assert lines[0].startswith("# Actuator sizing report")
    for n, a in rep["sizing"]["actuators"].items():
        (row,) = [ln for ln in lines if ln.startswith(f"| `{n}` |")]
        cells = [c.strip() for c in row.strip("|").split("|")][1:]
        assert [float(c) for c in cells] == pytest.approx(
            [a[k] for k, _, _ in SIZING_FIELDS], rel=1e-3, abs=1e-300)
        assert len(cells) == len(SIZING_FIELDS)
    # Table headers stay tables: a literal | inside a cell is escaped.
    header = [ln for ln in lines if ln.startswith("| actuator |")][0]
    assert header.count(" | ") == len(SIZING_FIELDS)
    assert "## Cross-checks" in md and "MuJoCo" in md
