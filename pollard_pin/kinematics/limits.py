"""Joint position limits (the ``[limits]`` of the parameter file, docs/model.md §3) checked on
stacks of configurations: an angle is inside when it, or the angle 2πk away from it, lies in
[lower, upper] (docs/model.md §22)."""
from __future__ import annotations

import numpy as np

TWO_PI = 2.0 * np.pi


def limit_violations(params, q, names) -> tuple[np.ndarray, np.ndarray]:
    """(side, excess), each (..., J) for the joints ``names`` (columns of q in that order):
    side 0 inside its limits (or NaN), −1 below the lower limit, +1 above the upper one — the
    nearer of the two, angles taken modulo 2π — and excess [rad] ≥ 0 the distance to it."""
    q = np.asarray(q, dtype=float)
    lim = [params.joint_limits(n) for n in names]
    lo = np.array([x.lower for x in lim])
    hi = np.array([x.upper for x in lim])
    with np.errstate(invalid="ignore"):
        shifted = lo + np.mod(q - lo, TWO_PI)  # in [lo, lo + 2π)
        over = shifted - hi  # > 0: outside, above hi by this much ...
        under = lo + TWO_PI - shifted  # ... and below lo (the next turn) by this
        outside = (over > 0.0) & (hi - lo < TWO_PI)
        side = np.where(outside, np.where(over <= under, 1, -1), 0).astype(np.int8)
    return side, np.where(outside, np.minimum(over, under), 0.0)
