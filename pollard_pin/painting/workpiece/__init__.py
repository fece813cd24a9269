"""The target: a part's mesh read and placed (docs/model.md §23), the example shapes.
Nothing here is for a caller to build: the names are public in their modules."""

__all__: list[str] = []
