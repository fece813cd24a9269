"""The passes: a panel's raster, a part's surface passes, a part's program of pieces
(docs/model.md §21, §23).
Nothing here is for a caller to build: the names are public in their modules."""

__all__: list[str] = []
