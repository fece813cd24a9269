"""The kinematics layer (docs/model.md §7, §11, §12).

``tree`` (forward recursions over the model tree: placements, velocities, accelerations;
compiled back-end ``kernels``) · ``closure`` (loop closure by Newton, forward kinematics) ·
``ik`` (constrained IK along a trajectory: ``ik_batch`` stacked over samples, ``ik_newton``
sample by sample, ``ik_common`` their shared inputs and result) · ``singularity``
(conditioning and margins) · ``errors``. The closed form lives in :mod:`pollard_pin.analytic`."""
from .capsules import link_capsules
from .closure import forward_kinematics, solve_closure, tool_pose
from .errors import (
    BranchFlipError,
    ClosureError,
    ClosureSingularError,
    JointLimitError,
    KinematicsError,
    KinematicsInputError,
    SingularityError,
    UnreachablePoseError,
)
from .ik import IkOptions, IKResult, inverse_kinematics
from .margins import MarginError, Margins

__all__ = ["inverse_kinematics", "IKResult", "IkOptions", "forward_kinematics", "solve_closure",
           "tool_pose", "Margins", "MarginError", "link_capsules", "KinematicsError",
           "KinematicsInputError", "ClosureError", "ClosureSingularError", "UnreachablePoseError",
           "SingularityError", "BranchFlipError", "JointLimitError"]
