"""A part on a line (painting/kinds/line_part.py): pp.paint's film is that of the plan seen
from the part, surface_film's, and its report line_part_report's (equal); the lines paint
prints: the line's, then a part's."""
import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.painting.kinds.line_part import line_part_report, summary_lines
from pollard_pin.painting.options import PaintOptions
from pollard_pin.painting.policy import PlannerPolicy
from pollard_pin.painting.summary import line_lines, part_summary_lines


@pytest.fixture(scope="module")
def paint_result(robot, line_part_job, act):
    """pp.paint of tests/line_parts.py's strip on its line, strokes across the travel as
    the line_part_plan fixture's, without compliance (read, never changed)."""
    across = PaintOptions(compliance=False, policy=PlannerPolicy(strokes="across"))
    return pp.paint(robot, line_part_job, act, across)


def test_line_part_is_the_line_planners(paint_result, line_part_plan, line_part_film, act):
    """A [part] on a [line]: the film of the plan seen from the part, surface_film's, and
    the report's statistics (equal)."""
    r = paint_result
    pts, f, painted, eff = line_part_film  # surface_film(line_part_plan.in_part_frame())
    direct = line_part_report(line_part_plan, pts, f, painted, eff, act)
    assert r.kind == "line part"
    assert np.array_equal(r.film.thickness, f.thickness)
    assert r.report.thickness == direct["thickness"] and r.film.efficiency == eff


def test_summary_lines_are_the_lines_then_a_parts(robot, line_part_job, act):
    rep = pp.paint(robot, line_part_job, act, PaintOptions(compliance=False)).report.data
    lines = summary_lines(rep, act.names)
    assert lines == line_lines(rep) + part_summary_lines(rep, act.names)
    # auto: the short strip's strokes along the travel, a shorter cycle than across it
    assert lines[0].startswith("line speed") and lines[2] == (
        "strokes along the travel; waits at the turnarounds none")
    assert lines[3].startswith("passes")
