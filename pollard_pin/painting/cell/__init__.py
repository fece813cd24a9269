"""A paint cell: several robots along one line (docs/model.md §26).

Nothing is imported here: the job reader (``painting.job``) reads a cell's ``[robot]`` tables
through ``cell.robots``, and every other room of the cell reads the job, so importing them here
would be a cycle. Each is public in its module: ``plan`` (``plan_cell``, ``CellPlan``),
``split`` (``split_cell``), ``zones`` (``Split``, ``Zone``); the robots' clearance is in
:mod:`pollard_pin.painting.checks.cell_clearance`, the layout proposals (``propose_layout``,
``fewest_robots``, ``LayoutOptions``) in :mod:`pollard_pin.painting`.
"""

__all__: list[str] = []
