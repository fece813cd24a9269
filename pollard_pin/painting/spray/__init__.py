"""The spray (docs/model.md §20): the deposition model, the part's shade on it, the steps
where a shadow edge passes."""
from .deposition import Gun, deposition_rate, film

__all__ = ["Gun", "deposition_rate", "film"]
