"""Forward recursions over the model tree (kinematics/tree.py) against Pinocchio's own
placements, velocities and classical accelerations, at random configurations."""
import numpy as np
import pinocchio as pin

from pollard_pin.kinematics.tree import cross, joint_motion, joint_placements


def test_cross_is_numpys():
    rng = np.random.default_rng(0)
    a, b = rng.normal(size=(5, 3)), rng.normal(size=(1, 3))
    assert np.abs(cross(a, b) - np.cross(a, b)).max() < 1e-15


def test_motion_matches_pinocchio(robot):
    """World rotation and origin of each joint, its body's angular velocity and its origin's
    velocity and (classical) acceleration, against pin.forwardKinematics with LOCAL_WORLD_ALIGNED
    frames (achieved 1e-15; asserted 1e-12)."""
    model = robot.model
    data = model.createData()
    rng = np.random.default_rng(4)
    n = 6
    Q = rng.uniform(-np.pi, np.pi, (n, model.nq))
    V, A = rng.normal(size=(n, model.nv)), rng.normal(size=(n, model.nv))
    m = joint_motion(model, Q, V, A)
    pl = joint_placements(model, Q, range(1, model.njoints))
    LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
    for k in range(n):
        pin.forwardKinematics(model, data, Q[k], V[k], A[k])
        for j in range(1, model.njoints):
            M = data.oMi[j]
            assert np.abs(pl[j][0][k] - M.rotation).max() < 1e-12
            assert np.abs(m.o[j][k] - M.translation).max() < 1e-12
            v = pin.getVelocity(model, data, j, LWA)
            a = pin.getClassicalAcceleration(model, data, j, LWA)
            assert np.abs(m.w[j][k] - v.angular).max() < 1e-12, j
            assert np.abs(m.vo[j][k] - v.linear).max() < 1e-12, j
            assert np.abs(m.alpha[j][k] - a.angular).max() < 1e-12, j
            assert np.abs(m.ao[j][k] - a.linear).max() < 1e-12, j
