"""The planning: the panel's and the part's planners, the one plan result type
(docs/model.md §21, §23); the checks they run are in :mod:`..checks`."""
