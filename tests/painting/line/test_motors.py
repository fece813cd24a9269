"""The motors along a line's world path (paint/line/motors.py, docs/model.md §24): a long
wait at the start pose checked from its last LEADING_RUN + 1 rows gives the whole path's
figures to the bit, and a failure is named as the whole path's check names it."""
import numpy as np
import pytest

WAIT = 100  # rows held at the start pose before the path moves


def _waiting_path():
    """The thesis trajectory (at rest at its ends) after WAIT rows at its first pose: (poses,
    rates, accelerations) and the sample times [s]."""
    import pollard_pin as pp

    tr = pp.thesis_trajectory(samples=101)
    P = np.concatenate([np.repeat(tr.poses[:1], WAIT, axis=0), tr.poses])
    D = np.concatenate([np.zeros((WAIT, 6)), tr.d_poses])
    A = np.concatenate([np.zeros((WAIT, 6)), tr.dd_poses])
    D[WAIT], A[WAIT] = 0.0, 0.0  # the path starts at rest
    return (P, D, A), 0.01 * np.arange(len(P))


def test_first_kept_leaves_out_all_but_the_waits_last_rows():
    from pollard_pin.painting.checks.motion import LEADING_RUN
    from pollard_pin.painting.line.motors import first_kept

    t = 0.01 * np.arange(300)
    leave = t[WAIT]  # rows 0..WAIT-1 before it
    j = first_kept(t, leave)
    assert j == WAIT - 1 - LEADING_RUN == 83
    assert first_kept(t, leave + 0.5e-12) == j
    assert first_kept(t, t[LEADING_RUN + 1]) == 0  # a wait too short to leave out
    assert first_kept(t, 0.0) == 0


def test_the_wait_checked_once_gives_the_whole_checks_figures(robot):
    from pollard_pin.dynamics.motors import load_actuators
    from pollard_pin.painting.checks.motion import motion
    from pollard_pin.painting.line.motors import first_kept, wait_motion

    act = load_actuators()
    path, t = _waiting_path()
    whole = motion(robot, act, *path)
    j = first_kept(t, t[WAIT])
    calls = []
    got = wait_motion(robot, act, [a[j:] for a in path], j,
                      lambda: calls.append(1) or path)
    assert not calls and len(got.tau) == len(path[0]) - j > 0
    for name in ("tau", "torque", "torque_ratio", "speed_ratio"):
        a, b = getattr(whole, name), getattr(got, name)
        assert np.array_equal(a[j:], b), name
        assert np.array_equal(a.max(axis=0), b.max(axis=0)), name
    assert whole.torque_ratio.max() > 0.01


@pytest.mark.parametrize("bad", [WAIT - 1, WAIT + 30])  # in the wait kept, later
def test_a_failure_is_the_whole_checks(robot, bad):
    """Out of reach at row ``bad``: the rows from j fail, and the whole path's check names
    the failure (the sample, the words), as without the rows left out."""
    from pollard_pin.dynamics.motors import load_actuators
    from pollard_pin.painting.checks.motion import motion
    from pollard_pin.painting.errors import ReachError
    from pollard_pin.painting.line.motors import first_kept, wait_motion

    act = load_actuators()
    (P, D, A), t = _waiting_path()
    P = P.copy()
    P[bad:bad + 3, 0] += 1.0
    if bad < WAIT:  # the whole wait moved: still the same rows
        P[:WAIT, 0] = P[bad, 0]
    with pytest.raises(ReachError) as ref:
        motion(robot, act, P, D, A)
    j = first_kept(t, t[WAIT])
    calls = []
    with pytest.raises(ReachError) as got:
        wait_motion(robot, act, [a[j:] for a in (P, D, A)], j,
                    lambda: calls.append(1) or (P, D, A))
    assert calls == [1]
    assert got.value.sample == ref.value.sample and str(got.value) == str(ref.value)


def test_the_screen_refuses_over_the_ratings_at_least(robot):
    """A too slow line's screen: over the ratings at the path's samples, "at least" that."""
    from dataclasses import replace

    from pollard_pin.dynamics.motors import load_actuators
    from pollard_pin.painting.checks.motion import motion
    from pollard_pin.painting.errors import LineSpeedError
    from pollard_pin.painting.line.motors import first_kept, screen_motors

    act = load_actuators()
    path, t = _waiting_path()
    j = first_kept(t, t[WAIT])
    screen_motors(robot, act, path, 0.01, j)  # within the ratings: passes
    worst = float(motion(robot, act, *path).utilisation.max())
    weak = replace(act, units=tuple(replace(u, peak_torque=u.peak_torque * worst / 2,
                                            max_speed=u.max_speed * worst / 2)
                                    for u in act.units))
    with pytest.raises(LineSpeedError) as exc:
        screen_motors(robot, weak, path, 0.01, j)
    assert "a motor needs at least 200 % of its peak torque or speed" in str(exc.value)
    assert not exc.value.too_fast
