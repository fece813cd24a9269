"""The film a plan leaves (paint/film/grid.py, docs/model.md §20–21): its grid, its statistics
against the target and the spacing rule, and its integration against a finer one."""
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from pollard_pin.dynamics.motors import load_actuators
from pollard_pin.painting.errors import PlanError, ResolutionError
from pollard_pin.painting.film import grid as film_module
from pollard_pin.painting.film.grid import film_resolution, plan_film
from pollard_pin.painting.film.stats import film_stats
from pollard_pin.painting.job import load_job
from pollard_pin.painting.plan.panel import plan_paint


def test_film_within_two_percent_edges_included(plan, film, job):
    """Target ±2 %; the layout allows 1 % and the film achieves −0.81 % / +0.50 %."""
    U, V, _, f = film
    assert U[0] == -job.width / 2 and U[-1] == job.width / 2  # edges on the grid
    assert V[0] == -job.height / 2 and V[-1] == job.height / 2
    step = job.sigma / 3 * (1 + 1e-12)  # σ/3, to round-off
    assert np.diff(U).max() <= step and np.diff(V).max() <= step
    st = film_stats(f.thickness, job.thickness)
    assert -0.02 <= st["deviation_min"] and st["deviation_max"] <= 0.02
    assert st["within_10pct"] == 1.0
    assert f.error_estimate.max() < 1e-3 * job.thickness  # the integration's 0.1 %


def test_interior_film_is_flow_over_speed_times_spacing(plan, film, job):
    """Away from the edges the film is flow/(speed·spacing) within the ripple bound."""
    U, V, _, f = film
    th = f.thickness.reshape(len(V), len(U))
    inner = th[np.abs(V) < job.height / 4][:, np.abs(U) < job.width / 4]
    expected = job.flow * plan.coats / (plan.speed * plan.spacing)
    assert expected == pytest.approx(job.thickness, rel=1e-12)
    # the spacing rule's ripple, 2·exp(−2π²σ²/Δ²) = 0.5 % (leading Poisson term)
    assert np.abs(inner / expected - 1).max() < 0.0051


@pytest.mark.parametrize("resolution", [0.0, -1.0, math.nan, math.inf, 0.0101, "0.005"])
def test_a_film_grid_coarser_than_the_spot_or_not_a_spacing(job, resolution):
    # coarser than σ, the grid would miss the ripple between passes (some 2σ apart)
    with pytest.raises(ResolutionError, match="must be > 0 and at most the spray spot's σ = "
                                              "0.01 m"):
        film_resolution(job, resolution)


def test_film_resolution_default_and_limit(job):
    assert film_resolution(job) == job.sigma / 3 and film_resolution(job, job.sigma) == job.sigma


def test_film_integration_converged(plan, film, job):
    """The film of the written samples against the same path integrated at 4× the sampling
    (exact segment positions): the planner's 2 ms steps are converged far below the required
    0.1 % of the target (achieved 5e-11 relative); the a-posteriori estimate (achieved 1.4e-9
    of the target) bounds it."""
    from pollard_pin.painting.passes.raster import task_motion
    from pollard_pin.painting.spray.deposition import film as integrate
    from pollard_pin.painting.spray.deposition import gun_of

    U, V, pts, f = film
    pick = np.r_[0:len(U) * len(V):37, len(U) * len(V) - 1]  # a spread of points, a corner
    s = pts.reshape(-1, 3)[pick]
    seg = plan.segments
    t = np.linspace(0, seg.total, 4 * (len(plan.trajectory) - 1) + 1)
    poses = task_motion(plan.frame, job.standoff, *seg.evaluate(t))[0]
    axes = np.tile(-plan.frame.n, (len(t), 1))
    fine = integrate(gun_of(job), t, poses[:, :3], axes, s, plan.frame.n, origin=plan.frame.c)
    rel = np.abs(f.thickness[pick] / fine.thickness - 1).max()
    assert rel < 5e-9
    assert f.error_estimate.max() < 1.4e-7 * job.thickness
    assert f.error_estimate.max() > rel * f.thickness.min()


EXAMPLES = Path(__file__).resolve().parents[3] / "examples"


def test_film_grid_budget_is_checked_in_floats():
    job = load_job(EXAMPLES / "paint.toml")
    assert film_resolution(job) == pytest.approx(job.sigma / 3)
    for res, says in ((1e-6, r"makes 3.12e\+10 film points"), (1e-300, "makes inf film points")):
        with pytest.raises(ResolutionError, match=says):
            film_resolution(job, res)  # floats: a 600-digit count is never made


def test_film_pairs_budget(robot, monkeypatch):
    job = load_job(EXAMPLES / "paint.toml")
    job = replace(job, width=0.1, height=0.05)
    plan = plan_paint(robot, job, load_actuators(EXAMPLES / "actuators.toml"))
    monkeypatch.setattr(film_module, "MAX_FILM_PAIRS", 1e5)
    with pytest.raises(PlanError, match="point × sample pairs"):
        plan_film(plan)
