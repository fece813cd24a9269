"""The run's statistics (run/stats.py): the streamed summary is the whole run's, a window's
statistics are the direct maxima, and the duty figures are a trapezoid recount of the columns."""
import re

import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.paths.curves import thesis_trajectory
from pollard_pin.run import StreamOptions, stream_run
from pollard_pin.run.stats import RunStats, duty_figures, summary


def test_summary_is_the_whole_runs(robot, tmp_path):
    traj = thesis_trajectory(samples=801)
    stats = stream_run(robot, traj, tmp_path / "s.csv", StreamOptions(chunk=128))
    whole = summary(pp.run_pipeline(robot, traj))
    number = re.compile(r"-?\d+\.?\d*(?:e[+-]?\d+)?")
    same_words = re.compile(r"\s+")
    assert [same_words.sub(" ", number.sub("#", x)) for x in (summary(stats), whole)] == \
        [same_words.sub(" ", number.sub("#", whole))] * 2  # the same lines
    a, b = (np.array([float(x) for x in number.findall(s)]) for s in (summary(stats), whole))
    # And the same figures (θ1817's τ is round-off): achieves 1.1e-16.
    assert np.abs(a - b).max() <= 1e-14


def test_stats_of_a_window_equal_a_direct_computation(robot):
    r = pp.run_pipeline(robot, thesis_trajectory(samples=301))
    st = RunStats("thesis", "analytic")
    st.add(r.ik, r.columns())
    assert st.peak["tau_theta21"] == np.abs(r.dynamics.tau[:, 0]).max()
    f = np.linalg.norm(r.dynamics.closure_forces, axis=2).max(0)
    assert st.closure_force == [f[0], f[1]]
    assert st.sigma_serial == r.ik.sigma_serial.min()


def test_duty_figures_are_a_trapezoid_recount(robot):
    # Each figure recomputed from the columns by numpy's trapezoid rule (the peaks by max).
    cols = pp.run_pipeline(robot, thesis_trajectory(samples=101)).columns()
    got = duty_figures(cols, robot.actuated)
    t = cols["t"]
    T = t[-1] - t[0]
    assert list(got["actuators"]) == list(robot.actuated)
    for n, a in got["actuators"].items():
        tau, qd, p = cols[f"tau_{n}"], cols[f"d_{n}"], cols[f"power_{n}"]
        want = {"peak_torque": np.abs(tau).max(),
                "rms_torque": np.sqrt(np.trapezoid(tau ** 2, t) / T),
                "peak_speed": np.abs(qd).max(), "peak_power": np.abs(p).max(),
                "energy": np.trapezoid(np.abs(p), t), "net_work": cols[f"work_{n}"][-1]}
        assert a.keys() == want.keys()
        for key, value in want.items():  # achieves ≈ 1e-16 relative
            assert a[key] == pytest.approx(value, rel=1e-13, abs=1e-300), (n, key)
    for i in (1, 2):
        f = np.sqrt(sum(cols[f"f{i}_{c}"] ** 2 for c in "xyz"))
        j = got["spherical_joints"][f"spherical_{i}"]
        assert j["peak_force"] == f.max() and j["peak_time"] == t[np.argmax(f)]
        assert j["rms_force"] == pytest.approx(np.sqrt(np.trapezoid(f ** 2, t) / T), rel=1e-13)
