"""The planners' policy, one home for panels, parts and lines (docs/model.md §21, §23, §24):
the motors' reserve, the sampling of the duration searches and of the final check, the path's
time step and the budgets checked before anything is built."""
from __future__ import annotations

UTILISATION = 0.97  # of peak torque and max speed: the planner's reserve for what it samples
TURN_SAMPLES = 48  # per turnaround/ramp in the duration search
CHECK_REFINE = 4  # the final motor check samples the path this many times more densely
MAX_STEP = 0.002  # s: the trajectory's largest time step
STEP_SIGMA = 0.25  # the gun moves at most this many σ per step (film integration, §20)
# Budgets, checked before anything is built: the path's samples (the final motor check
# solves CHECK_REFINE× as many at ≈ 3.3 KB and 20 µs each: ≈ 3.3 GB and 20 s) and the passes
# over all coats (the layout's cross-profile grid grows with their square).
MAX_PATH_SAMPLES = 250_000
MAX_PASSES = 1000
FIRST_DECELERATION = 10.0  # m/s²: the duration search starts from a reversal at this rate


def first_guess(speed: float) -> float:
    """The duration search's first turnaround/ramp duration [s] at pass ``speed`` [m/s]:
    reversing at about FIRST_DECELERATION; the search then finds the shortest the motors
    allow."""
    return 4 * speed / FIRST_DECELERATION


__all__ = ["CHECK_REFINE", "FIRST_DECELERATION", "MAX_PASSES", "MAX_PATH_SAMPLES", "MAX_STEP",
           "STEP_SIGMA", "TURN_SAMPLES", "UTILISATION", "first_guess"]
