"""The planning: the checks along a program (reach, limits, motors), the panel's and the
part's planners, the one plan result type (docs/model.md §21, §23)."""
from .compliance import program_deflection
from .panel import PaintPlan, plan_paint

__all__ = ["plan_paint", "PaintPlan", "program_deflection"]
