"""Joint position limits on stacks of configurations (kinematics/limits.py) against a brute
force over the turns q + 2πk."""
import numpy as np

from pollard_pin.kinematics.limits import limit_violations


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
