"""The sample-by-sample Newton IK (kinematics/ik_newton.py) against the batched solver and
the closed form of docs/model.md §7."""
import numpy as np

from pollard_pin.analytic import closed_form as T
from pollard_pin.kinematics.ik_batch import inverse_kinematics_batch
from pollard_pin.kinematics.ik_newton import inverse_kinematics_newton
from pollard_pin.paths.curves import smooth_random_trajectory


def wrap(a):
    return np.pi - np.mod(np.pi - np.asarray(a), 2.0 * np.pi)


def test_newton_equals_batch_and_the_closed_form(robot):
    """On a random smooth trajectory: positions to 5e-13 rad (achieved ~4e-15), rates and
    accelerations to 5e-12 and 5e-11 (the batch solver's own, docs/model.md §7)."""
    traj = smooth_random_trajectory(4, samples=61)
    args = (robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    newton, batch = inverse_kinematics_newton(*args), inverse_kinematics_batch(*args)
    assert np.abs(wrap(newton.q - batch.q)).max() < 5e-13
    assert np.abs(newton.v - batch.v).max() < 5e-12
    assert np.abs(newton.a - batch.a).max() < 5e-11
    assert np.abs(wrap(newton.spherical - batch.spherical)).max() < 5e-13
    tree = [T.JOINTS.index(j) for j in robot.joint_names]
    ref = T.position_ik(robot.params, traj.poses)[:, tree]
    assert np.abs(wrap(newton.q - ref)).max() < 5e-13
    assert newton.closure_residual.max() < 1e-12 and newton.tool_error.max() < 1e-12
