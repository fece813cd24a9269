"""The least distance between two robots' capsules over their samples (painting/checks/
capsule_pairs.py; docs/model.md §26.4): the search that skips what the way travelled proves
farther, against every pair measured at every sample. Through the cell's clearance (robots
and IK): test_cell_clearance.py."""
import numpy as np
import pytest
from capsule_steps import steps

from pollard_pin.kinematics.capsules import segment_distance
from pollard_pin.painting.checks.capsule_pairs import pair_distance


def test_the_pairs_skip_finds_a_dip_between_coarse_samples():
    """Two robots of three parallel capsules (r 10 mm, 0.6 m apart), the second the
    first's copy shifted along x stepping 30 mm a sample: 40 mm apart at sample 8 (between
    the coarse samples 0 and 16, 280 mm), 50 mm at the coarse sample 32. The search skipping
    what the way travelled proves beyond the ceiling finds sample 8, as every sample
    measured does; a way half as long would miss it."""
    k = np.arange(48)
    gap = np.minimum(0.04 + 0.03 * np.abs(k - 8), 0.05 + 0.03 * np.abs(k - 32))
    a1 = np.tile(np.array([[0.0, 0.0, z] for z in (0.0, 0.6, 1.2)]), (48, 1, 1))
    a1[:, :, 1] += 0.005 * np.sin(k)[:, None]  # a sway along the capsules
    b1 = a1 + [0.0, 0.3, 0.0]
    shift = np.zeros((48, 1, 3))
    shift[:, 0, 0] = gap + 0.02
    a2, b2, r = a1 + shift, b1 + shift, np.full(3, 0.01)
    moves = steps(a1, b1) + steps(a2, b2)
    every = pair_distance(a1, b1, a2, b2, r, r)
    assert pair_distance(a1, b1, a2, b2, r, r, moves) == every
    assert every[1] == 8 and every[0] == pytest.approx(0.04, abs=1e-12)
    assert pair_distance(a1, b1, a2, b2, r, r, moves / 2)[1] == 32  # the wrong bound: caught
    # held still at the least: from sample 5 to 12 (its first sample, 5), then from 5 to 40
    # (the coarse sample 16 is the one named, as without the skip); samples the same as the
    # one before are not measured
    for end in (12, 40):
        held = np.minimum(k, 5) + np.maximum(k - end, 0)  # the sample whose place each takes
        h1, h2 = a1[held], a2[held]
        h2[:, :, 0] = 0.05 + 0.03 * np.abs(held - 5)[:, None] + 0.02
        moves = steps(h1, h1 + [0.0, 0.3, 0.0]) + steps(h2, h2 + [0.0, 0.3, 0.0])
        every = pair_distance(h1, h1 + [0.0, 0.3, 0.0], h2, h2 + [0.0, 0.3, 0.0], r, r)
        assert every[1] == (5 if end == 12 else 16) and (moves == 0).sum() == end - 5
        assert pair_distance(h1, h1 + [0.0, 0.3, 0.0], h2, h2 + [0.0, 0.3, 0.0], r, r,
                             moves) == every


def test_the_skip_names_the_brute_forces_least_on_random_walks():
    """Two robots of three capsules on random walks, held still for 20 samples from where
    they come closest (the least held over a run of samples: ties), some cutting into each
    other (a layout refused): the skipping search (every 64th sample first) gives the least
    and its sample of every pair at every sample measured, a tie to the first 16th sample,
    else the first."""
    rng = np.random.default_rng(7)
    r = np.array([0.01, 0.02, 0.005])

    def least(a1, b1, a2, b2):  # every pair at every sample, as pair_distance measures one
        n, i, j = (x.ravel() for x in np.meshgrid(np.arange(len(a1)), range(3), range(3),
                                                  indexing="ij"))
        return (segment_distance(a1[n, i], b1[n, i], a2[n, j], b2[n, j])
                - (r[i] + r[j])).reshape(len(a1), 9).min(axis=1)

    cuts = ties = 0
    for case in range(12):
        n = int(rng.integers(40, 300))
        a1 = np.array([[0.0, 0.0, 0.0], [0.0, 0.3, 0.0], [0.2, 0.0, 0.5]]) + np.cumsum(
            rng.normal(0.0, 0.004, (n, 1, 3)), 0)
        gap = 0.1 if case % 3 else -0.24  # every third: the robots cut into each other
        a2 = a1[:, [2, 0, 1]] + [0.25 + gap, 0.0, 0.0] + np.cumsum(
            rng.normal(0.0, 0.004, (n, 1, 3)), 0)
        k = int(np.argmin(least(a1, a1 + [0.0, 0.0, 0.2], a2, a2 + [0.0, 0.2, 0.0])))
        at = np.minimum(np.arange(n), k) + np.maximum(np.arange(n) - k - 20, 0)
        at = np.minimum(at, n - 1)
        a1, a2 = a1[at], a2[at]  # held from k to k + 20
        b1, b2 = a1 + [0.0, 0.0, 0.2], a2 + [0.0, 0.2, 0.0]
        every = least(a1, b1, a2, b2)
        held = np.flatnonzero(every == every.min())
        grid = held[held % 16 == 0]
        named = int(grid[0] if len(grid) else held[0])
        moves = steps(a1, b1) + steps(a2, b2)
        for below in (np.inf, every.min() + 1e-3):
            assert pair_distance(a1, b1, a2, b2, r, r, moves, below) == (every.min(), named)
        assert pair_distance(a1, b1, a2, b2, r, r) == (every.min(), named)
        cuts += every.min() < 0
        ties += named != held[0]
    assert cuts == 4 and ties > 0  # (a 16th sample named, not the first at the least)
