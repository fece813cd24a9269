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
time
  RMS sqrt(1/T ∫ τ² dt) (trapezoid rule) [N·m], ``peak_power_<a>`` = max |τ·q̇| [W];
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
from __future__ import annotations

import copy
import itertools
import json
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Iterable, Mapping, Sequence

import numpy as np

from .dynamics.averages import time_rms
from .io.atomic import atomic_open
from .model.names import ACTUATED, TREE_JOINTS
from .model.params import (
    ParameterError,
    apply_overrides,
    lookup,
    params_from_dict,
    plain_value,
    read_params_dict,
    read_toml,
)

FAILURE_COLUMNS = ("feasible", "failure_kind", "failure", "failure_sample", "failure_time",
                   "failure_chain")
METRIC_COLUMNS = (tuple(f"{m}_{a}" for m in ("peak_tau", "rms_tau", "peak_power")
                        for a in ACTUATED)
                  + ("peak_force_leg1", "peak_force_leg2",
                     "min_wrist_margin", "min_sigma_parallel", "min_sigma_serial"))
# Peak bearing loads per tree joint (docs/model.md §2 order, §17).
LOAD_METRICS = ("peak_axial", "peak_radial", "peak_bending")
METRIC_COLUMNS += tuple(f"{m}_{j}" for m in LOAD_METRICS for j in TREE_JOINTS)
GRID_KEYS = ("trajectory", "duration", "samples", "params", "grid", "variant")


class SweepError(ValueError):
    """A grid file or sweep definition is invalid, or a variant crashed unexpectedly."""


# --- overrides with component keys ----------------------------------------------------------
# --- the per-variant function (pure, picklable) -----------------------------------------------
def _trajectory(spec: Mapping, home_pose):
    from .io.trajectory import Trajectory, thesis_trajectory

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
    (:class:`~pollard_pin.model.params.ParameterError`, e.g. an unreachable home pose) and a
    trajectory the variant cannot follow (:class:`~pollard_pin.kinematics.errors.KinematicsError`,
    :class:`~pollard_pin.kinematics.errors.ClosureError`, a singular linear system) give an
    infeasible
    row; anything else is a bug and raises.
    """
    from .run import run_pipeline
    from .kinematics.errors import ClosureError, KinematicsError
    from .model.build import load

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
    except KinematicsError as exc:
        return _failure(row, exc, exc.chain, exc.sample, exc.time)
    except ClosureError as exc:
        return _failure(row, exc, None if exc.leg is None else f"leg {exc.leg}")
    except ParameterError as exc:
        return _failure(row, exc)
    except np.linalg.LinAlgError as exc:
        return _failure(row, exc)
    if result.dynamics is None:
        raise SweepError("pollard_pin.dynamics.inverse is not available: cannot compute torques")
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


# --- sweep definition -------------------------------------------------------------------------
@dataclass(frozen=True)
class Sweep:
    """Variants (name, overrides) over one trajectory; build with :func:`make_sweep`."""

    variants: tuple[tuple[str, dict], ...]
    trajectory: dict  # the ``trajectory`` entry of evaluate_variant's spec
    keys: tuple[str, ...]  # parameter columns, in order of first appearance
    params: dict | None = None  # base thesis-unit dictionary (None: the shipped file)
    source: str = "<python>"

    def __len__(self) -> int:
        return len(self.variants)

    def specs(self) -> list[dict]:
        """The plain-data arguments of :func:`evaluate_variant`, one per variant."""
        return [{"name": name, "overrides": ov, "trajectory": self.trajectory,
                 "params": self.params, "keys": list(self.keys)}
                for name, ov in self.variants]

    @property
    def columns(self) -> list[str]:
        return ["variant", *self.keys, *FAILURE_COLUMNS, *METRIC_COLUMNS]


def _fmt(value: Any) -> str:
    if isinstance(value, (list, tuple, np.ndarray)):
        return json.dumps(plain_value(value))
    return f"{value:g}" if isinstance(value, float) else str(value)


def _short_keys(keys: Sequence[str]) -> dict[str, str]:
    """Each key without its first section (``bodies.gun.mass`` → ``gun.mass``) where that
    stays unambiguous among ``keys``; the full key otherwise."""
    short = {k: k.split(".", 1)[-1] for k in keys}
    clash = {s for s in short.values() if list(short.values()).count(s) > 1}
    return {k: (k if s in clash else s) for k, s in short.items()}


def grid_variants(grid: Mapping[str, Sequence[Any]]) -> list[tuple[str, dict]]:
    """The cartesian product of ``{key: [values]}`` as (name, overrides); first key slowest.

    Names read ``x32=0.32 gun.mass=0.05`` (keys without their first section where unambiguous).
    """
    keys = list(grid)
    label = _short_keys(keys)
    out = []
    for combo in itertools.product(*(grid[k] for k in keys)):
        ov = dict(zip(keys, combo))
        out.append((" ".join(f"{label[k]}={_fmt(v)}" for k, v in ov.items()), ov))
    return out


def trajectory_spec(trajectory: Any = "thesis", duration: float | None = None,
                    samples: int | None = None) -> dict:
    """The plain-data trajectory spec: ``"thesis"``, a CSV path or a :class:`Trajectory`.

    A CSV file is read here, once, and travels as arrays, so workers need no access to it.
    """
    from .io.trajectory import (
        THESIS_DURATION,
        THESIS_SAMPLES,
        Trajectory,
        from_csv,
        thesis_trajectory,
    )

    if isinstance(trajectory, str) and trajectory == "thesis":
        spec = {"kind": "thesis",
                "duration": THESIS_DURATION if duration is None else duration,
                "samples": THESIS_SAMPLES if samples is None else samples}
        thesis_trajectory(spec["duration"], spec["samples"])  # validates (TrajectoryError)
        return spec
    if duration is not None or samples is not None:
        raise SweepError("'duration' and 'samples' apply to the thesis trajectory only "
                         f"(trajectory = {str(trajectory)!r} uses the file's own times)")
    traj = trajectory if isinstance(trajectory, Trajectory) else from_csv(trajectory)
    return {"kind": "arrays", "name": traj.name, "derivatives": traj.derivatives,
            "t": np.asarray(traj.t), "poses": np.asarray(traj.poses),
            "d_poses": np.asarray(traj.d_poses), "dd_poses": np.asarray(traj.dd_poses)}


def make_sweep(grid: Mapping[str, Sequence[Any]] | None = None,
               variants: Iterable[tuple[str, Mapping[str, Any]] | Mapping[str, Any]] = (),
               trajectory: Any = "thesis", duration: float | None = None,
               samples: int | None = None, params: str | Path | Mapping | None = None,
               source: str = "<python>") -> Sweep:
    """Validate and build a :class:`Sweep`.

    ``grid`` = {key: [values]} (cartesian product) and/or ``variants`` = [(name, overrides)]
    or [{"name": …, key: value, …}]. Every key must name a parameter and every value must
    have the parameter's shape and pass its rules (a :class:`SweepError` naming the variant
    and the parameter otherwise); only whether the home pose is reachable is left to the run,
    where it makes the variant infeasible.
    """
    if isinstance(params, Mapping):
        base = copy.deepcopy(dict(params))
    else:
        try:
            base = read_params_dict(params)
        except ParameterError as exc:
            raise SweepError(f"params: {exc}") from None
    vlist: list[tuple[str, dict]] = []
    if grid:
        for key, values in grid.items():
            if not isinstance(values, (list, tuple)):
                raise SweepError(f"grid: '{key}' = {values!r} must be a list of values")
            if not values:
                raise SweepError(f"grid: '{key}' has an empty list of values")
        vlist += grid_variants(grid)
    for j, v in enumerate(variants):
        if isinstance(v, Mapping):
            v = dict(v)
            name = v.pop("name", f"variant {j + 1}")
            ov = v
        else:
            name, ov = v
        if not isinstance(name, str) or not name:
            raise SweepError(f"variant {j + 1}: name {name!r} must be a non-empty string")
        vlist.append((name, dict(ov)))
    if not vlist:
        raise SweepError(f"{source}: the sweep has no variants: give a [grid] table and/or "
                         "[[variant]] tables")
    names = [n for n, _ in vlist]
    dup = next((n for n in names if names.count(n) > 1), None)
    if dup is not None:
        raise SweepError(f"{source}: two variants are named {dup!r}")
    keys: list[str] = []
    for name, ov in vlist:
        whole = {k for k in ov if "[" not in str(k)}
        for key in ov:
            root = str(key).split("[")[0]
            if root != key and root in whole:
                raise SweepError(f"variant {name!r}: '{key}' and '{root}' set the same "
                                 "parameter")
            if key not in keys:
                keys.append(key)
        try:
            params_from_dict(apply_overrides(base, ov), source=name, check_home=False)
        except ParameterError as exc:
            raise SweepError(f"variant {name!r}: {exc}") from None
    traj = trajectory_spec(trajectory, duration, samples)
    return Sweep(variants=tuple(vlist), trajectory=traj, keys=tuple(keys),
                 params=None if params is None else base, source=source)


def _flatten(table: Mapping, prefix: str = "") -> dict:
    """TOML tables → dotted keys: ``chain0.x32 = …`` written unquoted nests in TOML."""
    out = {}
    for k, v in table.items():
        key = f"{prefix}{k}"
        if isinstance(v, Mapping):
            out.update(_flatten(v, key + "."))
        else:
            out[key] = v
    return out


def load_grid(path: str | Path) -> Sweep:
    """Read and validate a grid TOML file (format: module docstring)."""
    path = Path(path)
    d = read_toml(path, "grid file", SweepError)
    unknown = [k for k in d if k not in GRID_KEYS]
    if unknown:
        raise SweepError(f"{path}: unknown entry '{unknown[0]}' (expected: "
                         f"{', '.join(GRID_KEYS)}; quote dotted parameter keys inside [grid] "
                         "or [[variant]])")
    grid = d.get("grid", {})
    if not isinstance(grid, Mapping):
        raise SweepError(f"{path}: 'grid' must be a table ([grid])")
    variants = d.get("variant", [])
    if not isinstance(variants, list) or not all(isinstance(v, Mapping) for v in variants):
        raise SweepError(f"{path}: 'variant' must be an array of tables ([[variant]])")
    trajectory = d.get("trajectory", "thesis")
    if not isinstance(trajectory, str):
        raise SweepError(f"{path}: trajectory = {trajectory!r} must be 'thesis' or a CSV path")
    if trajectory != "thesis":
        trajectory = str(path.parent / trajectory)
    params = d.get("params")
    if params is not None:
        if not isinstance(params, str):
            raise SweepError(f"{path}: params = {params!r} must be a parameter file path")
        params = path.parent / params
    for k in ("duration", "samples"):
        if k in d and (isinstance(d[k], bool) or not isinstance(d[k], (int, float))):
            raise SweepError(f"{path}: {k} = {d[k]!r} must be a number")
    from .io.trajectory import TrajectoryError

    try:
        return make_sweep(_flatten(grid),
                          [_flatten(v) for v in variants],
                          trajectory=trajectory, duration=d.get("duration"),
                          samples=d.get("samples"), params=params, source=str(path))
    except SweepError as exc:
        msg = str(exc)
        raise SweepError(msg if msg.startswith(str(path)) else f"{path}: {msg}") from None
    except (TrajectoryError, ParameterError) as exc:
        raise SweepError(f"{path}: {exc}") from None


# --- running ----------------------------------------------------------------------------------
Progress = Callable[[int, int], None]


def _checked(name: str, future_or_fn, *args):
    try:
        return future_or_fn(*args)
    except Exception as exc:  # a bug, not an infeasible design: name the variant
        raise SweepError(f"variant {name!r} crashed: {type(exc).__name__}: {exc}") from exc


def run_sweep(sweep: Sweep, *, workers: int | None = None, dask: Any = None,
              progress: Progress | None = None, mp_context: str | None = None) -> list[dict]:
    """Evaluate every variant; the rows of the result table, in the sweep's variant order.

    ``dask``: a scheduler address (``"tcp://host:8786"``) or a ``distributed.Client`` runs
    the variants on that Dask cluster. Otherwise ``workers`` processes of a local pool
    (default ``os.cpu_count()``); ``workers=1`` runs serially in this process.
    ``progress(done, total)`` is called as variants finish.

    The pool starts its workers with the multiprocessing start method ``mp_context``. The
    default is ``"fork"`` where the platform has it and this process runs a single Python
    thread (workers start at once, with everything imported), otherwise ``"spawn"`` (a fresh
    interpreter: safe in a threaded parent such as a Dask client or a GUI). Under ``"spawn"``
    or ``"forkserver"`` a script that calls this must guard its top level with
    ``if __name__ == "__main__":``, as with any such pool.
    """
    specs = sweep.specs()
    if dask is not None:
        return _run_dask(specs, dask, progress)
    n = len(specs)
    workers = (os.cpu_count() or 1) if workers is None else int(workers)
    if workers < 1:
        raise SweepError(f"workers = {workers}: must be >= 1")
    rows: list[dict | None] = [None] * n
    if workers == 1 or n == 1:
        for k, spec in enumerate(specs):
            rows[k] = _checked(spec["name"], evaluate_variant, spec)
            if progress is not None:
                progress(k + 1, n)
        return rows  # type: ignore[return-value]
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor, as_completed
    from concurrent.futures.process import BrokenProcessPool

    if mp_context is None:
        import threading

        fork_ok = ("fork" in multiprocessing.get_all_start_methods()
                   and threading.active_count() == 1)
        mp_context = "fork" if fork_ok else "spawn"
    ctx = multiprocessing.get_context(mp_context)
    with ProcessPoolExecutor(max_workers=min(workers, n), mp_context=ctx) as pool:
        futures = {pool.submit(evaluate_variant, spec): k for k, spec in enumerate(specs)}
        try:
            for done, fut in enumerate(as_completed(futures), start=1):
                k = futures[fut]
                try:
                    rows[k] = _checked(specs[k]["name"], fut.result)
                except SweepError as exc:
                    if isinstance(exc.__cause__, BrokenProcessPool):
                        raise SweepError(
                            f"a worker process died ({exc.__cause__}); a script that runs a "
                            "sweep on the process pool needs an `if __name__ == '__main__':` "
                            "guard, or run it with workers=1") from exc.__cause__
                    raise
                if progress is not None:
                    progress(done, n)
        except BaseException:
            for fut in futures:
                fut.cancel()
            raise
    return rows  # type: ignore[return-value]


def _run_dask(specs: list[dict], address: Any, progress: Progress | None) -> list[dict]:
    try:
        from distributed import Client, as_completed
    except ImportError:
        raise SweepError("--dask needs dask.distributed: pip install 'pollard-pin[cluster]'"
                         ) from None
    own = not isinstance(address, Client)
    if own:
        try:
            client = Client(address)
        except (OSError, TimeoutError) as exc:
            raise SweepError(f"cannot connect to the Dask scheduler at {address!r}: {exc}"
                             ) from None
    else:
        client = address
    try:
        futures = client.map(evaluate_variant, specs, pure=False)
        index = {f.key: k for k, f in enumerate(futures)}
        rows: list[dict | None] = [None] * len(specs)
        try:
            for done, fut in enumerate(as_completed(futures), start=1):
                k = index[fut.key]
                rows[k] = _checked(specs[k]["name"], fut.result)
                if progress is not None:
                    progress(done, len(specs))
        except BaseException:
            client.cancel(futures)
            raise
        return rows  # type: ignore[return-value]
    finally:
        if own:
            client.close()


# --- output -----------------------------------------------------------------------------------
def _cell(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)  # round-trips exactly
    if isinstance(value, (list, tuple)):
        return json.dumps(plain_value(value))
    return str(value)


def write_csv(rows: Sequence[Mapping[str, Any]], path: str | Path,
              columns: Sequence[str] | None = None) -> None:
    """The result table as CSV (polars, atomic write). Empty cells: not applicable or
    infeasible; floats as their shortest exact repr, lists as JSON."""
    import polars as pl

    columns = list(columns or (rows[0].keys() if rows else ()))
    table = pl.DataFrame({c: [None if row.get(c) is None else _cell(row.get(c)) for row in rows]
                          for c in columns}, schema={c: pl.String for c in columns})
    with atomic_open(path, binary=True) as f:
        table.write_csv(f)


def summary(rows: Sequence[Mapping[str, Any]], max_rows: int = 20) -> str:
    """A short text table: per variant the worst actuator torque and power, or the failure."""
    n_ok = sum(1 for r in rows if r["feasible"])
    lines = [f"{len(rows)} variants: {n_ok} feasible, {len(rows) - n_ok} infeasible"]
    width = min(48, max([len("variant")] + [len(str(r["variant"])) for r in rows]))
    lines.append(f"{'variant':{width}s}  {'max|τ| [N·m] (actuator)':>25s}  "
                 f"{'max|P| [W]':>10s}  {'max|λ| [N]':>10s}")
    for r in list(rows)[:max_rows]:
        name = str(r["variant"])
        name = name if len(name) <= width else name[:width - 1] + "…"
        if r["feasible"]:
            peaks = [r[f"peak_tau_{a}"] for a in ACTUATED]
            i = int(np.argmax(peaks))
            pmax = max(r[f"peak_power_{a}"] for a in ACTUATED)
            fmax = max(r["peak_force_leg1"], r["peak_force_leg2"])
            lines.append(f"{name:{width}s}  {peaks[i]:12.4g} ({ACTUATED[i]:>10s})  "
                         f"{pmax:10.4g}  {fmax:10.4g}")
        else:
            where = []
            if r["failure_sample"] is not None:
                where.append(f"sample {r['failure_sample']}")
            if r["failure_time"] is not None:
                where.append(f"t = {r['failure_time']:.4g} s")
            if r["failure_chain"]:
                where.append(str(r["failure_chain"]))
            lines.append(f"{name:{width}s}  INFEASIBLE: {r['failure_kind']}"
                         + (f" ({', '.join(where)})" if where else ""))
    if len(rows) > max_rows:
        lines.append(f"… {len(rows) - max_rows} more in the CSV")
    return "\n".join(lines)


__all__ = ["Sweep", "SweepError", "evaluate_variant", "make_sweep", "load_grid", "run_sweep",
           "grid_variants", "trajectory_spec", "apply_overrides", "write_csv", "summary",
           "METRIC_COLUMNS", "FAILURE_COLUMNS"]
