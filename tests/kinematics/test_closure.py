"""Forward kinematics and loop closure (kinematics/closure.py) along the IK runs: the
Pinocchio closure solve back to the input poses, and the closure residual recomputed with
Pinocchio and with the numpy chain of docs/model.md §3–4 (no Pinocchio)."""
import numpy as np
import pytest
from ik_runs import RUN_NAMES, to_joints_order, wrap

import pollard_pin as pp
from pollard_pin.analytic import closed_form as T
from pollard_pin.errors import InputError
from pollard_pin.kinematics.errors import KinematicsInputError
from pollard_pin.model.build import constraint_residual

FK_TOL = 1e-10  # m and rad: Pinocchio's forward-kinematics Newton (achieves 2.4e-12)
ROUND_OFF = 1e-13  # m and rad: closed-form chains and the IK's own residuals (achieve 1.1e-15)
CLOSURE_TOL = 1e-13  # m (achieves 7.6e-16)


@pytest.mark.parametrize("name", RUN_NAMES)
def test_forward_kinematics_reproduces_input_poses(robot, runs, name):
    traj, ik = runs[name]
    step = 4 if name == "thesis" else 2  # subsample: FK warm-starts from the previous sample
    act = ik.q[::step, robot.actuated_v]
    qs, poses = pp.forward_kinematics(robot, act)
    want = traj.poses[::step]
    assert np.abs(poses[:, :3] - want[:, :3]).max() <= FK_TOL
    assert np.abs(wrap(poses[:, 3:] - want[:, 3:])).max() <= FK_TOL
    assert np.abs(wrap(qs - ik.q[::step])).max() <= 5e-10  # achieves 3.4e-12
    # The numpy forward chain of docs/model.md §3 (no Pinocchio) from all IK tree angles.
    fk = T.forward_tool_pose(robot.params, to_joints_order(robot, ik.q))
    assert np.abs(fk[:, :3] - traj.poses[:, :3]).max() <= ROUND_OFF
    assert np.abs(wrap(fk[:, 3:] - traj.poses[:, 3:])).max() <= ROUND_OFF


@pytest.mark.parametrize("name", RUN_NAMES)
def test_closure_residual_along_trajectory(robot, runs, name):
    traj, ik = runs[name]
    assert ik.closure_residual.shape == (len(traj),)
    assert ik.closure_residual.max() <= CLOSURE_TOL
    assert ik.tool_error.max() <= ROUND_OFF
    m, d = robot.model, robot.data
    res = np.array([constraint_residual(m, d, robot.constraint_models, robot.constraint_datas, q)
                    for q in ik.q[::2]])
    assert res.shape == (len(ik.q[::2]), 6)
    assert np.abs(res).max() <= CLOSURE_TOL
    # Independently with the numpy chain of docs/model.md §3/§4: link ball centre vs attachment
    # point.
    cp = T.closure_points(robot.params, to_joints_order(robot, ik.q))
    assert np.linalg.norm(cp[..., 0, :] - cp[..., 1, :], axis=-1).max() <= CLOSURE_TOL


@pytest.mark.parametrize("actuated, q_guess, says", [
    (np.zeros(5), None, r"actuator angles have shape \(5,\)"),
    (np.zeros((1, 1, 6)), None, r"actuator angles have shape \(1, 1, 6\)"),
    ("abc", None, "actuated = 'abc': expected an array of real numbers"),
    ([10**400] * 6, None, "actuated = .*expected an array of real numbers"),
    (np.full(6, np.nan), None, "actuator angles must be 6 finite numbers"),
    (None, np.zeros(5), "q_guess must be 12 finite joint angles"),
    (None, "x", "q_guess = 'x': expected an array of real numbers"),
])
def test_forward_kinematics_refuses_bad_arguments(robot, actuated, q_guess, says):
    """A wrong shape, a non-number or a NaN: one KinematicsInputError line (an InputError and
    still a ValueError), before Pinocchio is given the vector."""
    act = robot.home()[robot.actuated_v] if actuated is None else actuated
    with pytest.raises(KinematicsInputError, match=says) as got:
        pp.forward_kinematics(robot, act, q_guess)
    assert isinstance(got.value, ValueError) and "\n" not in str(got.value)
    with pytest.raises(InputError, match="robot = None: expected a Robot"):
        pp.forward_kinematics(None, robot.home()[robot.actuated_v])


def test_tool_pose_refuses_a_configuration_of_another_size(robot):
    from pollard_pin.kinematics import tool_pose

    with pytest.raises(KinematicsInputError, match=r"^q has shape \(5,\), expected \(12,\)"):
        tool_pose(robot, np.zeros(5))
