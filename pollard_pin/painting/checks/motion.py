"""Reach and motors along candidate tool motions: the rules of ``run`` (closed-form IK on the
configured branches, wrist and singularity margins) plus the joint limits of the parameter
file, and the motor model of docs/model.md §19 (docs/model.md §21)."""
from __future__ import annotations

import re
from dataclasses import dataclass, field, fields, replace
from functools import cached_property

import numpy as np

from ...analytic.taskspace import MAX_ABS_TASK
from ...dynamics.motors import Actuators, motor_speed, motor_torque
from ...kinematics.errors import KinematicsError
from ...kinematics.limits import check_joint_limits
from ...kinematics.margins import Margins
from ..errors import PlanError, ReachError
from ..progress import bar


@dataclass(frozen=True)
class Motion:
    """Joint motion and motor load of a batch of tool poses (not necessarily one path)."""

    solved: object  # IKResult of the distinct samples (a wait's once: :func:`reach`)
    tau: np.ndarray  # (N, 6) actuator torques
    torque: np.ndarray  # (N, 6) motor torques τm (§19)
    torque_ratio: np.ndarray  # (N, 6) |τm| / peak torque, with breakaway ±c at rest
    speed_ratio: np.ndarray  # (N, 6) |ωm| / max speed
    wait: int = 0  # samples 0..wait are the same (solved once)
    poses: np.ndarray | None = field(default=None, repr=False)

    @cached_property
    def ik(self):
        """The IKResult of every sample, made when asked (a long wait's (N, 6, 12)
        Jacobians are hundreds of MB the checks never read)."""
        return _spread(self.solved, self.wait, self.poses)

    @property
    def utilisation(self) -> np.ndarray:
        return np.maximum(self.torque_ratio, self.speed_ratio)


LEADING_RUN = 16  # identical first samples (a wait) at least this many are solved once


def _leading_run(*arrays) -> int:
    """m: samples 0..m of every array given (rows) are identical (0: none to spare)."""
    m = None
    for a in arrays:
        if a is None:
            continue
        a = np.asarray(a)
        if not (np.abs(a[0]) <= MAX_ABS_TASK).all():
            return 0  # an input error names its first sample: the IK sees them all
        same = (a == a[0]).all(axis=1)
        k = len(a) - 1 if same.all() else int(np.argmin(same)) - 1
        m = k if m is None else min(m, k)
    return m or 0


def reach(robot, poses, d_poses=None, dd_poses=None, *, margins: Margins | None = None):
    """The reach check alone (no dynamics, where the motors are not the question): IK of the
    tool poses (N, 6) under ``run``'s rules and ``margins`` (default ``run``'s), and the joint
    limits. Returns the IKResult; raises :class:`ReachError` (its ``sample``) where a pose
    fails. A path's wait (its first LEADING_RUN or more samples the same) is solved once:
    the same result, the same sample named."""
    ik, m = _solved(robot, poses, d_poses, dd_poses, margins, at_rest=True)
    return _spread(ik, m, poses)


def _solved(robot, poses, d_poses, dd_poses, margins, at_rest: bool = False):
    """(IKResult of samples m.. only, m): :func:`reach` with its wait, samples 0..m the
    same, solved at sample m alone. ``at_rest`` (:func:`reach`) without rates and
    accelerations (the clearance's and the compliance's, which read the positions): the
    poses solved at rest, their rates K⁻¹·0 without the drifts
    (:func:`.kinematics.ik_batch.inverse_kinematics_batch`), the same samples refused."""
    from ...kinematics.ik import IkOptions, inverse_kinematics, inverse_kinematics_batch
    from ...model.build import check_robot

    n = len(poses)
    m = _leading_run(poses, d_poses, dd_poses)
    m = m if m >= LEADING_RUN else 0
    tail = [None if a is None else np.asarray(a)[m:] for a in (poses, d_poses, dd_poses)]
    t = np.arange(m, n, dtype=float)
    try:
        if at_rest and d_poses is None and dd_poses is None:
            check_robot(robot)
            ik = inverse_kinematics_batch(robot, tail[0], None, None, t,
                                          IkOptions(margins=margins), at_rest=True)
        else:
            ik = inverse_kinematics(robot, *tail, t, options=IkOptions(margins=margins))
        check_joint_limits(robot, ik.q)
    except KinematicsError as exc:
        if exc.sample is not None and exc.sample > 0:
            exc = exc.shifted(m)  # its samples (a flip names two) on the whole path's count
        k = 0 if exc.sample is None else int(exc.sample)
        detail = re.sub(r"; \d+ samples fail in all", "", exc.detail)  # samples of a batch
        raise ReachError(detail, k, np.asarray(poses)[k]) from None
    return ik, m


def _spread(ik, m: int, poses):
    """The IKResult of every sample from :func:`_solved`'s (the wait's row repeated)."""
    if not m:
        return ik
    n = m + len(ik)
    at = np.maximum(np.arange(n) - m, 0)
    ik = replace(ik, **{f.name: getattr(ik, f.name)[at] for f in fields(ik)
                        if isinstance(getattr(ik, f.name), np.ndarray)})
    ik.t = np.arange(n, dtype=float)
    ik.poses = np.asarray(poses, dtype=float)
    return ik


def motion(robot, act: Actuators, poses, d_poses, dd_poses, *,
           margins: Margins | None = None) -> Motion:
    """IK, inverse dynamics and motor load of the tool poses (N, 6) with their rates and
    accelerations. Raises :class:`ReachError` (its ``sample``) where ``run`` would fail or a
    joint leaves its limits (:func:`reach`). A wait is solved once (:func:`reach`)."""
    from ...dynamics.inverse import inverse_dynamics

    ik, m = _solved(robot, poses, d_poses, dd_poses, margins)
    at = np.maximum(np.arange(m + len(ik)) - m, 0) if m else slice(None)
    tau = inverse_dynamics(robot, ik, energies=False).tau
    ia = robot.actuated_v
    v, a = ik.v[:, ia], ik.a[:, ia]
    tm = motor_torque(act, tau, v, a)  # at rest |τm| already carries the breakaway c
    # row by row, so the distinct samples' figures spread over the wait are every sample's
    return Motion(ik, tau[at], tm[at], (np.abs(tm) / act.column("peak_torque"))[at],
                  (np.abs(motor_speed(act, v)) / act.column("max_speed"))[at], m,
                  None if not m else np.asarray(poses))


GUESS_HALVINGS = 4  # the planners' ramps' and turnarounds' first guess halved at most 4× for reach


def fastest(evaluate, guess, target: float, iterations: int = 16, max_doublings: int = 12,
            halvings: int = 0):
    """Smallest durations τ (one per piece, vectorised bisection) with
    ``evaluate(τ)`` (per-piece peak utilisation) ≤ ``target``; ``guess`` (P,) starts the
    bracket, doubled until feasible. Utilisation must fall as τ grows (acceleration-bound
    pieces); raises :class:`PlanError` if a piece is not feasible at any tried duration.
    A guess whose ``evaluate`` raises :class:`ReachError` (pieces that run on out of reach:
    shorter ones travel less) is halved, at most ``halvings`` times; out of reach while
    doubling for the motors is raised (docs/model.md §21)."""
    hi = np.array(guess, dtype=float)
    for left in range(halvings, -1, -1):
        try:
            util = evaluate(hi)
            break
        except ReachError:
            if not left:
                raise
            hi = hi / 2
    lo = np.zeros_like(hi)
    for i in range(max_doublings):
        ok = (util if i == 0 else evaluate(hi)) <= target
        if ok.all():
            break
        lo = np.where(ok, lo, hi)
        hi = np.where(ok, hi, 2 * hi)
    else:
        raise PlanError(f"no turnaround or ramp of up to {hi.max():.3g} s keeps every motor "
                        f"within {100 * target:.0f} % of its ratings: the pass speed itself "
                        "is too much for them")
    for _ in bar(range(iterations), "planning: ramps and turnarounds", unit="step"):
        mid = 0.5 * (lo + hi)
        ok = evaluate(mid) <= target
        lo, hi = np.where(ok, lo, mid), np.where(ok, mid, hi)
    return hi


