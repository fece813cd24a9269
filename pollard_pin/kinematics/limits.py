"""Joint position limits (the ``[limits]`` of the parameter file, docs/model.md §3) checked on
stacks of configurations: an angle is inside when it, or the angle 2πk away from it, lies in
[lower, upper] (docs/model.md §22)."""
from __future__ import annotations

import math

import numpy as np

from .errors import JointLimitError

TWO_PI = 2.0 * np.pi
# rad: an angle this far inside its limits as it stands is inside by the rule too (its
# shifted angle, lo + mod(q − lo, 2π), errs from q by a few ulps of 2π ≈ 1e-15), so a stack
# all that far inside needs no more (first_violation's fast path, 20× the full rule's speed)
INSIDE_SLACK = 1e-9


def limit_bounds(params, names) -> tuple[np.ndarray, np.ndarray]:
    """(lower, upper) [rad], each (J,), of the joints ``names``: built once where a loop checks
    many configurations (:func:`limit_violations` takes them)."""
    lim = [params.joint_limits(n) for n in names]
    return np.array([x.lower for x in lim]), np.array([x.upper for x in lim])


def limit_violations(params, q, names, bounds=None) -> tuple[np.ndarray, np.ndarray]:
    """(side, excess), each (..., J) for the joints ``names`` (columns of q in that order):
    side 0 inside its limits (or NaN), −1 below the lower limit, +1 above the upper one — the
    nearer of the two, angles taken modulo 2π — and excess [rad] ≥ 0 the distance to it.
    ``bounds``: :func:`limit_bounds` of the same joints, if already built."""
    q = np.asarray(q, dtype=float)
    lo, hi = limit_bounds(params, names) if bounds is None else bounds
    with np.errstate(invalid="ignore"):
        shifted = lo + np.mod(q - lo, TWO_PI)  # in [lo, lo + 2π)
        over = shifted - hi  # > 0: outside, above hi by this much ...
        under = lo + TWO_PI - shifted  # ... and below lo (the next turn) by this
        outside = (over > 0.0) & (hi - lo < TWO_PI)
        side = np.where(outside, np.where(over <= under, 1, -1), 0).astype(np.int8)
    return side, np.where(outside, np.minimum(over, under), 0.0)


def first_violation(params, q, names, bounds=None):
    """The first (sample, joint index, excess [rad]) of a stack q (N, J) outside the limits of
    the joints ``names`` (the rule of :func:`limit_violations`), or None."""
    q = np.atleast_2d(q)
    if bounds is not None and np.all((bounds[0] <= q) & (q <= bounds[1])):
        return None  # inside as they stand: no turn to consider (a loop's fast path)
    if bounds is None:
        bounds = limit_bounds(params, names)
        lo, hi = bounds
        if np.all((lo + INSIDE_SLACK <= q) & (q <= hi - INSIDE_SLACK)):
            return None  # well inside as they stand: inside by the rule (INSIDE_SLACK)
    side, excess = limit_violations(params, q, names, bounds)
    if not side.any():
        return None
    k, j = (int(i) for i in np.argwhere(side)[0])
    return k, j, float(excess[k, j])


def violation_text(params, name: str, angle: float, excess: float) -> str:
    """'joint theta54 at 41.3° is outside its limits [-40°, 40°] by 1.3°'."""
    lim = params.joint_limits(name)
    return (f"joint {name} at {math.degrees(angle):.4g}° is outside its limits "
            f"[{math.degrees(lim.lower):g}°, {math.degrees(lim.upper):g}°] by "
            f"{math.degrees(excess):.3g}°")


def check_joint_limits(robot, q, t=None) -> None:
    """Raise :class:`JointLimitError` at the first sample of q (N, 12) where a tree joint is
    outside its limits: the reach rule of every command (``workspace`` and ``paint`` map and
    plan with it; ``run``, ``size`` and ``simulate`` refuse a path that breaks it)."""
    names = robot.joint_names
    bad = first_violation(robot.params, q, names)
    if bad is None:
        return
    k, j, excess = bad
    raise JointLimitError(violation_text(robot.params, names[j], float(np.atleast_2d(q)[k, j]),
                                         excess),
                          sample=k, time=None if t is None else float(t[k]), chain=names[j],
                          amount=excess)
