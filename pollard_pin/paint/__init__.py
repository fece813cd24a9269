"""Paint planning: the job file, the spray deposition model, the raster planner, the motion
checks and the film (docs/model.md §20–21)."""
