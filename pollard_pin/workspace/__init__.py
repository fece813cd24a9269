"""Workspace maps: where the tool tip reaches at a fixed orientation, with the first reason
where it does not, the conditioning and payload, and the largest reachable rectangle
(docs/model.md §22). ``grid`` maps, ``reach`` holds the per-point rule, ``rectangle`` the
largest-rectangle search."""
from .grid import WorkspaceError, WorkspaceMap, largest_panel, map_workspace
from .options import WorkspaceOptions

__all__ = ["map_workspace", "largest_panel", "WorkspaceMap", "WorkspaceOptions", "WorkspaceError"]
