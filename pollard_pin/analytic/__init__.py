"""The analytic layer, numpy only (docs/model.md §7): ``closed_form`` (the thesis' IK with exact
jet derivatives), ``jet`` (forward-mode Taylor jets), ``taskspace`` (pose conventions).
Its modules import numpy and one another only, never Pinocchio (tests/analytic/test_closed_form.py
loads them with Pinocchio hidden)."""
from .closed_form import SingularPoseError, UnreachableError, WristSingularError, position_ik
from .taskspace import TaskInputError

__all__ = ["position_ik", "UnreachableError", "WristSingularError", "SingularPoseError",
           "TaskInputError"]
