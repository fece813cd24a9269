"""The time-optimal cycle of a path with waits (a line job's: the conveyor brings the part,
the strokes, maybe more waits): each moving segment solved on its own, rest to rest, the
waits left out, so that time and memory grow with the moving samples, not with the wait's
(docs/model.md §19)."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..checks import instance
from ..model.build import check_robot
from ..paths.trajectory import Trajectory
from .motors import Actuators
from .path import PathDynamics
from .timeopt import Options, TimeOptimal, time_optimal_segment


def moving_segments(traj) -> list[tuple[int, int]]:
    """The samples ``start:stop`` of each moving segment of ``traj``, in order. A sample with
    zero rates and accelerations stands; an interval between two standing samples at the same
    pose is a wait (the quintic Hermite between them is that pose). A segment runs from a
    standing sample (or the start) through moving intervals to the next standing sample (or
    the end). One pose throughout: the whole path, one segment."""
    d, dd, poses = traj.d_poses, traj.dd_poses, traj.poses
    still = ~(np.any(d, axis=1) | np.any(dd, axis=1))
    wait = still[:-1] & still[1:] & np.all(poses[:-1] == poses[1:], axis=1)
    moving = ~wait
    if not moving.any():
        return [(0, len(traj.t))]
    k = np.arange(len(moving))
    before = np.concatenate([[False], moving[:-1]])
    after = np.concatenate([moving[1:], [False]])
    starts = k[moving & (~before | still[:-1])]
    ends = k[moving & (~after | still[1:])]
    return [(int(a), int(b) + 2) for a, b in zip(starts, ends)]


def time_optimal_path(robot, act: Actuators, traj, options: Options | None = None
                      ) -> TimeOptimal:
    """The time-optimal traversal of the path of ``traj`` under the motors' peak torque and
    speed, by TOPP-RA (docs/model.md §19): each of its moving segments solved on its own,
    rest to rest between them (``options.s_dot_start`` and ``s_dot_end`` at the path's own
    ends), the waits taking no time. The limits hold between the samples too (checked on the
    exact path, ``traj.curve`` or the spline through the samples).

    Parameters
    ----------
    robot : Robot
        The model.
    act : Actuators
        The motors (:func:`~pollard_pin.load_actuators`).
    traj : Trajectory
        The path (``t``, ``poses``, rates, accelerations and optional ``curve``).
    options : pollard_pin.dynamics.timeopt.Options or None, optional
        Check points per interval, the accepted utilisation between them, the end rates.

    Returns
    -------
    TimeOptimal
        At the grid ``s``: times ``t`` [s], path rate ``s_dot`` and acceleration ``s_ddot``;
        ``between`` the worst use of a limit found between the samples.

    Raises
    ------
    ActuatorError
        No traversal meets the ratings (e.g. a motor too weak to hold the path at rest).
    KinematicsError
        The path cannot be solved between its samples.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> act = pp.load_actuators()  # the package's ratings
    >>> robot = pp.load()
    >>> first_2s = pp.thesis_trajectory(samples=401).window(0, 41)  # the curve's first 2 s
    >>> timing = pp.time_optimal_path(robot, act, first_2s)
    >>> round(float(timing.t[-1]), 2), bool(timing.between <= 1.001)
    (0.83, True)
    """
    check_robot(robot)
    instance(act, "act", Actuators, "Actuators (pollard_pin.load_actuators())")
    instance(traj, "traj", Trajectory, "a Trajectory")
    options = instance(options, "options", Options, "pollard_pin.dynamics.timeopt.Options or None",
                       none=True) or Options()
    spans = moving_segments(traj)
    n = len(traj.t)
    parts = []
    for start, stop in spans:
        ends = replace(options, s_dot_start=options.s_dot_start if start == 0 else 0.0,
                       s_dot_end=options.s_dot_end if stop == n else 0.0)
        parts.append(time_optimal_segment(robot, act, traj.window(start, stop), ends))
    return parts[0] if len(parts) == 1 else join(parts)


def join(parts) -> TimeOptimal:
    """The traversals ``parts`` one after the other, each starting where the last stopped:
    times offset by the durations before, s = k + the k-th part's s (a junction's rest sample
    twice, at one time and one s, with both sides of s̈)."""
    offsets = np.cumsum([0.0] + [p.t[-1] - p.t[0] for p in parts[:-1]])
    worst = int(np.argmax([p.between for p in parts]))
    paths = [p.path for p in parts]
    path = PathDynamics(**{key: np.concatenate([getattr(q, key) for q in paths])
                           for key in ("a", "b", "c", "q_s", "q_ss")},
                        s=np.concatenate([k + p.s for k, p in enumerate(parts)]),
                        duration=float(sum(q.duration for q in paths)))
    return TimeOptimal(
        s=path.s, t=np.concatenate([p.t - p.t[0] + off for p, off in zip(parts, offsets)]),
        s_dot=np.concatenate([p.s_dot for p in parts]),
        s_ddot=np.concatenate([p.s_ddot for p in parts]),
        iterations=sum(p.iterations for p in parts),
        per_interval=max(p.per_interval for p in parts), between=parts[worst].between,
        between_at=worst + parts[worst].between_at,
        tightened=sum(p.tightened for p in parts), path=path, parts=tuple(parts))


__all__ = ["join", "moving_segments", "time_optimal_path"]
