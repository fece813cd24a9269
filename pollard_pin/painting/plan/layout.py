"""A still panel's raster before the motors have their say (docs/model.md §21): the spacing,
pass speed, coats and pass positions of a job (:func:`panel_layout`), and the path's sample
times (:func:`path_times`), each within its budget (:class:`..policy.PlannerPolicy`),
checked before anything is built."""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from ..errors import BudgetError, PlanError
from ..job import PaintJob
from ..passes.raster import (
    PROFILE_TOLERANCE,
    Segments,
    job_spacing,
    pass_offsets,
    ripple_spacing,
    spot_runon,
)
from ..passes.surface import pass_speed
from ..policy import DEFAULT_POLICY, PlannerPolicy
from ..spray.spots import STROKES
from ..workpiece.panel import PanelFrame, panel_frame


class PanelLayout(NamedTuple):
    """A panel's raster before the motors have their say."""

    frame: PanelFrame
    offsets: np.ndarray  # pass positions across the passes [m]
    half_length: float  # passes run at constant speed over |U| ≤ half_length
    speed: float  # pass speed [m/s]: the job's, or the one its film needs
    coats: int
    spacing: float  # between passes [m]


def panel_layout(job: PaintJob, policy: PlannerPolicy = DEFAULT_POLICY) -> PanelLayout:
    """The job's :class:`PanelLayout` before the motors have their say, its budgets
    (``policy``'s) checked: the raster's layout, shared with the moving line
    (painting/line/panel.py)."""
    frame = panel_frame(job)
    horizontal = job.direction == "horizontal"
    length, extent = (job.width, job.height) if horizontal else (job.height, job.width)
    coats = job.coats or 1
    if job.spacing is not None:
        spacing = job.spacing
    elif job.speed is not None:
        spacing = job.flow * coats / (job.thickness * job.speed)
    else:
        spacing = job_spacing(job)
    # pass_offsets' count, give or take the edges
    passes = (extent / spacing + 1) * coats if spacing > 0 else math.inf
    if passes > policy.max_passes:
        raise BudgetError(f"{job.source}: {passes:.3g} passes ({coats} coat(s) at spacing "
                          f"{spacing * 1e3:.4g} mm over {extent:g} m), budget {policy.max_passes}: "
                          "a wider spacing, fewer coats or a smaller panel")
    speed = pass_speed(job, spacing)  # an absurd one refused as a part's is (a unit slip)
    half_length = length / 2 + spot_runon(job.sigma, job.spot)
    # the passes alone, before any turnaround: their samples bound the path's from below
    passing = passes * 2 * half_length / speed if speed > 0 else math.inf
    check_samples(passing / policy.step(job.sigma, speed) if speed > 0 else math.inf,
                  passing, speed, job, policy)
    try:
        offsets = pass_offsets(extent, spacing, job.sigma, spot=job.spot,
                               direction=STROKES[job.direction])
    except ValueError as exc:  # name the job entries the spacing came from
        origin = ("job.spacing" if job.spacing is not None else
                  "job.speed" + (" and job.coats" if job.coats else "")
                  if job.speed is not None else "the ripple rule")
        raise PlanError(f"{job.source}: {origin}: {exc}") from None
    return PanelLayout(frame, offsets, half_length, speed, coats, spacing)


def spot_too_fine(job: PaintJob, speed: float, spacing: float,
                  vmax: float | None = None) -> str | None:
    """Why a gun too fast for the robot is the spot's doing, or None: a spot whose stripe
    needs passes closer than the Gaussian of its width for the ripple rule (docs/model.md
    §21: a β spot's steep rim), so a faster gun. With the motors' fastest pass ``vmax``
    [m/s], the spacing they would allow and its ripple (the job's ``spacing`` trades ripple
    for speed); without, the cause of ramps and turnarounds out of reach."""
    tol = PROFILE_TOLERANCE / 2
    if job.spot is None or job.spacing is not None or job.speed is not None:
        return None
    gauss = ripple_spacing(job.sigma, tol)
    if spacing >= gauss * (1 - 1e-9):
        return None
    what = ", ".join(f"{k} {v:.4g}" for k, v in job.spot.params().items() if k != "radius")
    why = (f"the {job.spot.name} spot ({what}) needs passes {spacing * 1e3:.4g} mm apart "
           f"for ±{tol * 100:g} % ripple")
    if vmax is None:
        most = job.spot.spacing(PROFILE_TOLERANCE, STROKES[job.direction])  # the layout's ±1 %
        return (f"{why}, so {speed:.4g} m/s: a lower flow or job.spacing up to "
                f"{most * 1e3:.4g} mm (±{PROFILE_TOLERANCE * 100:g} %)")
    wider = spacing * speed / vmax  # film ∝ 1/(speed·spacing): the motors' pass
    ripple = float(job.spot.ripple(wider, STROKES[job.direction]))
    return (f"{why} (a Gaussian of its width: {gauss * 1e3:.3g} mm), so {speed:.4g} m/s; "
            f"the motors allow {vmax:.4g}: job.spacing {wider * 1e3:.4g} mm (ripple "
            f"±{ripple * 100:.2g} %) or a lower flow")


def path_times(seg: Segments, job: PaintJob, speed: float, how=np.linspace,
               policy: PlannerPolicy = DEFAULT_POLICY) -> np.ndarray:
    """The path's sample times: steps of at most ``policy.max_step`` and
    ``policy.step_sigma``·σ of gun travel, within ``policy.max_path_samples`` (checked before
    they are made)."""
    dt = policy.step(job.sigma, speed)
    n = math.ceil(seg.total / dt) + 1
    check_samples(n, seg.total, speed, job, policy)
    return np.arange(0.0, seg.total, dt) if how is np.arange else np.linspace(0.0, seg.total, n)


def check_samples(n: float, duration: float, speed: float, job: PaintJob,
                  policy: PlannerPolicy = DEFAULT_POLICY) -> None:
    if n > policy.max_path_samples:
        dt = policy.step(job.sigma, speed)
        fix = (f"fewer coats or {policy.coarser(dt, True)}" if job.speed is not None else
               f"{policy.coarser(dt, False)} or a smaller panel")
        raise BudgetError(f"{job.source}: the path needs {n:.3g} samples ({duration:.4g} s "
                          f"at a gun speed of {speed:.4g} m/s), budget "
                          f"{policy.max_path_samples:.3g}: {fix}, {policy.budget_fix}")


__all__ = ["PanelLayout", "check_samples", "panel_layout", "path_times", "spot_too_fine"]
