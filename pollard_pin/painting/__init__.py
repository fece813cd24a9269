"""Painting: the job file, the spray deposition model, the planners of every job kind, the
motion checks and the film (docs/model.md §20–§27).

The entry point is the plain function :func:`pollard_pin.paint` (this subpackage's
:func:`pollard_pin.painting.api.paint`).
"""
