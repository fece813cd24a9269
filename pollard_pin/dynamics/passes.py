"""The time-optimal cycle of a paint program that keeps its film (docs/model.md §19).

Where the gun sprays, the film depends on the gun's speed along the surface, so every
interval with the gun on at either end keeps its planned timing. The stretches where it is
off (approach, turnarounds, return) are retimed time-optimally, TOPP-RA between the planned
path rates at their ends, so that they join the passes C¹ in the pose. A gun-off stretch
whose end rates TOPP-RA cannot hold keeps its planned timing too. A path that waits (a line
job's conveyor) times its passes to the world outside: everything up to its last pass is
kept, only what follows is retimed. Each retimed stretch costs a TOPP-RA solve (≈ 0.5 s, at
least 201 rows), so only those of ``MIN_SAMPLES`` samples or more are, the ``MAX_RETIMED``
longest of them (all 835 stretches of a 5008-sample program whose gun toggles every 3 samples
take 9 minutes, 2.1 GB and 206,000 rows).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..kinematics.errors import SAMPLE_ERRORS
from ..paths.trajectory import trajectory_curve
from .cycle import join, moving_segments, time_optimal_path
from .motors import ActuatorError, Actuators
from .path import path_dynamics_at
from .timeopt import Options, TimeOptimal, utilisation

MIN_SAMPLES = 16  # a shorter gun-off stretch keeps its plan (a turnaround at 2 ms: 40–100)
MAX_RETIMED = 32  # gun-off stretches retimed at most, the longest (the rest keep their plan)


def sprays(traj) -> bool:
    """Whether ``traj`` carries a paint gun's trigger that is on somewhere: its film then
    depends on its timing there."""
    spray = getattr(traj, "spray", None)
    return spray is not None and bool(np.any(np.asarray(spray) > 0))


def waits(traj) -> bool:
    """Whether ``traj`` stands still at one pose between two of its samples
    (:func:`~.cycle.moving_segments`)."""
    moving = sum(b - a - 1 for a, b in moving_segments(traj))
    return bool(np.any(traj.d_poses) or np.any(traj.dd_poses)) and moving < len(traj.t) - 1


def spray_stretches(traj) -> list[tuple[int, int, bool]]:
    """``(start, stop, on)`` of each stretch of ``traj`` (samples ``start:stop``, consecutive
    stretches sharing their join sample), in order: ``on`` where every interval has the gun
    on at one end at least, else off at both ends of every interval. A path that waits: one
    stretch, on, up to the end of its last pass."""
    spray = np.asarray(traj.spray, dtype=float)
    on = (spray[:-1] > 0) | (spray[1:] > 0)  # per interval
    bounds = [0, *(np.flatnonzero(np.diff(on)) + 1), len(on)]
    out = [(int(a), int(b) + 1, bool(on[a])) for a, b in zip(bounds[:-1], bounds[1:])]
    if waits(traj) and on.any():
        last = max(k for k, (_, _, is_on) in enumerate(out) if is_on)
        out = [(0, out[last][1], True)] + out[last + 1:]
    return out


def planned(robot, act: Actuators, window) -> TimeOptimal:
    """``window`` traversed as planned: s = (t − t0)/T, ṡ = 1/T, s̈ = 0 on its own curve, its
    worst utilisation at its samples and halfway between them in ``between``."""
    t = np.asarray(window.t, dtype=float)
    t0, span = float(t[0]), float(t[-1] - t[0])
    curve = trajectory_curve(window)
    s = (t - t0) / span
    half = np.empty(2 * len(s) - 1)  # the samples and the points halfway, in order
    half[0::2], half[1::2] = s, (s[:-1] + s[1:]) / 2
    dense = path_dynamics_at(robot, curve, t0, span, half)
    use = utilisation(act, dense, np.zeros(len(half)), np.full(len(half), 1.0 / span)).max(1)
    worst = int(np.argmax(use))
    return TimeOptimal(s=s, t=t - t0, s_dot=np.full(len(s), 1.0 / span),
                       s_ddot=np.zeros(len(s)), iterations=0, per_interval=1,
                       between=float(use[worst]), between_at=float(half[worst]),
                       path=dense.take(slice(None, None, 2)), curve=curve, t0=t0, span=span,
                       planned=window)


def time_optimal_program(robot, act: Actuators, traj, options: Options | None = None
                         ) -> tuple[TimeOptimal, dict]:
    """The fastest traversal of the paint program ``traj`` that keeps its film (the module's
    doc): its stretches one after the other (``parts``, flat: consecutive stretches kept as
    planned are one part, a retimed stretch that waits gives one part per moving segment),
    and a summary for the report."""
    stretches = spray_stretches(traj)
    chosen = _chosen(traj, stretches)
    parts, kept = _parts(robot, act, traj, stretches, chosen, options or Options())
    off = sum(not on for _, _, on in stretches)
    retimed = len(chosen) - len(kept)
    summary = {
        "gun_on_stretches": len(stretches) - off, "gun_off_stretches": off,
        "gun_off_retimed": retimed, "gun_off_as_planned": off - retimed,
        "timed_to_waits": waits(traj),
        "summary": (f"the film kept: {len(stretches) - off} stretch(es) with the gun on as "
                    f"planned, {retimed} of {off} gun-off stretch(es) retimed between the "
                    "passes' path rates" + ("; the path waits (a conveyor?): everything up "
                                            "to its last pass as planned"
                                            if waits(traj) else "")),
    }
    if off > len(chosen):
        summary["summary"] += (f"; {off - len(chosen)} kept as planned: shorter than "
                               f"{MIN_SAMPLES} samples or beyond the {MAX_RETIMED} longest")
    if kept:  # said once: the first stretch and why, the count
        summary["as_planned_because"] = kept[0]
        summary["summary"] += (f"; {len(kept)} kept as planned: TOPP-RA found no traversal "
                               f"between the path rates at its ends (first, {kept[0]})")
    return join(parts), summary


def _parts(robot, act, traj, stretches, chosen, options):
    """The traversals of ``stretches``: the ``chosen`` ones retimed where TOPP-RA can, the
    others and those as planned, runs of them joined; and why each chosen one failed."""
    parts, kept, run = [], [], None  # run: samples of the stretches as planned, not yet added
    for k, (start, stop, _) in enumerate(stretches):
        part = None
        if k in chosen:
            try:
                part = time_optimal_path(robot, act, traj.window(start, stop),
                                         replace(options, end_rates=True))
            except (ActuatorError, *SAMPLE_ERRORS) as exc:
                kept.append(f"t = {traj.t[start]:.4g}…{traj.t[stop - 1]:.4g} s: {exc}")
        if part is None:
            run = (start if run is None else run[0], stop)
            continue
        if run is not None:
            parts.append(planned(robot, act, traj.window(*run)))
            run = None
        parts.extend(part.parts or (part,))
    if run is not None:
        parts.append(planned(robot, act, traj.window(*run)))
    return parts, kept


def _chosen(traj, stretches) -> set[int]:
    """Indices of the gun-off stretches to retime: at least MIN_SAMPLES samples, the
    MAX_RETIMED longest in time."""
    long = [k for k, (a, b, on) in enumerate(stretches) if not on and b - a >= MIN_SAMPLES]
    long.sort(key=lambda k: traj.t[stretches[k][0]] - traj.t[stretches[k][1] - 1])
    return set(long[:MAX_RETIMED])


__all__ = ["MAX_RETIMED", "MIN_SAMPLES", "planned", "spray_stretches", "sprays",
           "time_optimal_program", "waits"]
