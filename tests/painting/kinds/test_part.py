"""A still part's mesh (painting/kinds/part.py): pp.paint's film and report are
plan_surface's, surface_film's and surface_report's (equal); the lines paint prints."""

import numpy as np

import pollard_pin as pp
from pollard_pin.painting.kinds import part
from pollard_pin.painting.options import PaintOptions


def test_part_is_the_part_planners(robot, act, curved_job, curved_plan):
    """examples/parts/curved_panel.toml at film spacing σ: plan_surface (the session's
    curved_plan, tests/examples_planned.py), surface_film and surface_report called directly
    give the same film and statistics (equal)."""
    from pollard_pin.painting.film.part import surface_film
    from pollard_pin.painting.report import surface_report

    job, plan = curved_job, curved_plan
    r = pp.paint(robot, job, act, PaintOptions(resolution=job.sigma, compliance=False))
    pts, f, painted, eff = surface_film(plan, job.sigma)
    direct = surface_report(plan, pts, f, painted, eff, act)
    assert r.kind == "part" and np.array_equal(r.film.thickness, f.thickness)
    assert np.array_equal(r.film.painted, painted) and r.film.efficiency == eff
    assert r.report.thickness == direct["thickness"]
    assert r.report.data["film_points"] == direct["film_points"]


def test_a_part_prints_a_parts_lines():
    from pollard_pin.painting.summary import part_summary_lines

    assert part.KIND.summary_lines is part_summary_lines and part.KIND.name == "part"
    assert not part.KIND.outputs.part_frame and not part.KIND.outputs.per_robot
