"""A trajectory traversed with a new timing along the same path, and its file, whose
metadata says how it moves between its rows (docs/model.md §19)."""
from __future__ import annotations

import numpy as np

from ..analytic.taskspace import TASK_NAMES
from ..dynamics.timeopt import TimeOptimal
from ..paths.arc_length import ArcLengthPath, ChordArcLengthPath
from ..paths.const_accel import Piecewise, RetimedCurve
from ..paths.trajectory import Trajectory, trajectory_curve
from .trajectory import SPRAY


def retimed_trajectory(traj: Trajectory, timing: TimeOptimal, name: str | None = None
                       ) -> Trajectory:
    """``traj``'s path with the timing s(t) of ``timing``: at the grid of ``timing`` on its own
    path (``timing.curve``, :func:`~pollard_pin.dynamics.timeopt.time_optimal_path`: by arc
    length), else at ``traj``'s samples (``timing`` computed on s = (t − t0)/T of ``traj``):
    exact rates p'(s)·ṡ and accelerations p'(s)·s̈ + p''(s)·ṡ². Its ``curve`` is the retimed
    motion between the samples: s̈ constant per interval on that path."""
    if timing.parts:
        return _joined(traj, timing, name)
    if timing.planned is not None:
        return _as_planned(timing, name or f"{traj.name}_time_optimal")
    spray = None if traj.spray is None else np.zeros(len(timing.t))  # retimed: gun off
    sd, sdd = timing.s_dot[:, None], timing.s_ddot[:, None]
    if timing.curve is not None:  # the grid's own path (time_optimal_path: by arc length)
        base, t0, T = timing.curve, timing.t0, timing.span
        poses, rates, accelerations = base(t0 + timing.s * T)
        p_s, p_ss = T * rates, T * T * accelerations
        return Trajectory(timing.t.copy(), poses, p_s * sd, p_s * sdd + p_ss * sd**2,
                          name=name or f"{traj.name}_time_optimal",
                          derivatives=f"{traj.derivatives}, retimed (exact chain rule)",
                          curve=RetimedCurve(base, t0, T, timing), spray=spray)
    t = np.asarray(traj.t, dtype=float)
    if len(timing.s) != len(t):
        raise ValueError(f"timing has {len(timing.s)} samples, the trajectory {len(t)}")
    T = float(t[-1] - t[0])
    p_s, p_ss = T * traj.d_poses, T * T * traj.dd_poses
    return Trajectory(timing.t.copy(), traj.poses.copy(), p_s * sd, p_s * sdd + p_ss * sd**2,
                      name=name or f"{traj.name}_time_optimal",
                      derivatives=f"{traj.derivatives}, retimed (exact chain rule)",
                      curve=RetimedCurve(trajectory_curve(traj), float(t[0]), T, timing),
                      spray=spray)


def _as_planned(timing: TimeOptimal, name: str) -> Trajectory:
    """A stretch kept as planned: its rows (poses, rates, accelerations, spray) unchanged, its
    times from 0."""
    rows = timing.planned
    spray = None if rows.spray is None else np.array(rows.spray, dtype=float)
    return Trajectory(rows.t - rows.t[0], rows.poses.copy(), rows.d_poses.copy(),
                      rows.dd_poses.copy(), name=name,
                      derivatives=f"{rows.derivatives}, as planned",
                      curve=RetimedCurve(timing.curve, timing.t0, timing.span, timing),
                      spray=spray)


def _joined(traj: Trajectory, timing: TimeOptimal, name: str | None) -> Trajectory:
    """:func:`retimed_trajectory` of a path in parts (waits, a paint program's passes): its
    parts' one after the other, a junction's sample once (the part before's, at the same time
    and pose, unless only the part after is kept as planned: then its row)."""
    pieces = [retimed_trajectory(traj, part) for part in timing.parts]
    starts = [timing.t[0]] + [timing.t[k] for k in _junctions(timing)]
    kept = [part.planned is not None for part in timing.parts]
    after = [k > 0 and kept[k] and not kept[k - 1] for k in range(len(pieces))] + [False]
    rows = [slice(0 if (k == 0 or after[k]) else 1, None if not after[k + 1] else -1)
            for k in range(len(pieces))]
    cat = [np.concatenate([getattr(p, key)[f] for p, f in zip(pieces, rows)])
           for key in ("poses", "d_poses", "dd_poses")]
    t = np.concatenate([p.t[f] - p.t[0] + t0 for p, f, t0 in zip(pieces, rows, starts)])
    spray = (None if any(p.spray is None for p in pieces) else
             np.concatenate([p.spray[f] for p, f in zip(pieces, rows)]))
    return Trajectory(t, *cat, name=name or f"{traj.name}_time_optimal",
                      derivatives=f"{traj.derivatives}, retimed (exact chain rule)",
                      curve=Piecewise(np.array(starts), tuple(p.curve for p in pieces)),
                      spray=spray)


def _junctions(timing: TimeOptimal) -> list[int]:
    """Index in ``timing``'s arrays of each part's first sample after the first part's."""
    return list(np.cumsum([len(p.t) for p in timing.parts[:-1]]))


# How the motion between consecutive rows is defined, by the path parameter s of the timing.
BETWEEN_ROWS = {
    "arc_length": (
        "along the source trajectory's path (its curve between times source_start and "
        "source_end) with constant acceleration along its arc length s between consecutive "
        "rows; s = σ/length, σ the arc length with lengths and angles each divided by "
        "arc_length_scale (x, y, z, psi, theta, phi); at a row ṡ = |(d_x, …, d_phi) / "
        "arc_length_scale| / length, so s_(i+1) − s_i = (ṡ_i + ṡ_(i+1))·(t_(i+1) − t_i)/2 and "
        "s̈ = (ṡ_(i+1)² − ṡ_i²) / (2(s_(i+1) − s_i)); the dd_* columns hold one side of the "
        "jump of s̈ at a row"),
    "source_time": (
        "along the source trajectory's path with constant acceleration along s between "
        "consecutive rows, s = (t − source_start)/(source_end − source_start) of the source "
        "(its path stops inside); the dd_* columns hold one side of the jump of s̈"),
    "planned": (
        "as in the source between the same rows (source_start to source_end, its times "
        "shifted by a constant): the planned timing and path, kept (the paint gun sprays "
        "there, or its ends could not be held)"),
}


def retime_metadata(traj: Trajectory, timing: TimeOptimal) -> dict:
    """The retimed file's metadata: the motion between its rows (:data:`BETWEEN_ROWS`) and to
    what tolerance the limits hold there; for a path in parts (waits, a paint program's
    passes), per ``segments`` (their ``rows``: first and last), the first row of each where
    the one before ended (at rest after a wait)."""
    meta = {"trajectory": f"{traj.name}_time_optimal", "source": traj.name,
            "derivatives": f"{traj.derivatives}, retimed (exact chain rule)",
            "worst_utilisation_between_rows": (float(timing.between)
                                               if np.isfinite(timing.between) else None),
            "check_points_per_interval": 2 * timing.per_interval}
    if not timing.parts:
        return {**meta, **_between_rows(timing)}
    first = [0] + [k - i - 1 for i, k in enumerate(_junctions(timing))]
    last = first[1:] + [len(timing.t) - len(timing.parts)]
    segments = [{"rows": [int(a), int(b)], **_between_rows(part)}
                for a, b, part in zip(first, last, timing.parts)]
    if any(part.planned is not None for part in timing.parts):
        meta["spray"] = ("the film kept: segments with the gun on as planned (path_parameter "
                         "'planned'), the gun-off ones retimed between their path rates where "
                         "they could be")
    return {**meta, "path_parameter": "segments", "between_rows": "per segment: " +
            "; ".join(sorted({seg["path_parameter"] for seg in segments})),
            "segments": segments}


def _between_rows(timing: TimeOptimal) -> dict:
    if timing.planned is not None:
        spray = timing.planned.spray
        return {"path_parameter": "planned", "between_rows": BETWEEN_ROWS["planned"],
                "source_start": float(timing.planned.t[0]),
                "source_end": float(timing.planned.t[-1]),
                "spray": "on" if spray is not None and np.any(spray > 0) else "off"}
    curve = timing.curve
    # a path standing at an end: a spline in σ through its points (within 1e-13 of the
    # length, docs/model.md §19), the same definition
    kind = ("arc_length" if isinstance(curve, (ArcLengthPath, ChordArcLengthPath)) else
            "source_time")
    if kind == "source_time":
        return {"path_parameter": kind, "between_rows": BETWEEN_ROWS[kind],
                "source_start": timing.t0, "source_end": timing.t0 + timing.span}
    return {"path_parameter": kind, "between_rows": BETWEEN_ROWS[kind],
            "source_start": curve.times[0], "source_end": curve.times[1],
            "arc_length_scale": [float(x) for x in curve.scale], "length": curve.length}


def _spraying(spray) -> int:
    """Rows with the gun on."""
    return 0 if spray is None else int(np.count_nonzero(np.asarray(spray) > 0))


def write_retimed(traj: Trajectory, timing: TimeOptimal, path, carried: dict | None = None
                  ) -> Trajectory:
    """Write ``traj`` retimed by ``timing`` in the ``run`` input format (every float64 exact),
    atomically, with :func:`retime_metadata` in its sidecar, and ``carried`` (the source's
    frame, robot and gravity: :func:`~pollard_pin.io.trajectory.carried_metadata`) with it;
    the retimed trajectory."""
    from .table import write_table

    retimed = retimed_trajectory(traj, timing)
    if _spraying(retimed.spray) != _spraying(traj.spray):  # the film would change: never written
        raise ValueError(f"{traj.name}: a paint program retimed with its gun on: its film "
                         "would change (time it with dynamics.passes.time_optimal_program)")
    cols = {"t": retimed.t}
    for prefix, arr in (("", retimed.poses), ("d_", retimed.d_poses),
                        ("dd_", retimed.dd_poses)):
        cols.update({prefix + n: arr[:, i] for i, n in enumerate(TASK_NAMES)})
    if retimed.spray is not None:
        cols[SPRAY] = retimed.spray
    write_table(path, cols, {**retime_metadata(traj, timing), **(carried or {})}, fmt="csv")
    return retimed


__all__ = ["BETWEEN_ROWS", "retime_metadata", "retimed_trajectory", "write_retimed"]
