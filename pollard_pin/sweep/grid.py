"""Sweep definitions: variants from a cartesian grid and explicit entries (:func:`make_sweep`)
or a TOML grid file (:func:`load_grid`)."""
from __future__ import annotations

import copy
import itertools
import json
import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..checks import file_path, instance, shorten
from ..model.overrides import ParameterError, apply_overrides, plain_value
from ..model.params import params_from_dict, read_params_dict
from ..model.values import number, read_toml
from .evaluate import FAILURE_COLUMNS, METRIC_COLUMNS, SweepError

GRID_KEYS = ("trajectory", "duration", "samples", "params", "grid", "variant")
# Variants per sweep, checked before the grid's product is built: each is validated (≈ 2 ms)
# and then a whole run of its trajectory (≈ 0.05 s for the thesis' 2001 samples): 10^4 is
# some 20 s of checks and 10 min of runs.
MAX_VARIANTS = 10_000




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
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) >= 10**16:
        return shorten(value)
    return f"{value:g}" if isinstance(value, float) else str(value)


def _short_keys(keys: Sequence[str]) -> dict[str, str]:
    """Each key without its first section (``bodies.gun.mass`` → ``gun.mass``) where that
    stays unambiguous among ``keys``; the full key otherwise."""
    short = {k: k.split(".", 1)[-1] for k in keys}
    seen: dict[str, int] = {}
    for s in short.values():
        seen[s] = seen.get(s, 0) + 1
    clash = {s for s, n in seen.items() if n > 1}
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
    from ..io.trajectory import from_csv
    from ..paths.curves import THESIS_DURATION, THESIS_SAMPLES, thesis_trajectory
    from ..paths.trajectory import Trajectory

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
    """Validate and build a design sweep: parameter variants over one trajectory.

    Every key must name a parameter and every value must have the parameter's shape and pass
    its rules; only whether the home pose is reachable is left to the run, where it makes the
    variant infeasible.

    Parameters
    ----------
    grid : Mapping or None, optional
        ``{key: [values]}``, a cartesian product; keys are the dotted keys of
        ``models/pollard.toml`` in its units (m, deg, kg, kg·mm²), ``"key[i]"`` one component
        of a vector parameter.
    variants : Iterable, optional
        Explicit variants after the grid: ``(name, overrides)`` pairs or
        ``{"name": ..., key: value, ...}`` mappings.
    trajectory : str or Trajectory, optional
        ``"thesis"`` (default; laid around each variant's home pose) or a trajectory (a CSV
        path or a :class:`~pollard_pin.Trajectory`, absolute).
    duration : float or None, optional
        The thesis trajectory's duration [s] (default 20).
    samples : int or None, optional
        The thesis trajectory's samples (default 2001).
    params : str or pathlib.Path or Mapping or None, optional
        The base parameters (default the shipped file).
    source : str, optional
        A label for messages.

    Returns
    -------
    pollard_pin.sweep.grid.Sweep
        The variants; ``specs()`` gives each one's plain-data spec for
        :func:`~pollard_pin.sweep.evaluate_variant`, ``columns`` the result table's columns.

    Raises
    ------
    SweepError
        An unknown key, a value of the wrong shape or breaking its rule (naming the variant
        and the parameter), duplicate variant names, no variant at all.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> sweep = pp.make_sweep(grid={"chain0.x32": [0.32, 0.34], "bodies.gun.mass": [0.035, 0.05]},
    ...                       variants=[("long legs", {"leg1.x87": 0.34, "leg2.x87": 0.34})],
    ...                       samples=201)
    >>> len(sweep), sweep.columns[:3]
    (5, ['variant', 'chain0.x32', 'bodies.gun.mass'])
    >>> pp.make_sweep(grid={"chain0.x99": [0.3]})
    Traceback (most recent call last):
    ...
    pollard_pin.sweep.evaluate.SweepError: ...
    """
    if isinstance(params, Mapping):
        base = copy.deepcopy(dict(params))
    else:
        try:
            base = read_params_dict(params)
        except ParameterError as exc:
            raise SweepError(f"params: {exc}") from None
    vlist: list[tuple[str, dict]] = []
    instance(grid, "grid", Mapping, "a mapping of parameter keys to lists of values",
             none=True, error=SweepError)
    if grid:
        for key, values in grid.items():
            if not isinstance(values, (list, tuple)):
                raise SweepError(f"grid: '{key}' = {shorten(values)} must be a list of values")
            if not values:
                raise SweepError(f"grid: '{key}' has an empty list of values")
        size = math.prod(len(v) for v in grid.values())
        if size > MAX_VARIANTS:
            raise SweepError(f"{source}: the grid makes {size:.4g} variants "
                             f"({' × '.join(str(len(v)) for v in grid.values())}), budget "
                             f"{MAX_VARIANTS:.4g}: fewer values per key or fewer keys")
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
        if len(vlist) > MAX_VARIANTS:
            raise SweepError(f"{source}: more than {MAX_VARIANTS:.4g} variants (the budget): "
                             "fewer grid values or [[variant]] tables")
    if not vlist:
        raise SweepError(f"{source}: the sweep has no variants: give a [grid] table and/or "
                         "[[variant]] tables")
    seen: set[str] = set()  # linear: a count per name was quadratic (10^6 variants: hours)
    for n, _ in vlist:
        if n in seen:
            raise SweepError(f"{source}: two variants are named {n!r}")
        seen.add(n)
    keys: dict[str, None] = {}  # ordered, with a set's look-up
    for name, ov in vlist:
        whole = {k for k in ov if "[" not in str(k)}
        for key in ov:
            root = str(key).split("[")[0]
            if root != key and root in whole:
                raise SweepError(f"variant {name!r}: '{key}' and '{root}' set the same "
                                 "parameter")
            keys.setdefault(key)
        try:
            params_from_dict(apply_overrides(base, ov), source=name, check_home=False)
        except ParameterError as exc:
            raise SweepError(f"variant {shorten(name)}: {exc}") from None
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
    """Read and validate a grid TOML file (format: ``examples/sweep.toml``): top-level
    ``trajectory`` (``"thesis"`` or a CSV path relative to the file), ``duration``,
    ``samples``, ``params``; a ``[grid]`` table (cartesian product) and ``[[variant]]``
    tables, keyed by quoted dotted parameter keys.

    Parameters
    ----------
    path : str or pathlib.Path
        The grid file.

    Returns
    -------
    pollard_pin.sweep.grid.Sweep
        As :func:`~pollard_pin.make_sweep`.

    Raises
    ------
    SweepError
        A missing or malformed file, an unknown entry, a bad parameter key or value.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> import os
    >>> lines = ["samples = 201", "[grid]", '"chain0.x32" = [0.32, 0.34]']
    >>> with open("grid.toml", "w") as f:
    ...     _ = f.write(os.linesep.join(lines))
    >>> [name for name, _ in pp.load_grid("grid.toml").variants]
    ['x32=0.32', 'x32=0.34']
    """
    path = file_path(path, "path", error=SweepError)
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
        raise SweepError(f"{path}: trajectory = {shorten(trajectory)} must be 'thesis' or a "
                         "CSV path")
    if trajectory != "thesis":
        trajectory = str(path.parent / trajectory)
    params = d.get("params")
    if params is not None:
        if not isinstance(params, str):
            raise SweepError(f"{path}: params = {shorten(params)} must be a parameter file path")
        params = path.parent / params
    for k in ("duration", "samples"):
        if k in d:
            number(d[k], k, SweepError, f"{path}: ")
    from ..paths.trajectory import TrajectoryError

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
