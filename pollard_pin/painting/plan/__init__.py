"""The planning: the panel's and the part's planners, the one plan result type
(docs/model.md §21, §23); the checks they run are in :mod:`pollard_pin.painting.checks`."""
from .panel import PaintPlan, plan_paint

__all__ = ["plan_paint", "PaintPlan"]
