"""The kinematics' errors: each says where (sample, time, chain) and how far off (amount)."""
from __future__ import annotations


class ClosureError(RuntimeError):
    """The loops cannot be closed for the given actuator angles."""

    def __init__(self, message: str, leg: int | None = None, residual: float | None = None):
        super().__init__(message)
        self.leg = leg
        self.residual = residual


class KinematicsError(RuntimeError):
    """IK failed at a sample: ``chain``, ``sample``, ``time``, ``amount`` say where, how far."""

    def __init__(self, message: str, *, sample: int | None = None, time: float | None = None,
                 chain: str | None = None, amount: float | None = None):
        where = "" if sample is None else f"sample {sample}" + (
            "" if time is None else f" (t = {time:.6g} s)")
        super().__init__(f"{where}: {message}" if where else message)
        self.detail = message  # the message without the sample/time prefix
        self.sample, self.time, self.chain, self.amount = sample, time, chain, amount


class UnreachablePoseError(KinematicsError):
    """A chain cannot reach the requested tool pose."""


class SingularityError(KinematicsError):
    """The trajectory passes closer to a singularity than the configured margin."""


class BranchFlipError(KinematicsError):
    """The solution jumped to another assembly branch between consecutive samples."""
