"""The line (docs/model.md §24): the conveyor table, the world program and its phases, a
panel's and a part's program on it, the line speeds that paint it (the fastest, the interval).
Nothing here is for a caller to build: the names are public in their modules."""

__all__: list[str] = []
