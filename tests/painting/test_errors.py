"""The paint planner's errors (paint/errors.py): a plan that does not exist is in the solve
family, as the kinematics' reach errors are, a value the planner cannot use in the input
family; one line, and a reach error carries the sample and pose that failed (here, checked
against the IK)."""
import numpy as np
import pytest

from pollard_pin.errors import InputError, PollardError, SolveError
from pollard_pin.kinematics.errors import KinematicsError, UnreachablePoseError
from pollard_pin.kinematics.ik import inverse_kinematics
from pollard_pin.painting.errors import JobKindError, PlanError, ReachError, ResolutionError


def test_family():
    assert issubclass(ReachError, PlanError) and issubclass(PlanError, SolveError)
    assert issubclass(UnreachablePoseError, SolveError)  # one family for a pose out of reach
    assert issubclass(PlanError, RuntimeError) and issubclass(PlanError, PollardError)
    assert not issubclass(PlanError, InputError)
    assert issubclass(ResolutionError, InputError) and issubclass(JobKindError, InputError)
    e = ReachError("out of reach", 7, np.zeros(6))
    assert (str(e), e.sample) == ("out of reach", 7) and e.pose.shape == (6,)


def test_reach_error_names_the_sample_and_pose_the_ik_refuses(robot, plan, act):
    """motion() on poses of the plan, one moved 0.5 m further out (x): the error names that
    sample and that pose, one line, and the IK alone refuses the pose too."""
    from pollard_pin.painting.checks.motion import motion

    tr = plan.trajectory
    poses = tr.poses[:10].copy()
    poses[6, 0] += 0.5
    with pytest.raises(ReachError) as info:
        motion(robot, act, poses, tr.d_poses[:10], tr.dd_poses[:10])
    e = info.value
    assert "\n" not in str(e) and e.sample == 6
    assert np.array_equal(e.pose, poses[6])
    with pytest.raises(KinematicsError):
        inverse_kinematics(robot, poses[6:7], 0 * poses[6:7], 0 * poses[6:7], np.zeros(1))
