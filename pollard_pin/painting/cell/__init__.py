"""A paint cell: several robots along one line (docs/model.md §26).

Only the robots' table is imported here (its error): the job reader (``painting.job``) reads a
cell's ``[robot]`` tables through it, and every other room of the cell reads the job, so
importing them here would be a cycle. The rest is public in its module: ``plan``
(``plan_cell``, ``CellPlan``), ``split`` (``split_cell``), ``zones`` (``Split``, ``Zone``),
``clearance`` (``cell_clearance``, ``CellClearance``, ``MovingPart``); the layout proposals
(``propose_layout``, ``fewest_robots``, ``LayoutOptions``) are in :mod:`pollard_pin.painting`.
"""
from .robots import CellError

__all__ = ["CellError"]
