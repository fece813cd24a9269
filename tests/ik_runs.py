"""IK runs shared by the kinematics tests (tests/kinematics/conftest.py solves them once): the
default trajectory (2001 samples, docs/model.md §9) and three smooth random ones."""
import numpy as np

import pollard_pin as pp
from pollard_pin.analytic import closed_form as T
from pollard_pin.paths.curves import smooth_random_trajectory, thesis_trajectory

SEEDS = (1, 2, 3)
RUN_NAMES = ["thesis"] + [f"random{s}" for s in SEEDS]


def wrap(a):
    """Angles into (−π, π]."""
    return np.pi - np.mod(np.pi - np.asarray(a), 2.0 * np.pi)


def solve(robot, traj, **kw):
    """IK of ``traj``; ``kw``: IkOptions fields (method, margins, tol, ...), q_start, progress."""
    options = {k: kw.pop(k) for k in ("method", "margins", "tol", "max_iter", "chunk") if k in kw}
    return pp.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t,
                                 options=pp.IkOptions(**options), **kw)


def to_joints_order(robot, q_tree):
    """Pinocchio tree configuration (N, 12) → thesis JOINTS order (first 12)."""
    return q_tree[:, [robot.joint_names.index(n) for n in T.JOINTS[:12]]]


def ik_runs(robot):
    """name → (trajectory, IKResult) for every name of RUN_NAMES."""
    out = {}
    traj = thesis_trajectory()
    out["thesis"] = (traj, solve(robot, traj))
    for seed in SEEDS:
        traj = smooth_random_trajectory(seed, samples=401)
        out[f"random{seed}"] = (traj, solve(robot, traj))
    return out
