"""A panel on a line (painting/kinds/line_panel.py): pp.paint's world path and film
statistics are plan_line's, line_film's and line_report's at the job's speed (equal); the
lines paint prints."""
import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.painting.kinds.line_panel import line_report, summary_lines
from pollard_pin.painting.options import PaintOptions


@pytest.fixture(scope="module")
def paint_result(robot, line_job, act):
    """pp.paint of examples/line.toml without compliance (read, never changed)."""
    return pp.paint(robot, line_job, act, PaintOptions(compliance=False))


def test_line_panel_is_the_line_planners(paint_result, line_job, line_plan, line_plan_film, act):
    """examples/line.toml: the world path and film statistics of plan_line + line_film +
    line_report at the job's speed (equal)."""
    r = paint_result
    U, V, _, f = line_plan_film  # line_film(line_plan)
    direct = line_report(line_plan, f, act, {"nu": len(U), "nv": len(V)})
    assert r.kind == "line panel" and r.report.line["searched"] is False
    assert np.array_equal(r.plan.trajectory.poses, line_plan.trajectory.poses)
    assert r.report.thickness == direct["thickness"]
    assert r.report.line["speed"] == direct["line"]["speed"] == line_job.line.speed


def test_summary_lines(paint_result, act):
    """The line's three lines first (the speed not searched, the strokes), then the
    panel's."""
    r = paint_result
    rep = r.report.data
    lines = summary_lines(rep, act.names)
    assert lines[0].startswith(f"line speed {rep['line']['speed']:.4g} m/s, upper bound")
    assert f"{rep['line']['parts_per_hour']:.1f} parts per hour" in lines[1]
    assert lines[2] == ("strokes across the travel, stepping from the leading end; waits at "
                        "the turnarounds none")
    assert lines[3].startswith(f"passes {rep['passes']} (") and "relative to the part" in lines[3]
    assert lines[5].startswith("motor peak torque") and len(lines) == 7
    assert r.summary_lines()[:7] == lines  # then the gun body's clearance (no compliance)
    assert not any(line.startswith("compliance") for line in r.summary_lines())


def test_a_pass_out_of_one_robots_reach_names_a_cell(monkeypatch):
    """A part too tall or too long for one robot on the line: the refusal says a cell may
    paint it (--robots), within the line's room, the asides in words given way first."""
    import pytest

    import pollard_pin.painting.kinds.line_panel as kind
    from pollard_pin.errors import MESSAGE_ROOM
    from pollard_pin.painting.errors import LineReachError

    said = ("all 19 passes out of reach at any place on the line: pass 10 is 0.561 m (run-on "
            "included), at most 0.412 m of it in reach, 149 mm too tall for the reach: turn, "
            "move or split the part")

    def refuses(*args, **kwargs):
        raise LineReachError(said)

    monkeypatch.setattr(kind, "plan_line_job", refuses)
    with pytest.raises(LineReachError) as info:
        kind.line_plan(None, None, None, PaintOptions())
    msg = str(info.value)
    assert len(msg) <= MESSAGE_ROOM, msg
    assert msg == said.replace(" (run-on included)", "") + (
        ", or a cell of robots (paint --robots N|auto)"), msg
