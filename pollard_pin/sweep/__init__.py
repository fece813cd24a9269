"""Design sweeps: evaluate many parameter variants over one trajectory, in parallel.

A sweep is a list of *variants*, each a set of parameter overrides in thesis units (the dotted
keys of :func:`pollard_pin.model.params.load_params`, e.g. ``"chain0.x32"``, ``"bodies.gun.mass"``,
``"bodies.gun.com"``, ``"home.tip"``; a single component of a vector or matrix parameter is
``"home.tip[2]"`` or ``"bodies.gun.inertia[1][1]"``). Every variant is run through the whole
pipeline (inverse kinematics, inverse dynamics) by :func:`evaluate_variant`, a pure, picklable
module-level function of plain data, and yields one flat row of the result table:

* ``variant`` and the value of every swept parameter (thesis units);
* ``feasible``; for an infeasible variant ``failure_kind`` (the exception class),
  ``failure`` (its message), ``failure_sample``, ``failure_time`` [s] and ``failure_chain``
  (first unreachable/singular/branch-flipping sample, as the kinematics reports it; empty when
  the parameter set itself is invalid, e.g. the home pose is unreachable);
* per actuator (docs/model.md §6 order): ``peak_tau_<a>`` = max |τ| [N·m], ``rms_tau_<a>`` = the
  time RMS sqrt(1/T ∫ τ² dt) (trapezoid rule) [N·m], ``peak_power_<a>`` = max |τ·q̇| [W];
* ``peak_force_leg1``, ``peak_force_leg2`` = max |λ_i| [N] at the spherical joints;
* ``min_wrist_margin``, ``min_sigma_parallel``, ``min_sigma_serial``: how close the variant
  came to the singularities (see :class:`pollard_pin.kinematics.ik.IKResult`);
* per tree joint (docs/model.md §17): ``peak_axial_<j>``, ``peak_radial_<j>`` [N] and
  ``peak_bending_<j>`` [N·m], the peak bearing loads.

Metric cells of an infeasible variant are ``None`` (empty in the CSV).

:func:`run_sweep` evaluates the variants serially, on a local process pool (all cores by
default) or on a Dask cluster (``dask=ADDRESS`` or a ``distributed.Client``; needs the optional
``cluster`` extra, ``pip install pollard-pin[cluster]``). The rows come back in input order and
are the same whichever way they were computed.

Grid files (:func:`load_grid`) are TOML::

    trajectory = "thesis"          # or a trajectory CSV (path relative to this file)
    duration = 20.0                # thesis trajectory only [s]
    samples = 401                  # thesis trajectory only
    params = "my_params.toml"      # optional base parameter file (default: the shipped one)

    [grid]                         # cartesian product, first key varies slowest
    "chain0.x32" = [0.32, 0.33, 0.34]
    "bodies.gun.mass" = [0.035, 0.05]

    [[variant]]                    # and/or explicit variants, after the grid ones
    name = "long legs"
    "leg1.x87" = 0.34
    "leg2.x87" = 0.34

The thesis trajectory is laid around each variant's own home pose (as ``pollard-pin run
--params`` does), so ``home.*`` overrides move the painting curve; a CSV trajectory is absolute.
"""
from .backends import run_sweep
from .evaluate import FAILURE_COLUMNS, LOAD_METRICS, METRIC_COLUMNS, SweepError, evaluate_variant
from .grid import load_grid, make_sweep
from .table import summary, write_sweep_table

__all__ = ["SweepError", "evaluate_variant", "make_sweep", "load_grid", "run_sweep",
           "write_sweep_table", "summary", "METRIC_COLUMNS", "FAILURE_COLUMNS", "LOAD_METRICS"]
