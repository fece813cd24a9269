"""Special tool poses shared by the kinematics tests, from the closed form's own frames."""
import numpy as np

from pollard_pin.analytic import closed_form as T
from pollard_pin.analytic import taskspace as ts


def wrist_singular_pose(params):
    """Home wrist centre, tool axis along the platform arm: θ1716 = 0 exactly."""
    f = {}
    T._solve(params, np.asarray(params.home_pose, dtype=float)[None], frames=f)
    Rp, P15 = f["platform"][0][0], f["wrist1"][1][0]
    return np.concatenate([P15 + params.x1918 * Rp[:, 0], ts.angles_from_rotation(Rp)])


def path_to_wrist_singularity(params, reach: float, samples: int, duration: float):
    """(t, poses, pose rates) of a straight pose path at constant rate from the home pose
    towards :func:`wrist_singular_pose`: the fraction s ∈ [0, reach] of the way (reach > 1
    goes through it, at t = duration / reach)."""
    home = np.asarray(params.home_pose, dtype=float)
    step = wrist_singular_pose(params) - home
    s = np.linspace(0.0, reach, samples)
    return s / reach * duration, home + np.outer(s, step), np.tile(step * reach / duration,
                                                                   (samples, 1))
