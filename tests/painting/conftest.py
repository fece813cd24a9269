"""The example job, motors and plan, planned once for every paint test (package scope)."""
from pathlib import Path

import pytest
from line_parts import write_line_part

from pollard_pin.dynamics.motors import load_actuators
from pollard_pin.painting.film.grid import plan_film
from pollard_pin.painting.job import load_job
from pollard_pin.painting.plan.panel import plan_paint

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="package")
def act():
    return load_actuators(ROOT / "examples" / "actuators.toml")


@pytest.fixture(scope="package")
def job():
    return load_job(ROOT / "examples" / "paint.toml")


@pytest.fixture(scope="package")
def plan(robot, job, act):
    return plan_paint(robot, job, act)


@pytest.fixture(scope="package")
def film(plan):
    return plan_film(plan)


@pytest.fixture(scope="package")
def line_job():
    """examples/line.toml: a strip longer than the reach on a line (docs/model.md §24)."""
    return load_job(ROOT / "examples" / "line.toml")


@pytest.fixture(scope="package")
def line_plan(robot, line_job, act):
    from pollard_pin.painting.line.panel import plan_line

    return plan_line(robot, line_job, act)


@pytest.fixture(scope="package")
def line_part_job(tmp_path_factory):
    """A [part] on a [line] (docs/model.md §24): :func:`write_line_part`."""
    return load_job(write_line_part(tmp_path_factory.mktemp("line_part")))


@pytest.fixture(scope="package")
def line_part_plan(robot, line_part_job, act):
    from pollard_pin.painting.line.panel import plan_line

    return plan_line(robot, line_part_job, act)
