"""The paint planner's errors, one home, one line each.

The rule: a value the planner cannot use (a key of a job file, a mesh, a film spacing, a job
of another kind, a robot table) is an :class:`pollard_pin.errors.InputError`; a valid job that
no program meets (out of reach, too fast for the motors, too close to the part, over a
budget) is a :class:`pollard_pin.errors.SolveError`, a :class:`PlanError` here, as a pose out
of the kinematics' reach is (:class:`pollard_pin.kinematics.errors.UnreachablePoseError`).
"""
from __future__ import annotations

from ..errors import InputError, SolveError

# --- a value the planner cannot use ------------------------------------------------------


class JobError(InputError):
    """A paint job breaks a rule (one line: the file, the key, the value, the rule)."""


class JobKindError(InputError):
    """A job of a kind the planner does not handle (one line naming the kind)."""


class MeshError(InputError):
    """A part's mesh cannot be used: one line naming the file, the value and the rule."""


class MeshFileError(MeshError):
    """A mesh file whose content contradicts itself (indices, counts): one line."""


class CellError(InputError):
    """A ``[[robot]]`` table breaks a rule, or the robots cannot stand where they are put."""


class ResolutionError(InputError):
    """A film point spacing the film cannot be computed at (not > 0, over σ, or over the
    budget of film points)."""


# --- a valid job that no program meets -----------------------------------------------------


class PlanError(SolveError):
    """No paint program meets the job: one line saying why, where, and what would fit."""


class ReachError(PlanError):
    """A tool pose the path needs is out of reach: ``sample`` indexes the poses checked,
    ``pose`` (6,) is that pose."""

    def __init__(self, message: str, sample: int, pose=None):
        super().__init__(message)
        self.sample, self.pose = sample, pose


class BudgetError(PlanError):
    """A plan over its stated budget (samples, passes): one line with what it would need."""


class ClearanceError(PlanError):
    """The gun's body comes closer to the part than the clearance (one line: where)."""


class PlaceError(PlanError):
    """No placement puts the part's gun poses within reach: one line saying by how much."""


class LineReachError(PlanError):
    """Passes out of one robot's reach at any place on the line (too tall or too long for the
    reach): a cell of more robots may paint the part."""


class LayoutSearchError(PlanError):
    """No proposed cell of the robot counts tried paints the part (``--robots auto``):
    ``causes`` maps each count to why it failed
    (:class:`pollard_pin.painting.causes.Cause`: the constraint that binds, its figure),
    ``levered`` each count's cause with the cell's levers, where they were tried, ``speed``
    the line speed [m/s] tried (None: any, ``max_line_speed``). The job is valid
    and no cell found paints it, a :class:`PlanError` whichever way each count failed (its
    proposal a :class:`CellError`, or its plan a :class:`PlanError`)."""

    def __init__(self, message: str, causes: dict, speed: float | None = None,
                 levered: dict | None = None):
        super().__init__(message)
        self.causes, self.speed, self.levered = dict(causes), speed, dict(levered or {})


class LineSpeedError(PlanError):
    """No program paints the part at this line speed (its drift does not fit the reach, or
    the motors cannot follow): ``too_fast`` says which side, ``why`` in a few words,
    ``hint`` a speed [m/s] worth trying next (None: no guess)."""

    def __init__(self, message: str, too_fast: bool, why: str = "",
                 hint: float | None = None):
        super().__init__(message)
        self.too_fast = too_fast
        self.why = why
        self.hint = hint


def kept(exc: Exception) -> tuple:
    """A refusal as a memo keeps it: its class, words and attributes, not the exception (its
    traceback would hold the frames of the plan refused: with the memo held by the frame
    raising it again, a cycle only the garbage collector frees, docs/model.md §26.5)."""
    return type(exc), exc.args, dict(vars(exc))


def made_again(refusal: tuple) -> Exception:
    """The refusal :func:`kept` kept, made anew to be raised (the same class, words and
    attributes; a traceback of its own)."""
    kind, args, attrs = refusal
    exc = kind.__new__(kind)
    exc.args = args
    vars(exc).update(attrs)
    return exc


class ReportError(SolveError):
    """A report number breaks an invariant the model guarantees (a lower bound over the cycle,
    a transfer efficiency over 100 %): a bug, refused rather than printed."""


__all__ = ["BudgetError", "CellError", "ClearanceError", "JobError", "JobKindError",
           "LayoutSearchError", "LineReachError", "LineSpeedError", "MeshError",
           "MeshFileError", "PlaceError", "PlanError", "ReachError", "ReportError",
           "ResolutionError", "kept", "made_again"]
