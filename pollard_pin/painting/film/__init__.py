"""The film: the panel's grid, a part's points, the film on the mesh and of a part's plan, a
panel's on the line, film.ply's mesh, one statistics (docs/model.md §20–§24)."""
from .grid import plan_film

__all__ = ["plan_film"]
