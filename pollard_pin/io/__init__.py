"""Data in and out: ``trajectory`` (the painting curve, trajectory CSVs), ``results`` (the run
pipeline and its CSV), ``atomic`` (writes that never leave a half-written file)."""
