"""Joint loads from MuJoCo (crosscheck/mujoco_loads.py) against the free-body Newton–Euler
loads (numpy only): two engines that share no code, on a random smooth trajectory."""
import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.crosscheck.newton_euler import joint_loads
from pollard_pin.paths.curves import smooth_random_trajectory

AGREE = 2e-13  # relative to the peak force / moment (the engines agree to ~2e-15)


def test_mujoco_loads_equal_the_free_bodies(robot):
    pytest.importorskip("mujoco")
    from pollard_pin.crosscheck.mujoco import JOINTS
    from pollard_pin.crosscheck.mujoco_loads import joint_loads_mujoco

    traj = smooth_random_trajectory(2, samples=41)
    ik = pp.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    cols = [list(ik.joint_names).index(n) for n in JOINTS]
    mj = joint_loads_mujoco(ik.q[:, cols], ik.v[:, cols], ik.a[:, cols])
    ne = joint_loads(robot.params, traj.poses, traj.d_poses, traj.dd_poses)
    back = [list(JOINTS).index(n) for n in ne["joints"]]
    for key in ("force", "moment"):
        scale = np.abs(ne[key]).max()
        assert scale > 0.1
        assert np.abs(mj[key][:, back] - ne[key]).max() < AGREE * scale, key
    assert np.abs(mj["closure_forces"] - ne["closure_forces"]).max() < \
        AGREE * np.abs(ne["closure_forces"]).max()
