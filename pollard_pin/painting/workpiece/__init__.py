"""The target: a part's mesh read and placed (docs/model.md §23), the example shapes."""
from .panel import PanelFrame

__all__ = ["PanelFrame"]
