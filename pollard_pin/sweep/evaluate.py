"""One sweep variant through the whole pipeline: :func:`evaluate_variant`, a pure, picklable
function of plain data returning one flat row (the columns of the package docstring)."""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from ..dynamics.averages import time_rms
from ..errors import InputError
from ..model.overrides import ParameterError, apply_overrides, lookup, plain_value
from ..model.params import params_from_dict, read_params_dict
from ..names import ACTUATED, TREE_JOINTS

FAILURE_COLUMNS = ("feasible", "failure_kind", "failure", "failure_sample", "failure_time",
                   "failure_chain")
METRIC_COLUMNS = (tuple(f"{m}_{a}" for m in ("peak_tau", "rms_tau", "peak_power")
                        for a in ACTUATED)
                  + ("peak_force_leg1", "peak_force_leg2",
                     "min_wrist_margin", "min_sigma_parallel", "min_sigma_serial"))
# Peak bearing loads per tree joint (docs/model.md §2 order, §17).
LOAD_METRICS = ("peak_axial", "peak_radial", "peak_bending")
METRIC_COLUMNS += tuple(f"{m}_{j}" for m in LOAD_METRICS for j in TREE_JOINTS)

class SweepError(InputError):
    """A grid file or sweep definition is invalid (one line naming the variant, the key and
    the rule), or a variant crashed unexpectedly."""


# --- the per-variant function (pure, picklable) -----------------------------------------------
def _trajectory(spec: Mapping, home_pose):
    from ..paths.curves import thesis_trajectory
    from ..paths.trajectory import Trajectory

    if spec["kind"] == "thesis":
        return thesis_trajectory(duration=spec["duration"], samples=spec["samples"],
                                 home_pose=home_pose)
    if spec["kind"] == "arrays":
        return Trajectory(t=np.asarray(spec["t"], dtype=float),
                          poses=np.asarray(spec["poses"], dtype=float),
                          d_poses=np.asarray(spec["d_poses"], dtype=float),
                          dd_poses=np.asarray(spec["dd_poses"], dtype=float),
                          name=spec.get("name", "trajectory"),
                          derivatives=spec.get("derivatives", "file columns"))
    raise SweepError(f"unknown trajectory kind {spec['kind']!r} (expected 'thesis' or 'arrays')")


def _failure(row: dict, exc: BaseException, chain=None, sample=None, time=None) -> dict:
    row.update(feasible=False, failure_kind=type(exc).__name__, failure=str(exc),
               failure_sample=None if sample is None else int(sample),
               failure_time=None if time is None else float(time),
               failure_chain=None if chain is None else str(chain))
    return row


def evaluate_variant(spec: Mapping[str, Any]) -> dict[str, Any]:
    """Run one variant through the pipeline and return its flat result row.

    ``spec`` is plain, picklable data:

    * ``name``: the variant's name;
    * ``overrides``: {dotted thesis-unit key: value} applied to the base parameters;
    * ``trajectory``: ``{"kind": "thesis", "duration": s, "samples": n}`` (laid around the
      variant's home pose) or ``{"kind": "arrays", "t": …, "poses": …, "d_poses": …,
      "dd_poses": …}`` (absolute; (N,) and (N, 6) sequences);
    * ``params`` (optional): the base thesis-unit parameter dictionary (the TOML layout of
      :func:`~pollard_pin.model.params.read_params_dict`); default: the shipped parameter file;
    * ``keys`` (optional): the parameter columns of the row (default: the override keys);
      each holds the value the variant used (the base value if it does not override it).

    The function has no side effects and depends on nothing but ``spec``, so it gives the same
    row in any process or machine with the same pollard-pin installed. An invalid parameter set
    (:class:`~pollard_pin.model.ParameterError`, e.g. an unreachable home pose) and a trajectory the
    variant cannot follow (:class:`~pollard_pin.kinematics.KinematicsError`,
    :class:`~pollard_pin.kinematics.ClosureError`, a singular linear system) give an infeasible row;
    anything else is a bug and raises.

    Parameters
    ----------
    spec : Mapping
        As above (one of ``Sweep.specs()``).

    Returns
    -------
    dict
        The row: ``variant``, the parameter values, ``feasible`` and the failure columns,
        then per actuator ``peak_tau_*`` and ``rms_tau_*`` [N·m], ``peak_power_*`` [W], the
        peak closure forces [N], the smallest singularity margins and the peak bearing loads
        (the columns of :mod:`pollard_pin.sweep`).

    Examples
    --------
    >>> import pollard_pin as pp
    >>> from pollard_pin.sweep import evaluate_variant
    >>> spec = pp.make_sweep(variants=[("short leg 1", {"leg1.x87": 0.31})], samples=201).specs()[0]
    >>> row = evaluate_variant(spec)
    >>> row["variant"], row["feasible"], row["failure_kind"]
    ('short leg 1', False, 'UnreachablePoseError')
    """
    from ..kinematics.errors import SAMPLE_ERRORS, ClosureError
    from ..model.build import load
    from ..run import run_pipeline

    overrides = dict(spec.get("overrides") or {})
    keys = list(spec.get("keys") or overrides)
    row: dict[str, Any] = {"variant": spec.get("name", "")}
    row.update({k: plain_value(overrides[k]) if k in overrides else None for k in keys})
    row.update({c: None for c in FAILURE_COLUMNS})
    row.update({c: None for c in METRIC_COLUMNS})
    try:
        base = spec.get("params")
        d = apply_overrides(base if base is not None else read_params_dict(), overrides)
        row.update({k: lookup(d, k) for k in keys})
        params = params_from_dict(d, source=f"variant {row['variant']}")
    except ParameterError as exc:
        return _failure(row, exc)
    try:
        robot = load(params)
        traj = _trajectory(spec["trajectory"], params.home_pose)
        result = run_pipeline(robot, traj, loads=True)
    except SAMPLE_ERRORS as exc:
        return _failure(row, exc, exc.chain, exc.sample, exc.time)
    except ClosureError as exc:
        return _failure(row, exc, None if exc.leg is None else f"leg {exc.leg}")
    except ParameterError as exc:
        return _failure(row, exc)
    except np.linalg.LinAlgError as exc:
        return _failure(row, exc)
    dyn, ik = result.dynamics, result.ik
    if tuple(dyn.actuated) != ACTUATED:
        raise SweepError(f"actuator order {dyn.actuated} is not docs/model.md §6 order {ACTUATED}")
    tau, power = dyn.tau, dyn.power
    peak, rms, ppow = np.abs(tau).max(0), time_rms(ik.t, tau), np.abs(power).max(0)
    force = np.linalg.norm(dyn.closure_forces, axis=2).max(0)
    row["feasible"] = True
    for i, a in enumerate(ACTUATED):
        row[f"peak_tau_{a}"] = float(peak[i])
        row[f"rms_tau_{a}"] = float(rms[i])
        row[f"peak_power_{a}"] = float(ppow[i])
    row["peak_force_leg1"], row["peak_force_leg2"] = float(force[0]), float(force[1])
    row["min_wrist_margin"] = float(ik.wrist_margin.min())
    row["min_sigma_parallel"] = float(ik.sigma_parallel.min())
    row["min_sigma_serial"] = float(ik.sigma_serial.min())
    bearings = result.loads.bearing_table()["joints"]
    for m in LOAD_METRICS:
        row.update({f"{m}_{j}": bearings[j][m] for j in TREE_JOINTS})
    return row
