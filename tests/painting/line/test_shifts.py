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
