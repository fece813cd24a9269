"""Constrained inverse kinematics along a trajectory (docs/model.md §7, §11): positions,
velocities and accelerations of all tree joints from the tool pose, batched
(:mod:`.ik_batch`) or per sample (:mod:`.ik_newton`)."""
from __future__ import annotations

from ..checks import callback
from ..model.build import Robot, check_robot
from .errors import KinematicsInputError
from .ik_batch import inverse_kinematics_batch
from .ik_common import BATCH_CHUNK, IK_TOL, IkOptions, IKResult, ik_options
from .ik_newton import inverse_kinematics_newton
from .margins import Margins


def inverse_kinematics(robot: Robot, poses, d_poses=None, dd_poses=None, t=None,
                       q_start=None, options: IkOptions | None = None, *,
                       progress=None) -> IKResult:
    """Constrained IK with Pinocchio: positions, velocities, accelerations of all 12 tree joints.

    ``options`` (:class:`~pollard_pin.IkOptions`, default its defaults): ``method="batch"``
    (the default without ``q_start``) stacks the work over samples; ``method="newton"`` (the
    default with ``q_start``) solves sample by sample. Both give the same result to
    round-off. Its ``margins`` (:class:`~pollard_pin.Margins`) say how close to a singularity
    a sample may come (docs/model.md §12); ``tol`` is Newton's.

    Parameters
    ----------
    robot : Robot
        The model (:func:`pollard_pin.load`).
    poses : ndarray
        Tool poses (N, 6): x, y, z [m] of the tip and its ZYZ angles ψ, θ, φ [rad], world
        frame (a :class:`~pollard_pin.Trajectory`'s ``poses``).
    d_poses, dd_poses : ndarray or None, optional
        Their time derivatives (N, 6) [m/s, rad/s] and [m/s², rad/s²]; None: zeros (a
        static pose per sample).
    t : ndarray or None, optional
        Times (N,) [s], strictly increasing; None: 0, 1, 2, ...
    q_start : ndarray or None, optional
        A configuration (12,) [rad] near the first sample's (Newton method only); None: the
        assembly branches of the parameter file.
    options : IkOptions or None, optional
        Method, margins, tolerance and iterations (None: the defaults).
    progress : Callable or None, optional
        ``progress(done, total)`` is called as samples are solved.

    Returns
    -------
    IKResult
        Joint positions, velocities and accelerations, the spherical joints' angles, and the
        residuals and singularity margins at each sample.

    Raises
    ------
    UnreachablePoseError
        A chain cannot reach a sample's pose (the message names the sample, time and chain).
    SingularityError
        A sample comes closer to a singularity than the margins allow.
    BranchFlipError
        The solution changes assembly branch between two samples.
    pollard_pin.kinematics.errors.KinematicsInputError
        Invalid arguments (empty or non-finite poses, times that do not increase, a bad
        tolerance); also a :class:`ValueError`.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> robot = pp.load()
    >>> traj = pp.thesis_trajectory(duration=20.0, samples=101)
    >>> ik = pp.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    >>> ik.q.shape, bool(ik.closure_residual.max() < 1e-12)
    ((101, 12), True)
    >>> pp.inverse_kinematics(robot, [[2.0, 0.0, 0.16, 0.0, 0.0, 0.0]])
    Traceback (most recent call last):
    ...
    pollard_pin.kinematics.errors.UnreachablePoseError: sample 0 ...
    """
    check_robot(robot)
    callback(progress, "progress", error=KinematicsInputError)
    options = ik_options(options)
    method = options.method or ("newton" if q_start is not None else "batch")
    if method == "newton":
        return inverse_kinematics_newton(robot, poses, d_poses, dd_poses, t, q_start, options,
                                         progress=progress)
    if q_start is not None:
        raise KinematicsInputError("q_start applies to method='newton' only")
    return inverse_kinematics_batch(robot, poses, d_poses, dd_poses, t, options,
                                    progress=progress)


__all__ = ["inverse_kinematics", "IKResult", "IkOptions", "IK_TOL", "BATCH_CHUNK", "Margins",
           "inverse_kinematics_batch", "inverse_kinematics_newton"]
