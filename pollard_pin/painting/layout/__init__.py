"""Where things stand: a part placed in the reach (place.py) and a cell's robots proposed
along the line (cell.py) (docs/model.md §22, §23, §26.5)."""
