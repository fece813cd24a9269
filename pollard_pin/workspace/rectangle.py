"""The largest axis-aligned rectangle of True cells in a 2-D boolean grid, the samples along
its edges, and the cells a region's boundary may cut (docs/model.md §22).

Row by row, each column keeps the height of its run of True cells ending at the row and the
widest interval [left, right) over which that whole run is True; the rectangle of that height
and interval is maximal, and every maximal rectangle appears so (the classic dynamic
programme). Each row is a few numpy operations over the columns: O(rows) Python steps.
"""
from __future__ import annotations

import numpy as np


def largest_rectangle(mask) -> tuple[int, int, int, int] | None:
    """(row0, row1, col0, col1), half-open, of the largest-area rectangle of True cells of a
    2-D ``mask`` (the first found of equal area, scanning rows downwards); None if no cell is
    True."""
    mask = np.asarray(mask, dtype=bool)
    rows, cols = mask.shape
    idx = np.arange(cols)
    height = np.zeros(cols, dtype=np.int64)
    left = np.zeros(cols, dtype=np.int64)
    right = np.full(cols, cols, dtype=np.int64)
    best, where = 0, None
    for r in range(rows):
        row = mask[r]
        height = np.where(row, height + 1, 0)
        # Nearest False to the left (+1) and to the right, within this row.
        cur_left = np.maximum.accumulate(np.where(row, 0, idx + 1))
        cur_right = np.minimum.accumulate(np.where(row, cols, idx)[::-1])[::-1]
        left = np.where(row, np.maximum(left, cur_left), 0)
        right = np.where(row, np.minimum(right, cur_right), cols)
        area = (right - left) * height
        k = int(np.argmax(area))
        if area[k] > best:
            best = int(area[k])
            where = (r + 1 - int(height[k]), r + 1, int(left[k]), int(right[k]))
    return where


def edge_samples(r0: int, r1: int, c0: int, c1: int, refine: int) -> np.ndarray:
    """(n, 2) fractional grid indices along the closed rectangle [r0, r1] × [c0, c1]: its
    corners and ``refine`` samples per step along each edge."""
    rows = np.linspace(r0, r1, refine * (r1 - r0) + 1)
    cols = np.linspace(c0, c1, refine * (c1 - c0) + 1)
    return np.unique(np.concatenate([
        np.column_stack([rows, np.full_like(rows, c0)]),
        np.column_stack([rows, np.full_like(rows, c1)]),
        np.column_stack([np.full_like(cols, r0), cols]),
        np.column_stack([np.full_like(cols, r1), cols])]), axis=0)


def boundary_points(mask: np.ndarray) -> int:
    """Points of a plane map whose 3 × 3 neighbourhood (beyond the grid: unreachable) mixes
    reachable and unreachable points: the cells the region's boundary may cut, each off by
    at most one cell in ``area`` (docs/model.md §22)."""
    m = np.pad(np.asarray(mask, dtype=bool), 1)
    rows, cols = mask.shape
    near = [m[1 + i:1 + i + rows, 1 + j:1 + j + cols] for i in (-1, 0, 1) for j in (-1, 0, 1)]
    anyr = np.logical_or.reduce(near)
    allr = np.logical_and.reduce(near)
    return int(np.count_nonzero(anyr & ~allr))
