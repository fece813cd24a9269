"""The paint planner's errors (painting/errors.py, every one of them): a plan that does not
exist is in the solve family, as the kinematics' reach errors are, a value the planner cannot
use in the input family; one line, and a reach error carries the sample and pose that failed
(here, checked against the IK)."""
import numpy as np
import pytest

import pollard_pin.painting.errors as paint_errors
from pollard_pin.errors import InputError, PollardError, SolveError
from pollard_pin.kinematics.errors import KinematicsError, UnreachablePoseError
from pollard_pin.kinematics.ik import inverse_kinematics
from pollard_pin.painting.errors import JobKindError, PlanError, ReachError, ResolutionError


def test_family():
    assert issubclass(ReachError, PlanError) and issubclass(PlanError, SolveError)
    assert issubclass(UnreachablePoseError, SolveError)  # one family for a pose out of reach
    assert issubclass(PlanError, RuntimeError) and issubclass(PlanError, PollardError)
    assert not issubclass(PlanError, InputError)
    assert issubclass(ResolutionError, InputError) and issubclass(JobKindError, InputError)
    e = ReachError("out of reach", 7, np.zeros(6))
    assert (str(e), e.sample) == ("out of reach", 7) and e.pose.shape == (6,)


INPUT = {"JobError", "JobKindError", "MeshError", "MeshFileError", "CellError",
         "ResolutionError"}
SOLVE = {"PlanError", "ReachError", "BudgetError", "ClearanceError", "PlaceError",
         "LineSpeedError", "LineReachError", "LayoutSearchError", "ReportError"}


def test_every_paint_error_is_here_by_the_rule():
    """The module's docstring rule: a value the planner cannot use is an InputError, a valid
    job no program meets a SolveError (PlanError but for ReportError, a bug); every exception
    class of pollard_pin.painting is defined in painting/errors.py."""
    import importlib
    import inspect
    import pkgutil

    import pollard_pin.painting as painting

    classes = {n for n in paint_errors.__all__ if isinstance(getattr(paint_errors, n), type)}
    assert classes == INPUT | SOLVE
    assert set(paint_errors.__all__) - classes == {"kept", "made_again"}  # a memo's rule
    for name in INPUT:
        cls = getattr(paint_errors, name)
        assert issubclass(cls, InputError) and not issubclass(cls, SolveError), name
    for name in SOLVE:
        cls = getattr(paint_errors, name)
        assert issubclass(cls, SolveError) and not issubclass(cls, InputError), name
        assert issubclass(cls, PlanError) == (name != "ReportError"), name
    assert issubclass(paint_errors.MeshFileError, paint_errors.MeshError)
    for info in pkgutil.walk_packages(painting.__path__, "pollard_pin.painting."):
        module = importlib.import_module(info.name)
        for name, obj in vars(module).items():
            if inspect.isclass(obj) and issubclass(obj, BaseException):
                assert obj.__module__ == "pollard_pin.painting.errors" or not \
                    obj.__module__.startswith("pollard_pin.painting"), (info.name, name)
    # the constructors kept their fields
    e = paint_errors.LineSpeedError("too fast", True, "drift", 0.2)
    assert (str(e), e.too_fast, e.why, e.hint) == ("too fast", True, "drift", 0.2)
    causes = {3: "a cause"}
    e = paint_errors.LayoutSearchError("no cell", causes, 0.024)
    assert (str(e), e.causes, e.speed) == ("no cell", causes, 0.024) and e.causes is not causes
    # no cell found for a valid job: a plan that does not exist, not a [[robot]] table refused
    assert issubclass(paint_errors.LayoutSearchError, paint_errors.PlanError)
    assert not issubclass(paint_errors.LayoutSearchError, paint_errors.CellError)


def test_reach_error_names_the_sample_and_pose_the_ik_refuses(robot, plan, act):
    """motion() on poses of the plan, one moved 0.5 m further out (x): the error names that
    sample and that pose, one line, and the IK alone refuses the pose too."""
    from pollard_pin.painting.checks.motion import motion

    tr = plan.trajectory
    poses = tr.poses[:10].copy()
    poses[6, 0] += 0.5
    with pytest.raises(ReachError) as info:
        motion(robot, act, poses, tr.d_poses[:10], tr.dd_poses[:10])
    e = info.value
    assert "\n" not in str(e) and e.sample == 6
    assert np.array_equal(e.pose, poses[6])
    with pytest.raises(KinematicsError):
        inverse_kinematics(robot, poses[6:7], 0 * poses[6:7], 0 * poses[6:7], np.zeros(1))


def test_a_kept_refusal_is_made_again_the_same_without_its_frames():
    """errors.kept / made_again: the class, words and attributes of a refusal (a subclass
    with its own, LineSpeedError's side, why and hint) come back equal, as a new exception
    with no traceback; what the raising frame held is not kept (freed with the collector
    off)."""
    import gc
    import weakref

    from pollard_pin.painting.errors import LineSpeedError, kept, made_again

    class Held:
        pass

    def refuse():
        samples = Held()
        refuse.ref = weakref.ref(samples)
        raise LineSpeedError("drifts out of reach", too_fast=True, why="drifts", hint=0.01)

    gc.disable()
    try:
        try:
            refuse()
        except LineSpeedError as exc:
            memo = kept(exc)
        assert refuse.ref() is None  # the exception gone, the frame with it
    finally:
        gc.enable()
    again = made_again(memo)
    assert type(again) is LineSpeedError and again.__traceback__ is None
    assert (str(again), again.too_fast, again.why, again.hint) == (
        "drifts out of reach", True, "drifts", 0.01)
    assert made_again(memo) is not again
