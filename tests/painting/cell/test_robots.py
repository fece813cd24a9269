"""A cell's [[robot]] tables: frames against hand-made rotations, and each bad table one line."""
import json
import math

import numpy as np
import pinocchio as pin
import pytest

from pollard_pin.painting.cell.robots import (
    MAX_ROBOTS,
    CellRobot,
    base_footprint,
    check_spacing,
    robots_from_tables,
)
from pollard_pin.painting.errors import CellError, JobError
from pollard_pin.painting.job import job_from_dict, job_kind


def _job(robots=None, line=True) -> dict:
    d = {"panel": {"center": [0.70, -0.75, 0.16], "normal": [-1.0, 0.0, 0.0],
                   "width": 0.9, "height": 0.1},
         "gun": {"standoff": 0.15, "sigma": 0.010, "flow": 1.5e-7},
         "job": {"thickness": 25e-6}}
    if line:
        d["line"] = {"speed": 0.03, "direction": [0.0, 1.0, 0.0]}
    if robots is not None:
        d["robot"] = robots
    return d


def test_robots_make_a_cell_and_round_trip():
    job = job_from_dict(_job([{"name": "low", "base": [0, 0, 0]},
                              {"name": "high", "base": [0, 0.75, 0.17], "rotation": [0, 0, 90]}]))
    assert job_kind(job) == "cell panel"
    assert [r.name for r in job.robots] == ["low", "high"]
    assert job.robots[1].base == (0.0, 0.75, 0.17) and job.robots[0].is_origin
    again = job_from_dict(json.loads(json.dumps(job.to_dict())))  # as a file would say it
    assert again == job
    assert job_kind(job_from_dict(_job())) == "line panel"  # no [[robot]]: today's job


def test_frame_is_rx_ry_rz_about_world_axes():
    # R = Rx·Ry·Rz from Pinocchio's own rotations (independent of the package's code)
    rx, ry, rz = 20.0, -35.0, 130.0
    robot = CellRobot("a", (0.1, -0.2, 0.3), (rx, ry, rz))
    R = (pin.AngleAxis(math.radians(rx), np.array([1.0, 0, 0])).matrix()
         @ pin.AngleAxis(math.radians(ry), np.array([0, 1.0, 0])).matrix()
         @ pin.AngleAxis(math.radians(rz), np.array([0, 0, 1.0])).matrix())
    assert np.abs(robot.R - R).max() < 1e-14  # achieved ~1e-16
    p = np.array([[0.5, 0.2, -0.1], [0.0, 0.0, 0.0]])
    assert np.abs(robot.to_world(p) - (p @ R.T + [0.1, -0.2, 0.3])).max() < 1e-14
    assert np.abs(robot.to_base(robot.to_world(p)) - p).max() < 1e-14
    upside_down = CellRobot("u", (0, 0, 1.0), (180.0, 0, 0))
    assert np.abs(upside_down.direction_to_base([0, 0, -9.81]) - [0, 0, 9.81]).max() < 1e-13


@pytest.mark.parametrize("robots, words", [
    ([{"name": "a", "base": [0, 0, 0]}, {"name": "a", "base": [0, 1, 0]}],
     "two robots are named 'a'"),
    ([{"name": "Low", "base": [0, 0, 0]}, {"name": "b", "base": [0, 1, 0]},
      {"name": "lOW", "base": [0, 2, 0]}], "robots 'Low' and 'lOW' differ only in case "
                                           "(robot[0] and robot[2])"),
    ([{"name": "a", "base": [0, float("nan"), 0]}], "robot[0].base[1]"),
    ([{"name": "a", "base": [0, 0, 1e4]}], "within ±10 m"),
    ([{"name": "a", "base": [0, 0]}], "list of 3 numbers"),
    ([{"name": "a/b", "base": [0, 0, 0]}], "names the robot's folder"),
    ([{"name": "", "base": [0, 0, 0]}], "robot[0].name"),
    ([{"name": 7, "base": [0, 0, 0]}], "robot[0].name"),
    ([{"base": [0, 0, 0]}], "'robot[0].name' is missing"),
    ([{"name": "a", "base": [0, 0, 0], "rotaton": [0, 0, 0]}], "did you mean 'rotation'"),
    ([{"name": "a", "base": [0, 0, 0], "rotation": [0, 0, math.inf]}], "rotation[2]"),
    ([], "array of tables"),
    ({"name": "a", "base": [0, 0, 0]}, "array of tables"),
    ([{"name": f"r{i}", "base": [0, i, 0]} for i in range(MAX_ROBOTS + 1)], "at most 16"),
])
def test_bad_robot_tables_are_one_line(robots, words):
    with pytest.raises(CellError) as e:
        job_from_dict(_job(robots), "cell.toml")
    text = str(e.value)
    assert words in text and "\n" not in text and text.startswith("cell.toml: ")


def test_robots_need_a_line():
    with pytest.raises(JobError, match=r"\[\[robot\]\] needs \[line\]"):
        job_from_dict(_job([{"name": "a", "base": [0, 0, 0]}], line=False))


def test_bases_closer_than_a_robot_are_refused():
    import pollard_pin as pp

    size = 2 * base_footprint(pp.load().model)
    assert size == pytest.approx(2 * math.hypot(0.0, 0.085))  # the legs' base joints (§2)
    a, b = CellRobot("a", (0, 0, 0)), CellRobot("b", (0, size * 0.99, 0))
    with pytest.raises(CellError, match="robots 'a' and 'b' stand 168 mm apart"):
        check_spacing([a, b], size, "cell.toml")
    check_spacing([a, CellRobot("b", (0, size * 1.01, 0))], size)


def test_tables_validate_alone():
    (r,) = robots_from_tables("x", [{"name": "Low_1", "base": [1, 2, 3]}])
    assert r == CellRobot("Low_1", (1.0, 2.0, 3.0), (0.0, 0.0, 0.0))
