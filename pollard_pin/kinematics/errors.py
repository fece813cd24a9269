"""The kinematics' errors: each says where (sample, time, chain) and how far off (amount)."""
from __future__ import annotations

import copy
import re

from ..errors import InputError, SolveError

_SAMPLE_WORDS = re.compile(r"\b(samples? )(\d+)(?:( and )(\d+))?")


class ClosureError(SolveError):
    """The loops cannot be closed for the given actuator angles: ``leg`` (1 or 2) the leg
    that falls short, ``residual`` [m] the closure residual reached."""

    def __init__(self, message: str, leg: int | None = None, residual: float | None = None):
        super().__init__(message)
        self.leg = leg
        self.residual = residual


class AtSample:
    """Where a kinematics error happened, for the solve's errors (:class:`KinematicsError`) and
    the input's (:class:`KinematicsInputError`) alike: ``sample`` (index), ``time`` [s],
    ``chain`` (``"chain 0"``, ``"leg 1"``, ``"leg 2"``, a joint, a margin or an input column)
    say where and ``amount`` how far off (in the unit of the rule broken); ``detail`` is the
    message without the sample prefix. Not an exception itself: each error class adds its
    family. :data:`SAMPLE_ERRORS` is what a caller that reports where catches."""

    def __init__(self, message: str, *, sample: int | None = None, time: float | None = None,
                 chain: str | None = None, amount: float | None = None):
        where = "" if sample is None else f"sample {sample}" + (
            "" if time is None else f" (t = {time:.6g} s)")
        super().__init__(f"{where}: {message}" if where else message)
        self.detail = message  # the message without the sample/time prefix
        self.sample, self.time, self.chain, self.amount = sample, time, chain, amount

    def shifted(self, offset: int):
        """The same error for a window of a longer trajectory that starts at sample
        ``offset``: every sample number (attribute and message) counts from the full
        trajectory's start. Used by the streaming run (pollard_pin.run)."""
        if not offset:
            return self

        def move(m):
            out = m.group(1) + str(int(m.group(2)) + offset)
            return out + (m.group(3) + str(int(m.group(4)) + offset) if m.group(3) else "")

        other = copy.copy(self)
        # Its own attributes: with tblib installed (dask.distributed does), copy.copy of an
        # exception shares the original's __dict__.
        other.__dict__ = dict(vars(self))
        other.detail = _SAMPLE_WORDS.sub(move, self.detail)
        other.sample = None if self.sample is None else self.sample + offset
        where = "" if other.sample is None else f"sample {other.sample}" + (
            "" if self.time is None else f" (t = {self.time:.6g} s)")
        other.args = (f"{where}: {other.detail}" if where else other.detail,)
        return other


class KinematicsError(AtSample, SolveError):
    """IK failed at a sample of a valid trajectory (where: :class:`AtSample`): a pose out of
    reach, a singularity, a joint limit, a branch flip."""


class KinematicsInputError(AtSample, InputError):
    """An argument is invalid before any kinematics runs: empty or mis-shaped arrays, a
    non-finite or absurd pose component (``chain`` names the column, e.g. ``"d_psi"``),
    times that do not increase, a tolerance that is not > 0 (a bad margin is a
    :class:`~.margins.MarginError` when the :class:`~.margins.Margins` is made). An
    :class:`~pollard_pin.errors.InputError` (so a :class:`ValueError`) that says where as a
    :class:`KinematicsError` does (:class:`AtSample`), not a KinematicsError: nothing was
    solved."""


class JointLimitError(KinematicsError):
    """A joint leaves its limits (the ``[limits]`` of the parameter file): ``chain`` names the
    joint, ``amount`` [rad] how far outside."""


class UnreachablePoseError(KinematicsError):
    """A chain cannot reach the requested tool pose."""


class SingularityError(KinematicsError):
    """The trajectory passes closer to a singularity than the configured margin, or a linear
    system of the pipeline is singular at round-off level (docs/model.md §12). ``sigma`` is the
    measure that failed (smallest singular value, or |sin| of the angle) when there is one."""

    def __init__(self, message: str, *, sigma: float | None = None, **where):
        super().__init__(message, **where)
        self.sigma = sigma


class ClosureSingularError(SingularityError, ClosureError):
    """The loops cannot be closed because the passive-joint constraint Jacobian is singular
    (a :class:`ClosureError` and a :class:`SingularityError`)."""

    def __init__(self, message: str, *, leg: int | None = None,
                 residual: float | None = None, **kw):
        super().__init__(message, **kw)
        self.leg, self.residual = leg, residual


class BranchFlipError(KinematicsError):
    """The solution changed assembly branch between consecutive samples: a branch-defining sign
    (docs/model.md §7: the branch term of a circle equation, cos θ54, sin θ1716, cos θ76_i)
    changed, i.e. the motion passed through the boundary between two assembly modes."""


# Every kinematics error that says where: what a caller that reports or renumbers the sample
# catches (the solve's and the input's).
SAMPLE_ERRORS = (KinematicsError, KinematicsInputError)
