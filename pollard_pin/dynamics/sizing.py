"""Motor and gearbox sizing of one trajectory: everything ``pollard-pin size`` reports
(docs/model.md §19; the table and figure: :mod:`pollard_pin.viz.torque_speed`).

Per actuator, on the given trajectory and on the time-optimal traversal of the same path:
peak and RMS motor torque and peak motor speed, each with its ratio to the rating (≤ 1
passes). Besides: the shortest uniformly time-scaled duration, the time-optimal duration
(TOPP-RA under the peak-torque and speed limits, rest to rest, checked between the samples;
a paint program's passes kept as planned, :mod:`.passes`),
and where the time-optimal cycle spends its time (which limit binds, time-weighted).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..checks import instance, shorten
from ..errors import InputError
from ..kinematics.errors import SAMPLE_ERRORS
from ..model.build import check_robot
from .averages import mean_weights
from .cycle import time_optimal_path
from .motors import (
    ActuatorError,
    Actuators,
    MotorLoad,
    UniformScaling,
    motor_load,
    motor_load_of,
    uniform_min_duration,
)
from .passes import sprays, time_optimal_program
from .path import PathDynamics, path_dynamics
from .timeopt import TimeOptimal

ACTIVE = 0.98  # a limit "binds" at a sample when used to within 2 %
MIN_TRAVEL = 1e-9  # rad: a path moving no actuator further stands still (IK noise: 1e-14)
CHECKS = (  # report key, MotorLoad attribute, ratio key, heading, unit
    ("peak_motor_torque", "peak_torque", "peak_torque", "peak |τm|", "N·m"),
    ("rms_motor_torque", "rms_torque", "rms_torque", "RMS τm", "N·m"),
    ("peak_motor_speed", "peak_speed", "speed", "peak |ωm|", "rad/s"),
)


@dataclass(frozen=True)
class Sizing:
    """Everything ``size`` computes; ``report`` is the JSON-ready summary. Without a
    time-optimal traversal (TOPP-RA failed: ``report['time_optimal_error']``), ``optimal``
    and ``timing`` are None."""

    report: dict
    actuators: Actuators
    given: MotorLoad
    optimal: MotorLoad | None
    uniform: UniformScaling
    timing: TimeOptimal | None
    path: PathDynamics


def _checks(load: MotorLoad, prefix: str = "") -> dict[str, dict[str, float]]:
    ratios = load.ratios()
    out = {n: {} for n in load.actuators.names}
    for key, attr, rkey, _, _ in CHECKS:
        values = getattr(load, attr)
        for j, n in enumerate(load.actuators.names):
            out[n][prefix + key] = float(values[j])
            out[n][prefix + key + "_ratio"] = float(ratios[rkey][j])
    return out


def binding_shares(load: MotorLoad, active: float = ACTIVE) -> dict[str, float]:
    """Share of the time in which each limit binds (the most-used one, if used to within
    ``active``), keyed ``<actuator> <peak_torque|speed>``, plus ``switching`` (no limit
    within ``active``: the samples where the discretised profile turns from one limit to
    another). Time-weighted by the trapezoid rule; the shares sum to 1."""
    a = load.actuators
    use = np.concatenate([np.abs(load.torque) / a.column("peak_torque"),
                          np.abs(load.speed) / a.column("max_speed")], axis=1)
    labels = [f"{n} peak_torque" for n in a.names] + [f"{n} speed" for n in a.names]
    w = mean_weights(load.t)
    best = use.argmax(axis=1)
    bound = use.max(axis=1) >= active
    shares = {lab: float(w[bound & (best == i)].sum()) for i, lab in enumerate(labels)}
    shares = {k: v for k, v in shares.items() if v > 0}
    shares["switching"] = float(w[~bound].sum())
    return dict(sorted(shares.items(), key=lambda kv: -kv[1]))


def actuator_sizing(robot, result, act: Actuators) -> Sizing:
    """Size the motors of ``act`` on the pipeline result ``result`` (IK, dynamics and the
    trajectory, whose ``curve``, if any, is the exact path between its samples). A failing
    time-optimal solve leaves the rest of the report and says why in
    ``report['time_optimal_error']`` (docs/model.md §19).

    Parameters
    ----------
    robot : Robot
        The model.
    result : RunResult
        :func:`~pollard_pin.run_pipeline`'s result, with its dynamics.
    act : Actuators
        The motors and gearboxes (:func:`~pollard_pin.load_actuators`).

    Returns
    -------
    pollard_pin.dynamics.sizing.Sizing
        ``report`` (what ``pollard-pin size --format json`` prints: per motor the peak and RMS
        torque and peak speed and their ratios to the ratings; ``uniform_min_duration`` [s],
        the shortest uniformly time-scaled cycle; ``time_optimal_duration`` [s], TOPP-RA's),
        the motor loads of the given and of the time-optimal motion, and the traversal.

    Raises
    ------
    ActuatorError
        The path does not move the actuators (no cycle to find).

    Examples
    --------
    >>> import pollard_pin as pp
    >>> act = pp.load_actuators()  # the package's ratings
    >>> robot = pp.load()
    >>> first_2s = pp.thesis_trajectory(samples=401).window(0, 41)  # the curve's first 2 s
    >>> report = pp.actuator_sizing(robot, pp.run_pipeline(robot, first_2s), act).report
    >>> report["given_within_ratings"], round(report["time_optimal_duration"], 2)
    (True, 0.83)
    """
    check_robot(robot)
    instance(act, "act", Actuators, "Actuators (pollard_pin.load_actuators())")
    if not all(hasattr(result, a) for a in ("ik", "trajectory", "dynamics")):
        raise InputError(f"result = {shorten(result)}: expected a run's result "
                         f"(pollard_pin.run_pipeline), got {type(result).__name__}")
    ik, traj = result.ik, result.trajectory
    given = motor_load_of(robot, act, ik, result.dynamics)
    path = path_dynamics(robot, ik)
    travel = float(np.abs(path.q_s).max())  # bounds each actuator's travel ∫|q_s| ds
    if not travel > MIN_TRAVEL:  # no cycle to find: every duration would do
        raise ActuatorError(f"the path does not move the actuators (each travels at most "
                            f"{travel:.2g} rad over its {len(ik.t)} samples)")
    uniform = uniform_min_duration(act, path)
    film = None
    try:
        if sprays(traj):  # a paint program: its passes keep their timing (docs/model.md §19)
            timing, film = time_optimal_program(robot, act, traj)
        else:
            timing = time_optimal_path(robot, act, traj)
    except (ActuatorError, *SAMPLE_ERRORS) as exc:  # e.g. between the samples
        timing, error = None, str(exc)
    checks = _checks(given)
    per = {n: {"gear_ratio": act.units[j].gear_ratio, **checks[n]}
           for j, n in enumerate(act.names)}
    t = ik.t
    report = {
        "trajectory": {"name": traj.name, "samples": len(t), "duration": float(t[-1] - t[0]),
                       "derivatives": traj.derivatives},
        "actuator_file": act.source,
        "given_within_ratings": bool(all(r <= 1.0 for row in checks.values()
                                         for k, r in row.items() if k.endswith("_ratio"))),
        "actuators": per,
        "uniform_min_duration": uniform.duration,
        "uniform_binding": {"actuator": uniform.actuator, "limit": uniform.limit},
        "uniform_min_duration_by_limit": uniform.by_limit,
        "time_optimal_start_end": "rest to rest",
    }
    if sprays(traj):
        report["time_optimal_start_end"] = "rest to rest, the passes (gun on) as planned"
        report["time_optimal_film"] = film
    if timing is None:
        report.update(time_optimal_duration=None, time_optimal_error=error)
        return Sizing(report, act, given, None, uniform, None, path)
    optimal = motor_load(act, timing.t, *timing.joint_motion(
        path if timing.path is None else timing.path))
    shares = binding_shares(optimal)
    opt = _checks(optimal, "time_optimal_")
    for n in act.names:
        per[n].update(opt[n],
                      time_optimal_torque_limited_share=shares.get(f"{n} peak_torque", 0.0),
                      time_optimal_speed_limited_share=shares.get(f"{n} speed", 0.0))
    report.update(time_optimal_duration=timing.duration,
                  time_optimal_binding_shares=shares,
                  time_optimal_between_samples={
                      "worst_utilisation": timing.between, "at_s": timing.between_at,
                      "check_points_per_interval": timing.per_interval,
                      "intervals_tightened": timing.tightened})
    return Sizing(report, act, given, optimal, uniform, timing, path)


__all__ = ["ACTIVE", "CHECKS", "Sizing", "actuator_sizing", "binding_shares"]
