"""Where things stand: a part placed in the reach (place.py) and a cell's robots proposed
along the line (cell.py) (docs/model.md §22, §23, §26.5)."""

# Public through pollard_pin.painting (place, PlaceOptions, PlaceResult, propose_layout,
# fewest_robots, LayoutOptions): a name here would hide its module (place).
__all__: list[str] = []
