"""An end robot of a proposed cell seated by its plan (painting/layout/seat.py, docs/model.md
§26.5): refused where its band just holds the top edge, moved up to the first place that
plans, its seam held by both bands, the cell then painting the part."""
import math
from dataclasses import replace

import pytest
from cell_split_jobs import tall_panel

from pollard_pin.painting.cell.bands import STEP, job_strokes, robot_band
from pollard_pin.painting.cell.robots import CellRobot
from pollard_pin.painting.cell.split import split_cell
from pollard_pin.painting.errors import PlanError
from pollard_pin.painting.layout.cell import cover_edge
from pollard_pin.painting.layout.seat import SEAT_TRIES, paint_seated
from pollard_pin.painting.options import PaintOptions
from pollard_pin.painting.policy import PlannerPolicy


@pytest.fixture(scope="module")
def low_top(robot):
    """A narrow 0.33 m panel and two robots, the top one as low as its band still holds the
    top edge's run-on (cover_edge downwards): the passes' tops run 15 mm out of its reach."""
    job = tall_panel(height=0.33, z=0.18, width=0.15)
    strokes = job_strokes(job)
    top = strokes.needed(-math.inf, math.inf)[1]
    high = cover_edge(robot, CellRobot("high", (0.0, 0.75, 0.17)), strokes, (top - STEP, top),
                      toward=-1.0)
    return replace(job, robots=(CellRobot("low"), high)), strokes


def test_a_refused_top_robot_is_seated_at_the_first_place_that_plans(robot, low_top,
                                                                    monkeypatch):
    """Each robot's plan alone (plans_alone) is read from the seating's own calls, their
    splits checked equal to the ones made here (split_cell): the same answers the test once
    asked for again, each a plan of a second or so."""
    job, strokes = low_top
    from pollard_pin.painting.cell import plan as cell_plan
    from pollard_pin.painting.layout import seat

    planned = []  # the zone programs made, by robot: the search's are the cell's
    alone = []  # (robot, its split's seams, the policy's seams, plans_alone's answer)

    def counted(model, act, job_b, view, *args):
        planned.append(view.zone.robot)
        return plan_zone(model, act, job_b, view, *args)

    def asked(model, job_a, cell_robot, act_a, split_a, part, policy_a):
        got = plans_alone(model, job_a, cell_robot, act_a, split_a, part, policy_a)
        alone.append((cell_robot, [(z.robot, z.lo, z.hi) for z in split_a.zones],
                      policy_a.seams, got))
        return got

    plan_zone, plans_alone = cell_plan.plan_zone, seat.plans_alone
    low, high = job.robots
    policy = PlannerPolicy(clearance_stride=8)  # the clearances are not what is tested
    split = split_cell(robot, job, job.robots)
    # seated and painted at the job's line speed
    monkeypatch.setattr(cell_plan, "plan_zone", counted)
    monkeypatch.setattr(seat, "plans_alone", asked)
    robots, painted = paint_seated(robot, replace(job, robots=()), job.robots, options=
                                   PaintOptions(resolution=0.005, compliance=False,
                                                policy=policy))
    monkeypatch.undo()
    # as proposed: the low robot plans alone, the high one is refused out of reach
    zones = [(z.robot, z.lo, z.hi) for z in split.zones]
    first = {r.name: (z, seams, got) for r, z, seams, got in alone[::-1] if r in (low, high)}
    assert first["low"][:2] == (zones, None) and first["low"][2] is None
    assert first["high"][:2] == (zones, None)
    assert "out of reach" in str(first["high"][2])
    assert painted.plan.speed == job.line.speed
    assert planned.count("low") == 1  # planned alone, then taken by the cell's plan
    assert robots[0] == low
    seated = robots[1]
    k = round((seated.base[2] - high.base[2]) / STEP)
    assert 1 <= k <= SEAT_TRIES
    assert seated.base == pytest.approx((high.base[0], high.base[1], high.base[2] + k * STEP),
                                        abs=1e-6)
    # the seam stays the split's: both bands still hold it with R past it (the bands, not
    # the planner, say so)
    seams = tuple(z.hi for z in painted.plan.split.zones[:-1])
    assert seams == (split.zones[0].hi,)
    for r, (lo, hi) in ((low, (-math.inf, seams[0])), (seated, (seams[0], math.inf))):
        need = strokes.needed(lo, hi)
        assert robot_band(robot, r, strokes).holding(*need).holds(*need)
    # the place a step below was refused: the first that plans
    lower = replace(seated, base=(*seated.base[:2], round(seated.base[2] - STEP, 6)))
    at = split_cell(robot, replace(job, robots=(low, lower)), (low, lower), seams=seams)
    below = [(z, s, got) for r, z, s, got in alone if r == lower]
    assert below and below[-1][:2] == ([(z.robot, z.lo, z.hi) for z in at.zones], seams)
    assert isinstance(below[-1][2], PlanError)
    # the cell paints its film (the robots' programs on the part, not their reach)
    assert painted.report.thickness["within_5pct"] >= 0.99
