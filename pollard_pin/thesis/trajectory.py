"""Default painting trajectory (thesis appendix B, spec §9) with exact derivatives."""
from __future__ import annotations

import numpy as np


def painting_trajectory(params, n: int = 2001, duration: float = 20.0, t=None):
    """(t, poses, d_poses, dd_poses): x = −0.001u², y = u, z = 100 sin(0.3u) [mm], u linear
    from −60π to 60π over ``duration`` s, added to the home tip pose; angles held at home.
    ``t`` overrides the n-point uniform time grid (it may leave [0, duration])."""
    t = np.linspace(0.0, duration, n) if t is None else np.asarray(t, dtype=float)
    n = t.size
    ud = 120.0 * np.pi / duration
    u = -60.0 * np.pi + ud * t
    mm = 1e-3
    pos = np.zeros((n, 6))
    vel = np.zeros((n, 6))
    acc = np.zeros((n, 6))
    pos[:, 0], vel[:, 0], acc[:, 0] = -0.001 * u * u, -0.002 * u * ud, -0.002 * ud * ud
    pos[:, 1], vel[:, 1] = u, ud
    pos[:, 2] = 100.0 * np.sin(0.3 * u)
    vel[:, 2] = 30.0 * np.cos(0.3 * u) * ud
    acc[:, 2] = -9.0 * np.sin(0.3 * u) * ud * ud
    pos[:, :3] *= mm
    vel[:, :3] *= mm
    acc[:, :3] *= mm
    pos += np.asarray(params.home_pose, dtype=float)
    return t, pos, vel, acc


def sinusoid_trajectory(params, n: int = 401, duration: float = 4.0,
                        amplitude=(0.04, 0.05, 0.04, 0.25, 0.3, 0.35),
                        freq=(0.31, 0.23, 0.41, 0.37, 0.29, 0.19),
                        phase=(0.3, 1.1, 2.0, 0.7, 2.5, 1.6), t=None):
    """Smooth motion of all six task coordinates about home: a_k sin(2π f_k t + φ_k) [m, rad]."""
    t = (np.linspace(0.0, duration, n) if t is None else np.asarray(t, dtype=float))[:, None]
    a, w, ph = np.asarray(amplitude), 2 * np.pi * np.asarray(freq), np.asarray(phase)
    arg = w * t + ph
    pos = np.asarray(params.home_pose, dtype=float) + a * np.sin(arg)
    return t[:, 0], pos, a * w * np.cos(arg), -a * w * w * np.sin(arg)
