"""Task-space curves about the home pose shared by the closed-form and Euler–Lagrange tests:
(t, poses, rates, accelerations) at any times."""
import importlib.util
from pathlib import Path

import numpy as np

from pollard_pin.paths.curves import sinusoid_curve, thesis_curve


def painting_trajectory(p, n=2001, duration=20.0, t=None):
    """(t, poses, rates, accelerations) of docs/model.md §9 curve; ``t`` may be any times."""
    t = np.linspace(0.0, duration, n) if t is None else np.asarray(t, dtype=float)
    return (t, *thesis_curve(t, duration, p.home_pose))


def sinusoid_trajectory(p, n=401, duration=4.0, t=None):
    """All six task coordinates moving about home (sinusoid_curve defaults)."""
    t = np.linspace(0.0, duration, n) if t is None else np.asarray(t, dtype=float)
    return (t, *sinusoid_curve(t, p.home_pose))


TRAJECTORIES = [painting_trajectory, sinusoid_trajectory]
T_PROBE = np.array([0.37, 1.9, 3.3, 7.1, 12.6, 19.4])  # inside both trajectories' useful spans


def thesis_head(seconds: float, step: float = 0.01):
    """The first ``seconds`` of the thesis trajectory (20 s), sampled every ``step``."""
    from pollard_pin.paths.curves import thesis_trajectory
    from pollard_pin.paths.trajectory import Trajectory

    full = thesis_trajectory(samples=int(round(20.0 / step)) + 1)
    n = int(round(seconds / step)) + 1
    return Trajectory(full.t[:n], full.poses[:n], full.d_poses[:n], full.dd_poses[:n],
                      name="thesis head")


def figure_eight():
    """examples/make_trajectory.py's figure_eight (the example CSV's own curve)."""
    path = Path(__file__).resolve().parents[1] / "examples" / "make_trajectory.py"
    spec = importlib.util.spec_from_file_location("make_trajectory", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.figure_eight

