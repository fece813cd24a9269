"""The planning layer: workspace maps (issue 21) and paint planning (issue 22)."""
