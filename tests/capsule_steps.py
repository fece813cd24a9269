"""The way capsules travel, for the tests of the robot pairs' least distance
(test_capsule_pairs.py, test_cell_clearance.py)."""
import numpy as np


def steps(a, b):
    """The farthest a capsule point moves in each step (N − 1,): at an end (ends (N, L, 3))."""
    move = [np.linalg.norm(np.diff(x, axis=0), axis=2) for x in (a, b)]
    return np.maximum(*move).max(axis=1)
