"""paint.json's numbers for a part (paint/surface_report.py), on the example panel as a mesh."""
import numpy as np
import pytest

from pollard_pin.paint.job import PartJob
from pollard_pin.paint.mesh import panel_part
from pollard_pin.paint.surface_plan import plan_surface, surface_film
from pollard_pin.paint.surface_report import surface_report


@pytest.fixture(scope="module")
def report(robot, act, job):
    part = panel_part(job)
    pj = PartJob(mesh="<panel>", position=(0.0, 0.0, 0.0), standoff=job.standoff,
                 sigma=job.sigma, flow=job.flow, thickness=job.thickness, source="panel")
    plan = plan_surface(robot, pj, act, part)
    pts, film, painted, te = surface_film(plan, job.sigma)
    return plan, surface_report(plan, pts, film, painted, te, act), pts, film


def test_report_numbers(report, act):
    plan, rep, pts, film = report
    th = rep["thickness"]
    assert th["min"] <= th["mean"] <= th["max"]
    assert 0 <= th["within_5pct"] <= th["within_10pct"] <= 1
    # a flat panel: the thickness is the area-weighted mean of the film points
    assert th["mean"] == pytest.approx(np.average(film.thickness, weights=pts.areas), rel=1e-12)
    job = plan.job
    assert rep["lower_bound"] == pytest.approx(plan.part.painted_area * job.thickness / job.flow)
    assert rep["largest_incidence_deg"] < 1e-6  # a flat panel: the gun is normal
    assert 0 < rep["transfer_efficiency"] < 1
    assert set(rep["motors"]) == set(act.names)
    assert rep["passes"] == len(plan.layout.passes)
    # the spline through the 1 mm samples: its speed within 1e-6 of the spot's (measured)
    assert rep["tip_speed_range"][0] == pytest.approx(plan.speed, rel=1e-4)
