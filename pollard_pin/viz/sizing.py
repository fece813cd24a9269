"""Motor and gearbox sizing of one trajectory: the table of ``pollard-pin size``, its JSON, and
the torque–speed figure (docs/model.md §19).

Per actuator, on the given trajectory and on the time-optimal traversal of the same path:
peak and RMS motor torque and peak motor speed, each with its ratio to the rating (≤ 1
passes). Besides: the shortest uniformly time-scaled duration, the time-optimal duration
(TOPP-RA under the peak-torque and speed limits, rest to rest), and where the time-optimal
cycle spends its time (which limit binds, time-weighted).
"""
from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..dynamics.actuators import (Actuators, MotorLoad, PathDynamics, TimeOptimal,
                                  UniformScaling, motor_load, motor_load_of, path_dynamics,
                                  time_optimal, trapezoid_weights, uniform_min_duration)
from ..io.retime import retimed_trajectory
from ..io.trajectory import Trajectory

ACTIVE = 0.98  # a limit "binds" at a sample when used to within 2 %
CHECKS = (  # report key, MotorLoad attribute, ratio key, heading, unit
    ("peak_motor_torque", "peak_torque", "peak_torque", "peak |τm|", "N·m"),
    ("rms_motor_torque", "rms_torque", "rms_torque", "RMS τm", "N·m"),
    ("peak_motor_speed", "peak_speed", "speed", "peak |ωm|", "rad/s"),
)
RATING = {"peak_torque": "peak", "rms_torque": "continuous", "speed": "max speed"}


@dataclass(frozen=True)
class Sizing:
    """Everything ``size`` computes; ``report`` is the JSON-ready summary."""

    report: dict
    actuators: Actuators
    given: MotorLoad
    optimal: MotorLoad
    uniform: UniformScaling
    timing: TimeOptimal
    path: PathDynamics
    retimed: Trajectory


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
    w = trapezoid_weights(load.t)
    best = use.argmax(axis=1)
    bound = use.max(axis=1) >= active
    shares = {lab: float(w[bound & (best == i)].sum()) for i, lab in enumerate(labels)}
    shares = {k: v for k, v in shares.items() if v > 0}
    shares["switching"] = float(w[~bound].sum())
    return dict(sorted(shares.items(), key=lambda kv: -kv[1]))


def actuator_sizing(robot, result, act: Actuators) -> Sizing:
    """Size the motors of ``act`` on the pipeline result ``result`` (IK and dynamics)."""
    ik, traj = result.ik, result.trajectory
    given = motor_load_of(robot, act, ik, result.dynamics)
    path = path_dynamics(robot, ik)
    uniform = uniform_min_duration(act, path)
    timing = time_optimal(act, path)
    optimal = motor_load(act, timing.t, *timing.joint_motion(path))
    checks, opt = _checks(given), _checks(optimal, "time_optimal_")
    shares = binding_shares(optimal)
    per = {}
    for j, n in enumerate(act.names):
        per[n] = {"gear_ratio": act.units[j].gear_ratio, **checks[n], **opt[n],
                  "time_optimal_torque_limited_share": shares.get(f"{n} peak_torque", 0.0),
                  "time_optimal_speed_limited_share": shares.get(f"{n} speed", 0.0)}
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
        "time_optimal_duration": timing.duration,
        "time_optimal_binding_shares": shares,
        "time_optimal_start_end": "rest to rest",
    }
    return Sizing(report, act, given, optimal, uniform, timing, path,
                  retimed_trajectory(traj, timing))


def to_json(rep: dict) -> str:
    return json.dumps(rep, indent=2, ensure_ascii=False)


def _table(rep: dict, prefix: str) -> list[str]:
    head = " | ".join(f"{h} [{u}] | ÷ {RATING[r]}" for _, _, r, h, u in CHECKS)
    lines = ["| actuator | N | " + head.replace("|τm|", "\\|τm\\|").replace("|ωm|", "\\|ωm\\|")
             + " |", "|---|---:|" + "---:|" * (2 * len(CHECKS))]
    for n, row in rep["actuators"].items():
        cells = [f"{row[prefix + k]:.4g} | {row[prefix + k + '_ratio']:.3f}"
                 for k, _, _, _, _ in CHECKS]
        lines.append(f"| `{n}` | {row['gear_ratio']:g} | " + " | ".join(cells) + " |")
    return lines


def to_markdown(rep: dict) -> str:
    tr = rep["trajectory"]
    ub = rep["uniform_binding"]
    verdict = "within every rating" if rep["given_within_ratings"] else "**over a rating**"
    lines = [f"# Motor and gearbox sizing: {tr['name']} trajectory", "",
             f"{tr['samples']} samples over {tr['duration']:.4g} s; actuators from "
             f"{rep['actuator_file']}. Motor side: τm = τ/N + Jm·N·q̈ + b·N·q̇ + c·sign(q̇), "
             "ωm = N·q̇ (docs/model.md §19).", "",
             f"## Given trajectory: {verdict}", "", *_table(rep, ""), "",
             "## Fastest cycle along the same path", "",
             f"* uniform time scaling: **{rep['uniform_min_duration']:.4g} s** (every limit "
             f"holds at this duration and any longer; binding: `{ub['actuator']}` "
             f"{ub['limit']}; each limit alone: "
             + ", ".join(f"{k.replace('_', ' ')} {v:.4g} s"
                         for k, v in rep["uniform_min_duration_by_limit"].items()) + ")",
             f"* time-optimal (TOPP-RA, peak torque and speed, rest to rest): "
             f"**{rep['time_optimal_duration']:.4g} s**", "", *_table(rep, "time_optimal_"),
             "", "Where the time-optimal cycle spends its time (binding limit, share of the "
             "duration):", ""]
    for label, share in rep["time_optimal_binding_shares"].items():
        what = ("switching between limits (no limit within 2 %)" if label == "switching"
                else f"`{label.split()[0]}` {label.split()[1].replace('_', ' ')}")
        lines.append(f"* {what}: {100 * share:.1f} %")
    lines += ["", "RMS = sqrt(∫τm² dt / T), trapezoid rule over the samples. The time-optimal "
              "cycle ignores the RMS limit; its ratio says whether the motor can repeat it "
              "without overheating."]
    return "\n".join(lines) + "\n"


def torque_speed_figure(sizing: Sizing):
    """Each motor's operating points (ωm, τm) for the given and the time-optimal trajectory,
    with its rating envelope: |τm| ≤ peak and |ωm| ≤ max speed (solid), ±continuous
    (dashed). Line gids: ``given_<actuator>``, ``time_optimal_<actuator>``,
    ``envelope_<actuator>``."""
    from .plots import figure_maker

    plt = figure_maker()
    act = sizing.actuators
    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5), constrained_layout=True)
    for j, (ax, name) in enumerate(zip(axes.ravel(), act.names)):
        u = act.units[j]
        w, p, c = u.max_speed, u.peak_torque, u.continuous_torque
        (env,) = ax.plot([-w, w, w, -w, -w], [-p, -p, p, p, -p], color="k", lw=1.2,
                         label="peak, max speed")
        env.set_gid(f"envelope_{name}")
        for sign in (1, -1):
            ax.axhline(sign * c, color="k", lw=0.8, ls="--",
                       label="continuous (RMS)" if sign > 0 else None)
        for load, label, colour in ((sizing.given, "given", "tab:blue"),
                                    (sizing.optimal, "time_optimal", "tab:orange")):
            (ln,) = ax.plot(load.speed[:, j], load.torque[:, j], ".", ms=2, color=colour,
                            label=f"{label.replace('_', '-')} "
                                  f"({load.t[-1] - load.t[0]:.3g} s)")
            ln.set_gid(f"{label}_{name}")
        ax.set_title(f"{name} (N = {u.gear_ratio:g})", fontsize=10)
        ax.set_xlabel("motor speed ωm [rad/s]")
        ax.set_ylabel("motor torque τm [N·m]")
        ax.grid(True, alpha=0.3)
    handles, labels = axes.ravel()[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=4, markerscale=4,
               fontsize=9)
    fig.suptitle(f"Motor operating points, {sizing.report['trajectory']['name']} trajectory")
    return fig


def write_torque_speed(sizing: Sizing, out_dir, dpi: int = 100) -> Path:
    """Write :func:`torque_speed_figure` as ``out_dir/torque_speed.png``."""
    from ..io.atomic import make_folder
    from .plots import save_png

    return save_png(torque_speed_figure(sizing), make_folder(out_dir) / "torque_speed.png", dpi)


__all__ = ["Sizing", "actuator_sizing", "binding_shares", "to_json", "to_markdown",
           "torque_speed_figure", "write_torque_speed"]
