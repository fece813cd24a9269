"""The shifts along the line that keep a world program in reach (painting/line/shifts.py):
the window searched follows a robot far down the line, and the scan finds the shifts there."""
import numpy as np

from pollard_pin.painting.line.shifts import SHIFT_RANGE, feasible_shifts, shift_window


def test_the_shift_search_follows_a_robot_far_down_the_line(robot):
    # a cell's robot 4 stands ~3 m down the line: the part reaches it past the first 2 m
    lo = 0.01
    assert shift_window(lo, -0.75) == (lo, lo + SHIFT_RANGE)  # the example's: unchanged
    for far in (1.2, 3.2, 9.5):
        start, stop = shift_window(lo, -far)
        assert stop - start == SHIFT_RANGE and start + 0.9 <= far <= stop - 0.9
    e = np.array([0.0, 1.0, 0.0])
    poses = np.array([[0.55, -3.2, 0.0, 0.0, 0.0, 0.0]])  # in reach once carried 3.2 m
    assert feasible_shifts(robot, poses, e, lo, SHIFT_RANGE, anchor=-3.2) is None
    start, stop = shift_window(lo, -3.2)
    a, b = feasible_shifts(robot, poses, e, start, stop - start, anchor=-3.2)
    assert start < a <= 3.2 <= b < stop


def test_the_stacked_scan_equals_the_scan_shift_by_shift(robot):
    # a tilted pass of 40 poses, scanned along the line: the stacked judgement of every
    # shift and the bisected ends equal those of reach() called shift by shift (the brute
    # force, as the scan was first written)
    import math

    from pollard_pin.painting.checks.motion import reach
    from pollard_pin.painting.errors import ReachError
    from pollard_pin.painting.line.shifts import SHIFT_BISECT, SHIFT_STEP, fits

    def alone(poses, e, x):
        p = np.array(poses)
        p[:, :3] += x * e
        try:
            reach(robot, p)
        except ReachError:
            return False
        return True

    e = np.array([0.0, 1.0, 0.0])
    u = np.linspace(0.0, 1.0, 40)[:, None]
    poses = np.hstack([0.5 + 0.0 * u, -0.9 + 0.4 * u, 0.1 - 0.1 * u, 0.2 * u,
                       np.zeros_like(u), np.zeros_like(u)])
    lo, span = 0.01, SHIFT_RANGE
    xs = np.arange(math.ceil(lo / SHIFT_STEP - 1e-9),
                   math.floor((lo + span) / SHIFT_STEP + 1e-9) + 1) * SHIFT_STEP
    ok = np.array([alone(poses, e, x) for x in xs])
    assert 10 < ok.sum() < len(xs) - 10  # in and out of reach along the scan
    assert np.array_equal(fits(robot, poses, e, xs), ok)
    edges = np.diff(np.concatenate([[0], ok.astype(int), [0]]))
    starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    k = int(np.argmax(stops - starts))

    def refine(good, bad):
        for _ in range(SHIFT_BISECT):
            mid = 0.5 * (good + bad)
            good, bad = (mid, bad) if alone(poses, e, mid) else (good, mid)
        return good

    a, b = xs[starts[k]], xs[stops[k] - 1]
    assert feasible_shifts(robot, poses, e, lo, span) == (refine(a, a - SHIFT_STEP),
                                                         refine(b, b + SHIFT_STEP))


def test_the_coarse_scan_finds_the_full_scans_longest_run(monkeypatch):
    """The scan tries every SCAN_COARSE-th shift first and then only where a run may lie
    (shifts.scan): on random patterns of shifts in reach (runs long and short, ties, none),
    the longest run it finds is the one of every shift tried (the brute force), and where a
    long run is met it tries fewer shifts."""
    from pollard_pin.painting.line import shifts

    rng = np.random.default_rng(7)
    fewer = 0
    for trial in range(300):
        n = int(rng.integers(1, 420))
        truth = rng.random(n) < rng.choice([0.05, 0.3, 0.7, 0.95])
        if trial % 3 == 0:  # one long run among noise
            a = int(rng.integers(0, n))
            truth[a:a + int(rng.integers(1, 60))] = True
        xs = np.arange(n) * 0.005
        tried = []

        def fits(robot, poses, e, x, truth=truth, tried=tried):
            i = np.rint(np.asarray(x) / 0.005).astype(int)
            tried.extend(i.tolist())
            return truth[i]

        monkeypatch.setattr(shifts, "fits", fits)
        ok = shifts.scan(None, np.zeros((3, 6)), np.array([0.0, 1.0, 0.0]), xs)
        assert len(tried) == len(set(tried)) and not ok[~truth].any()  # each once, no guess
        assert ok.any() == truth.any()
        if truth.any():
            assert shifts.longest_run(ok) == shifts.longest_run(truth)
        fewer += len(tried) < n
    assert fewer > 50


def test_a_second_windows_scan_takes_the_first_windows_shifts(monkeypatch):
    """The shifts a first window's scan judged (``known``) are not judged again by a second,
    overlapping window's (choose_shift's robot far down the line): each shift judged once
    over both, and each window's answer the one of its scan alone."""
    from pollard_pin.painting.line import shifts

    rng = np.random.default_rng(11)
    for _ in range(40):
        truth = rng.random(720) < rng.choice([0.05, 0.5, 0.95])
        tried = []

        def fits(robot, poses, e, x, truth=truth, tried=tried):
            i = np.rint(np.asarray(x) / 0.005).astype(int)
            tried.extend(np.atleast_1d(i).tolist())
            return truth[i]

        monkeypatch.setattr(shifts, "fits", fits)
        a, b = sorted(rng.integers(0, 700, 2)), sorted(rng.integers(0, 700, 2))
        first, second = (np.arange(lo, hi + 20) * 0.005 for lo, hi in (a, b))
        args = (None, np.zeros((3, 6)), np.array([0.0, 1.0, 0.0]))
        alone = [shifts.scan(*args, xs) for xs in (first, second)]
        tried.clear()
        known: dict = {}
        both = [shifts.scan(*args, xs, known) for xs in (first, second)]
        assert all(np.array_equal(p, q) for p, q in zip(both, alone))
        assert len(tried) == len(set(tried))  # no shift judged twice
        assert all(known[x] == truth[int(round(x / 0.005))] for x in known)
