"""The one type every paint planner returns: a panel's, a part's, either still or on a line
(:class:`.plan.panel.PaintPlan`, :class:`.plan.part.SurfacePlan`,
:class:`.line.panel.LinePlan`, :class:`.line.part.LinePartPlan`)."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...paths.trajectory import Trajectory


@dataclass(frozen=True)
class PlanResult:
    """A planned program: the ``job`` first, then each kind's layout and program; every kind
    has, by keyword, the robot's path ``trajectory`` (world), its trigger ``spray`` (N,) (1
    sprays), the gun body's ``clearance`` from the part (``painting.checks.clearance.Clearance``),
    each motor's use ``ratios`` (peak_torque, rms_torque, speed: arrays over the
    motors, each over its rating) and ``timings`` [s]."""

    job: Any
    trajectory: Trajectory = field(kw_only=True)
    spray: np.ndarray = field(kw_only=True)
    ratios: dict = field(kw_only=True)
    timings: dict = field(default_factory=dict, kw_only=True)
    clearance: Any = field(default=None, kw_only=True)  # checks.clearance.Clearance

    def motor_use(self, names) -> dict:
        """{motor name: {limit: use over its rating}}, paint.json's ``motors``."""
        return {name: {lim: float(self.ratios[lim][i]) for lim in self.ratios}
                for i, name in enumerate(names)}


__all__ = ["PlanResult"]
