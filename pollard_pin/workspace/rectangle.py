"""The largest axis-aligned rectangle of True cells in a 2-D boolean grid (docs/model.md §22).

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
