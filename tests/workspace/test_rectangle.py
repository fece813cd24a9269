"""The largest rectangle, its edge samples and the boundary cells (workspace/rectangle.py)
against brute force."""
import numpy as np

from pollard_pin.workspace.rectangle import boundary_points, edge_samples, largest_rectangle


def brute_rectangle(mask):
    best = 0
    rows, cols = mask.shape
    for r0 in range(rows):
        for r1 in range(r0 + 1, rows + 1):
            for c0 in range(cols):
                for c1 in range(c0 + 1, cols + 1):
                    if mask[r0:r1, c0:c1].all():
                        best = max(best, (r1 - r0) * (c1 - c0))
    return best


def test_largest_rectangle_against_brute_force():
    rng = np.random.default_rng(1)
    for _ in range(60):
        mask = rng.random((rng.integers(1, 9), rng.integers(1, 9))) < rng.uniform(0.3, 0.95)
        found = largest_rectangle(mask)
        best = brute_rectangle(mask)
        if best == 0:
            assert found is None
            continue
        r0, r1, c0, c1 = found
        assert mask[r0:r1, c0:c1].all() and (r1 - r0) * (c1 - c0) == best


def test_boundary_points_against_brute_force():
    rng = np.random.default_rng(2)
    for _ in range(30):
        mask = rng.random((rng.integers(1, 8), rng.integers(1, 8))) < 0.6
        rows, cols = mask.shape
        count = 0
        for r in range(rows):
            for c in range(cols):
                near = [mask[i, j] if 0 <= i < rows and 0 <= j < cols else False
                        for i in (r - 1, r, r + 1) for j in (c - 1, c, c + 1)]
                count += any(near) and not all(near)
        assert boundary_points(mask) == count


def test_edge_samples_walk_the_closed_rectangle():
    # Every sample lies on an edge, each edge is walked in 1/refine steps, corners included,
    # and no sample is repeated: compared with the set written out point by point.
    r0, r1, c0, c1, refine = 2, 5, 1, 3, 4
    got = edge_samples(r0, r1, c0, c1, refine)
    want = set()
    for k in range(refine * (r1 - r0) + 1):
        want |= {(r0 + k / refine, c0), (r0 + k / refine, c1)}
    for k in range(refine * (c1 - c0) + 1):
        want |= {(r0, c0 + k / refine), (r1, c0 + k / refine)}
    assert len(got) == len(want) == len({tuple(p) for p in got})
    assert {tuple(p) for p in got} == want
    assert edge_samples(4, 4, 2, 2, 3).tolist() == [[4.0, 2.0]]  # one cell: one point
