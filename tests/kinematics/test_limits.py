"""Joint position limits (kinematics/limits.py): the rule on stacks of configurations against
a brute force over the turns q + 2πk, and one reach rule everywhere (docs/model.md §22): the
limits that workspace and paint apply also bound run, size and simulate, unless waived
(``--ignore-limits``)."""
import re
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_cli

import pollard_pin as pp
from pollard_pin.kinematics.errors import JointLimitError
from pollard_pin.kinematics.limits import check_joint_limits, limit_violations

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def crossing(robot, seconds: float = 2.0, samples: int = 101) -> pp.Trajectory:
    """Rest to rest (quintic time law, exact derivatives) from home to a pose that needs θ43
    at 125.3°, beyond its 125° limit (every other rule of run holds)."""
    t = np.linspace(0.0, seconds, samples)
    s = t / seconds
    h = 10 * s**3 - 15 * s**4 + 6 * s**5
    hd = (30 * s**2 - 60 * s**3 + 30 * s**4) / seconds
    hdd = (60 * s - 180 * s**2 + 120 * s**3) / seconds**2
    off = np.array([-0.17, -0.15, 0.04, 0.0, 0.0, 0.0])
    home = np.asarray(robot.params.home_pose)
    return pp.Trajectory(t, home + h[:, None] * off, hd[:, None] * off, hdd[:, None] * off,
                         name="crossing")


def _excess_deg(robot, q) -> np.ndarray:
    """(N, 12) degrees beyond [lower, upper], by direct comparison (no 2π wrap here)."""
    lo = np.array([np.degrees(robot.params.joint_limits(n).lower) for n in robot.joint_names])
    hi = np.array([np.degrees(robot.params.joint_limits(n).upper) for n in robot.joint_names])
    deg = np.degrees(q)
    return np.maximum(np.maximum(lo - deg, deg - hi), 0.0)


def test_run_pipeline_refuses_a_joint_beyond_its_limits(robot):
    traj = crossing(robot)
    free = pp.run_pipeline(robot, traj, joint_limits=False)
    excess = _excess_deg(robot, free.ik.q)
    first = int(np.argmax(excess.max(axis=1) > 0))
    j = robot.joint_names.index("theta43")
    assert first == 70 and excess[first].argmax() == j
    with pytest.raises(JointLimitError) as info:
        pp.run_pipeline(robot, traj)
    err = info.value
    assert (err.sample, err.chain) == (first, "theta43")
    assert abs(np.degrees(err.amount) - excess[first, j]) < 1e-9  # same number, two ways
    assert str(err).startswith(f"sample {first} (t = 1.4 s): joint theta43 at 125.3° is "
                               "outside its limits [70°, 125°] by 0.254°")


@pytest.mark.parametrize("trajectory", ["thesis", str(EXAMPLES / "figure8.csv")])
def test_shipped_trajectories_keep_the_limits(robot, trajectory):
    traj = (pp.thesis_trajectory() if trajectory == "thesis" else pp.from_csv(trajectory))
    result = pp.run_pipeline(robot, traj, dynamics=False)  # no JointLimitError
    assert _excess_deg(robot, result.ik.q).max() == 0.0
    check_joint_limits(robot, result.ik.q)


@pytest.mark.parametrize("command", [
    ["run", "--out", "{tmp}/run.csv"],
    ["size", "--actuators", str(EXAMPLES / "actuators.toml"), "--out", "{tmp}/size.md"],
    ["simulate", "--out", "{tmp}/sim.csv", "--control-period", "0.005"],
])
def test_commands_refuse_the_crossing_and_run_it_when_waived(robot, tmp_path, capsys, command):
    src = tmp_path / "crossing.csv"
    pp.to_csv(crossing(robot), src)
    argv = [a.format(tmp=tmp_path) for a in command] + ["--trajectory", src, "--quiet"]
    out = Path(argv[argv.index("--out") + 1])
    code, _, err = run_cli(argv, capsys)
    assert code == 2 and not out.exists(), err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert re.search(r"joint theta43 at 125\.\d° is outside its limits \[70°, 125°\] by "
                     r"0\.\d+°", lines[0])
    # simulate checks its reference at the control ticks, between the samples: by time
    where = "the reference at t = 1.385 s" if command[0] == "simulate" else "sample 70"
    assert where in lines[0] and "--ignore-limits" in lines[0]
    code, _, err = run_cli(argv + ["--ignore-limits"], capsys)
    assert code == 0 and out.exists(), err


def brute(lo, hi, q):
    """(side, excess) by trying q + 2πk for k in −3 … 3: inside if one lies in [lo, hi], else
    the nearer of the two limits over all turns."""
    turns = q + 2 * np.pi * np.arange(-3, 4)
    if np.any((lo <= turns) & (turns <= hi)):
        return 0, 0.0
    above, below = turns[turns > hi] - hi, lo - turns[turns < lo]
    a, b = above.min(), below.min()
    return (1, a) if a <= b else (-1, b)


def test_against_brute_force(robot):
    names = robot.joint_names
    rng = np.random.default_rng(3)
    q = rng.uniform(-2 * np.pi, 2 * np.pi, (400, len(names)))
    side, excess = limit_violations(robot.params, q, names)
    assert side.shape == excess.shape == q.shape
    checked = 0
    for j, n in enumerate(names):
        lim = robot.params.joint_limits(n)
        if lim.upper - lim.lower >= 2 * np.pi:
            assert not side[:, j].any()
            continue
        for k in range(len(q)):
            s, e = brute(lim.lower, lim.upper, q[k, j])
            assert side[k, j] == s and abs(excess[k, j] - e) <= 1e-12, (n, q[k, j])
            checked += s != 0
    assert checked > 100  # the random angles do leave the limits


def test_home_is_inside_and_nan_is_not_a_violation(robot):
    q = robot.home()[None]
    side, excess = limit_violations(robot.params, q, robot.joint_names)
    assert not side.any() and not excess.any()
    side, _ = limit_violations(robot.params, np.full_like(q, np.nan), robot.joint_names)
    assert not side.any()


def test_limit_violations_modulo_two_pi():
    params = pp.load_params()
    lim = params.joint_limits("theta21")  # [−105°, −35°]
    q = np.radians([[-70.0], [-70.0 + 360.0], [-30.0], [-110.0], [-70.0 - 720.0], [np.nan]])
    side, excess = limit_violations(params, q, ("theta21",))
    assert side[:, 0].tolist() == [0, 0, 1, -1, 0, 0]
    np.testing.assert_allclose(excess[:, 0], np.radians([0, 0, 5, 5, 0, 0]), atol=1e-12)
    assert lim.lower < lim.upper


def test_the_fast_path_agrees_with_the_rule_at_and_near_the_limits(robot):
    """first_violation's fast path (a stack well inside as it stands) never passes a stack
    the rule (limit_violations: angles modulo 2π) finds outside: stacks at the limits, a few
    ulps and INSIDE_SLACK off them, a turn away and in between, against the rule itself."""
    from pollard_pin.kinematics.limits import INSIDE_SLACK, first_violation, limit_bounds

    names = robot.joint_names
    lo, hi = limit_bounds(robot.params, names)
    rng = np.random.default_rng(4)
    edges = [lo, hi, np.nextafter(lo, -9), np.nextafter(hi, 9), lo + INSIDE_SLACK,
             hi - INSIDE_SLACK, lo + 2 * INSIDE_SLACK, hi - 2 * INSIDE_SLACK]
    seen = {True: 0, False: 0}
    for _ in range(400):
        q = lo + rng.random((6, len(names))) * (hi - lo)
        rows, cols = rng.integers(0, 6, 3), rng.integers(0, len(names), 3)
        for r, c in zip(rows, cols):
            q[r, c] = edges[rng.integers(len(edges))][c] + 2 * np.pi * rng.integers(-1, 2)
        outside = bool(limit_violations(robot.params, q, names)[0].any())
        assert (first_violation(robot.params, q, names) is not None) == outside
        seen[outside] += 1
    assert min(seen.values()) > 20  # both answers met
