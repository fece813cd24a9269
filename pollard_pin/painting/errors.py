"""The paint planner's errors, one line each.

A job the planner cannot paint is a :class:`pollard_pin.errors.SolveError`, as a pose out of
the kinematics' reach is (:class:`pollard_pin.kinematics.errors.UnreachablePoseError`): the
job is a valid one and no program meets it. A value the planner cannot use (a film spacing,
a job of another kind) is an :class:`pollard_pin.errors.InputError`.
"""
from __future__ import annotations

from ..errors import InputError, SolveError


class PlanError(SolveError):
    """No paint program meets the job: one line saying why, where, and what would fit."""


class ReachError(PlanError):
    """A tool pose the path needs is out of reach: ``sample`` indexes the poses checked,
    ``pose`` (6,) is that pose."""

    def __init__(self, message: str, sample: int, pose=None):
        super().__init__(message)
        self.sample, self.pose = sample, pose


class ReportError(SolveError):
    """A report number breaks an invariant the model guarantees (a lower bound over the cycle,
    a transfer efficiency over 100 %): a bug, refused rather than printed."""


class BudgetError(PlanError):
    """A plan over its stated budget (samples, passes): one line with what it would need."""


class ResolutionError(InputError):
    """A film point spacing the film cannot be computed at (not > 0, over σ, or over the
    budget of film points)."""


class JobKindError(InputError):
    """A job of a kind the planner does not handle (one line naming the kind)."""
