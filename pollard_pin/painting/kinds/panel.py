"""A still panel (docs/model.md §20–§21): plan_paint's raster, the film on the panel's grid,
paint.json's numbers and the lines ``pollard-pin paint`` prints."""
from __future__ import annotations

import time

import numpy as np

from ...dynamics.motors import Actuators
from ...version import __version__
from ..film.grid import plan_film
from ..film.stats import film_stats
from ..plan.panel import PaintPlan, plan_paint
from ..report import check_report, clearance_entries
from ..result import PaintFilm
from ..spray.deposition import Film
from ..summary import motor_use_line
from .base import JobKind


def paint(robot, job, act, options, res):
    """(plan, film, report) of a still panel."""
    t0 = time.perf_counter()
    plan = plan_paint(robot, job, act, options.policy)
    t1 = time.perf_counter()
    U, V, pts, film = plan_film(plan, res)
    t2 = time.perf_counter()
    rep = paint_report(plan, film, act)
    rep.update(timings={"plan": t1 - t0, "film": t2 - t1},
               grid={"nu": len(U), "nv": len(V), "resolution": res}, pollard_pin=__version__)
    return plan, PaintFilm(pts, film, res, grid=(U, V)), rep


def paint_report(plan: PaintPlan, f: Film, act: Actuators) -> dict:
    """The numbers of ``paint.json`` for a still panel: the job, film statistics [m], timing
    and layout, and each motor's peak utilisation (checked at CHECK_REFINE× the path's
    sampling).

    Parameters
    ----------
    plan : PaintPlan
        From :func:`~pollard_pin.painting.plan.plan_paint`.
    f : pollard_pin.painting.spray.deposition.Film
        Its film (:func:`~pollard_pin.painting.film.plan_film`).
    act : Actuators
        The motor ratings.

    Returns
    -------
    dict
        ``job``, ``thickness`` (mean, min, max, std [m], shares within ±5 % and ±10 %),
        ``target`` [m], ``cycle_time`` and ``lower_bound`` [s], passes, spacing, speed, the
        motors' use of their ratings, ...
    """
    j = plan.job
    tr = plan.trajectory
    swept = 2 * plan.half_length * len(plan.offsets) * plan.spacing * plan.coats
    steps = np.linalg.norm(np.diff(tr.poses[:, :3], axis=0), axis=1)
    rep = {
        "job": j.to_dict(),
        "thickness": film_stats(f.thickness, j.thickness),
        "target": j.thickness,
        "cycle_time": plan.cycle_time,
        "lower_bound": plan.lower_bound,
        "swept_lower_bound": swept * j.thickness / j.flow / plan.coats,
        "passes": plan.passes,
        "spacing": plan.spacing,
        "speed": plan.speed,
        "coats": plan.coats,
        "max_pass_speed": plan.max_speed,
        "direction": j.direction,
        "turnarounds": [float(d) for d, k in zip(plan.segments.duration, plan.segments.kind)
                        if k == "turn"],
        "samples": len(tr),
        **clearance_entries(plan),
        "motors": plan.motor_use(act.names),
        "motors_source": act.source,
        "integration": {"rule": "trapezoid over the path samples",
                        "time_step": float(tr.t[1] - tr.t[0]),
                        "largest_step_over_sigma": float(steps.max() / j.sigma),
                        "error_estimate_max": float(np.nanmax(f.error_estimate))},
    }
    return check_report(rep, plan.job.source)


def summary_lines(rep: dict, names) -> list[str]:
    """The report-style lines ``paint`` prints for a still panel."""
    th, target = rep["thickness"], rep["target"]
    return [
        f"passes {rep['passes']} ({rep['direction']}), spacing {rep['spacing'] * 1e3:.2f} mm, "
        f"speed {rep['speed']:.4g} m/s, coats {rep['coats']}",
        f"cycle {rep['cycle_time']:.3f} s; painting-only lower bound {rep['lower_bound']:.3f} s "
        f"(panel area × target / flow), {rep['swept_lower_bound']:.3f} s over the swept passes",
        f"film {th['min'] * 1e6:.4g}–{th['max'] * 1e6:.4g} µm, mean {th['mean'] * 1e6:.4g} µm "
        f"(target {target * 1e6:.4g} µm: {100 * th['deviation_min']:+.2f} % / "
        f"{100 * th['deviation_max']:+.2f} %), {100 * th['within_10pct']:.0f} % within ±10 %",
        motor_use_line(rep, names),
        f"planned in {rep['timings']['plan']:.2f} s, film map in {rep['timings']['film']:.2f} s "
        f"({rep['grid']['nu']} × {rep['grid']['nv']} points, {rep['samples']} path samples)",
    ]


KIND = JobKind("panel", paint, summary_lines)

__all__ = ["KIND", "paint", "paint_report", "summary_lines"]
