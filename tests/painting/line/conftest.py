"""A slow line's plan shared by the line tests (one per session): examples/line.toml at
0.01 m/s, a third of its speed, so it waits at the turnarounds (docs/model.md §24.1)."""
import pytest


@pytest.fixture(scope="session")
def slow_plan(robot, line_job, act):
    """examples/line.toml at 0.01 m/s (plan_line, clearance not checked): refused before the
    dwell, it now waits at each turnaround. Read, never written."""
    from pollard_pin.painting.line.panel import plan_line

    return plan_line(robot, line_job, act, 0.01, clearance=False)
