"""Constrained inverse kinematics along a trajectory (docs/model.md §7, §11): positions,
velocities and accelerations of all tree joints from the tool pose, batched
(:mod:`.ik_batch`) or per sample (:mod:`.ik_newton`)."""
from __future__ import annotations

from ..model.build import Robot
from .errors import KinematicsInputError
from .ik_batch import BATCH_CHUNK, inverse_kinematics_batch
from .ik_common import IK_TOL, IKResult
from .ik_newton import inverse_kinematics_newton
from .margins import MarginError, Margins


def inverse_kinematics(robot: Robot, poses, d_poses=None, dd_poses=None, t=None,
                       q_start=None, *, method: str | None = None,
                       margins: Margins | None = None, tol: float = IK_TOL, progress=None,
                       **options) -> IKResult:
    """Constrained IK with Pinocchio: positions, velocities, accelerations of all 12 tree joints.

    ``method="batch"`` (the default without ``q_start``) stacks the work over samples (see
    :func:`inverse_kinematics_batch`); ``method="newton"`` (the default with ``q_start``)
    solves sample by sample (see :func:`inverse_kinematics_newton`). Both give the same result
    to round-off. ``margins`` (:class:`~.margins.Margins`, default its defaults) say how close
    to a singularity a sample may come (docs/model.md §12); ``tol`` is Newton's; ``options``:
    ``max_iter`` (Newton) or ``chunk``, ``timings`` (batch). Invalid arguments (empty or
    non-finite poses, times that do not increase, a bad tolerance) raise
    :class:`KinematicsInputError`, a ValueError; a bad margin cannot be made
    (:class:`~.margins.MarginError`), and anything but a ``Margins`` is refused with it.
    """
    old = sorted({"wrist_margin", "singularity_margin"} & set(options))
    if old:  # the keywords of before Margins: say what replaced them
        raise MarginError(f"{', '.join(old)}: pass margins=Margins(wrist=…, singularity=…)")
    method = method or ("newton" if q_start is not None else "batch")
    if method == "newton":
        return inverse_kinematics_newton(robot, poses, d_poses, dd_poses, t, q_start,
                                         margins=margins, tol=tol, progress=progress,
                                         **options)
    if method != "batch":
        raise KinematicsInputError(f"method must be 'batch' or 'newton', got {method!r}")
    if q_start is not None:
        raise KinematicsInputError("q_start applies to method='newton' only")
    return inverse_kinematics_batch(robot, poses, d_poses, dd_poses, t, margins=margins,
                                    tol=tol, progress=progress, **options)


__all__ = ["inverse_kinematics", "IKResult", "IK_TOL", "BATCH_CHUNK", "Margins",
           "inverse_kinematics_batch", "inverse_kinematics_newton"]
