"""PaintedJob (painting/result.py): summary_lines are the lines the CLI prints (the kind's,
then the shared ones: the clearance, the compliance, the paint used); the robots' folders
are a cell's only."""
from dataclasses import fields

import pytest

from pollard_pin.painting.accounting import material_lines
from pollard_pin.painting.kinds.panel import summary_lines
from pollard_pin.painting.result import PaintedJob
from pollard_pin.painting.summary import clearance_line, compliance_line


@pytest.fixture(scope="module")
def result(panel_result):
    """paint_job(robot, examples/paint.toml, examples/actuators.toml): the session's
    pp.paint of it (tests/examples_planned.py), that computation as the PaintedJob it is."""
    return PaintedJob(**{f.name: getattr(panel_result, f.name) for f in fields(PaintedJob)})


def test_summary_lines_are_the_kinds_then_clearance_and_compliance(result):
    """A still panel: its kind's five lines, the gun body's clearance, the compliance, the
    paint it uses (two lines: the example has a [paint] table); no folder per robot."""
    rep = result.report.data
    paint = material_lines(rep)
    assert len(paint) == 2 and paint[0].startswith("paint: ")
    assert result.summary_lines() == [*summary_lines(rep, result.actuators.names),
                                      clearance_line(rep), compliance_line(rep["compliance"]),
                                      *paint]
    assert result.robot_folders == () and result.painter.name == result.kind == "panel"
