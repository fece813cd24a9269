"""The passes: a panel's raster, a part's surface passes, a part's program of pieces
(docs/model.md §21, §23)."""
from .raster import Segments

__all__ = ["Segments"]
