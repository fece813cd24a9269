"""The paint planner's errors (one line each, under :class:`pollard_pin.errors.InputError`)."""
from __future__ import annotations

from ..errors import InputError


class PlanError(InputError):
    """No paint program meets the job: one line saying why, where, and what would fit."""


class ReachError(PlanError):
    """A tool pose the path needs is out of reach: ``sample`` indexes the poses checked,
    ``pose`` (6,) is that pose."""

    def __init__(self, message: str, sample: int, pose=None):
        super().__init__(message)
        self.sample, self.pose = sample, pose


class BudgetError(PlanError):
    """A plan over its stated budget (samples, passes): one line with what it would need."""
