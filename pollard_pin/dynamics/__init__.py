"""The dynamics layer: ``inverse`` (RNEA + closure forces, docs/model.md §13) and ``forward``
(constrained forward dynamics, replay, docs/model.md §14)."""
