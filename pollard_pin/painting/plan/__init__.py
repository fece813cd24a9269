"""The planning: the checks along a program (reach, limits, motors), the panel's and the
part's planners, the one plan result type (docs/model.md §21, §23)."""
