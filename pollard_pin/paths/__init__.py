"""One home for curves (as toppra's ``interpolator.py``): the :class:`~.trajectory.Trajectory`
type and its curve, the quintic splines (:mod:`.splines`), the analytic curves (:mod:`.curves`:
the thesis painting curve, docs/model.md §9) and the constant-s̈ parametrisation of a path
(:mod:`.const_accel`, docs/model.md §19). numpy and scipy only; io reads and writes them."""
