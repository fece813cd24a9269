"""The IK runs of tests/ik_runs.py, solved once for every kinematics test (package scope)."""
import pytest
from ik_runs import ik_runs


@pytest.fixture(scope="package")
def runs(robot):
    """name → (trajectory, IKResult) for each of ik_runs.RUN_NAMES."""
    return ik_runs(robot)
