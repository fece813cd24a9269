"""Constrained inverse kinematics along a trajectory (docs/model.md §7, §11): positions,
velocities and accelerations of all tree joints from the tool pose, batched
(:mod:`.ik_batch`) or per sample (:mod:`.ik_newton`)."""
from __future__ import annotations

from ..model.build import Robot
from .errors import KinematicsInputError
from .ik_batch import inverse_kinematics_batch
from .ik_common import BATCH_CHUNK, IK_TOL, IkOptions, IKResult, ik_options
from .ik_newton import inverse_kinematics_newton
from .margins import Margins


def inverse_kinematics(robot: Robot, poses, d_poses=None, dd_poses=None, t=None,
                       q_start=None, options: IkOptions | None = None, *,
                       progress=None) -> IKResult:
    """Constrained IK with Pinocchio: positions, velocities, accelerations of all 12 tree joints.

    ``options`` (:class:`IkOptions`, default its defaults): ``method="batch"`` (the default
    without ``q_start``) stacks the work over samples (see :func:`inverse_kinematics_batch`);
    ``method="newton"`` (the default with ``q_start``) solves sample by sample (see
    :func:`inverse_kinematics_newton`). Both give the same result to round-off. Its
    ``margins`` (:class:`~.margins.Margins`) say how close to a singularity a sample may come
    (docs/model.md §12); ``tol`` is Newton's. ``progress(done, total)`` is called as samples
    are solved. Invalid arguments (empty or non-finite poses, times that do
    not increase, a bad tolerance) raise :class:`KinematicsInputError`, a ValueError.
    """
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
