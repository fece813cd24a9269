"""A paint cell: several robots along one line (docs/model.md §26)."""
