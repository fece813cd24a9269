"""The line (docs/model.md §24): the conveyor table, the world program and its phases, a
panel's and a part's program on it, the fastest line speed."""
from .conveyor import Line

__all__ = ["Line"]
