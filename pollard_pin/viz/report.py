"""Actuator sizing report and engine cross-check for one trajectory.

**Sizing** (from the same arrays as the ``run`` CSV; t is the sample time, integrals by the
trapezoid rule over the samples):

* peak torque ``max |τ|`` [N·m]; RMS torque ``sqrt(∫τ² dt / T)`` [N·m], T the duration;
* peak speed ``max |q̇|`` [rad/s]; peak power ``max |τ·q̇|`` [W];
* energy ``∫|τ·q̇| dt`` [J] (all mechanical energy through the actuator, motoring and braking)
  and net work ``∫τ·q̇ dt`` [J] (the CSV's final ``work_*``);
* per spherical joint: peak ``|f_i|`` [N] and the time it occurs, and RMS ``|f_i|``;
* bearings (docs/model.md §17): per tree joint, peak axial and radial force, peak bending
  moment and the ISO 281 equivalent (time-weighted cubic mean) radial and axial loads; per
  ball joint, peak and equivalent ``|f_i|``.

**Cross-checks**: the same trajectory through

* the thesis' method (``pollard_pin.crosscheck.euler_lagrange``: closed-form IK, task-space
Euler–Lagrange,
  numpy only): joint positions, velocities, accelerations and actuator torques;
* MuJoCo (``pollard_pin.crosscheck.mujoco``: the URDF in MuJoCo, ``mj_inverse`` plus the connect
  constraints): actuator torques and closure forces. If MuJoCo is not installed the report
  says so and skips it.

Agreement is reported as the largest absolute difference and that difference relative to the
largest magnitude of the reference quantity.
"""
from __future__ import annotations

import math
from dataclasses import replace

from ..crosscheck.compare import cross_check_mujoco, cross_check_thesis, result_loads
from ..io.json_text import finite_json
from ..run.stats import duty_figures

SIZING_FIELDS = (  # key, heading, unit
    ("peak_torque", "peak |τ|", "N·m"),
    ("rms_torque", "RMS τ", "N·m"),
    ("peak_speed", "peak |q̇|", "rad/s"),
    ("peak_power", "peak |P|", "W"),
    ("energy", "energy ∫|P|dt", "J"),
    ("net_work", "net work ∫P dt", "J"),
)


BEARING_FIELDS = (  # key, heading (docs/model.md §17); torque in N·m, forces in N
    ("peak_axial", "peak axial [N]"), ("peak_radial", "peak radial [N]"),
    ("peak_bending", "peak bending [N·m]"), ("peak_torque", "peak axis torque [N·m]"),
    ("equivalent_radial", "equiv. radial [N]"), ("equivalent_axial", "equiv. axial [N]"),
)


def sizing_report(robot, result, cross_check: bool = True) -> dict:
    """The whole ``pollard-pin report`` for a run as a JSON-ready dict.

    Parameters
    ----------
    robot : Robot
        The model.
    result : RunResult
        :func:`~pollard_pin.run_pipeline`'s result, with its dynamics.
    cross_check : bool, optional
        Also compare the torques with the thesis' Euler–Lagrange method and MuJoCo (default
        True; MuJoCo's column says so when it is not installed).

    Returns
    -------
    dict
        ``trajectory``, ``model``, ``units``, ``sizing`` (per actuator: peak and RMS torque
        [N·m], peak speed [rad/s], peak power [W], energy and net work [J]; per spherical
        joint: peak force [N]), ``bearings`` (peak and equivalent joint loads) and, with
        ``cross_check``, ``cross_check`` with the ``thesis`` and ``mujoco`` agreement.

    Raises
    ------
    ValueError
        The result has no dynamics.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> from pollard_pin.viz import sizing_report
    >>> robot = pp.load()
    >>> result = pp.run_pipeline(robot, pp.thesis_trajectory(samples=201))
    >>> report = sizing_report(robot, result, cross_check=False)
    >>> round(report["sizing"]["actuators"]["theta21"]["peak_torque"], 2)    # N·m
    1.21
    """
    if result.dynamics is None:
        raise ValueError("the report needs the dynamics: run_pipeline(..., dynamics=True)")
    ik, traj = result.ik, result.trajectory
    loads = result_loads(robot, result)  # once, for the bearings and both cross-checks
    out = {
        "trajectory": {"name": traj.name, "samples": len(ik), "t0": float(ik.t[0]),
                       "duration": float(ik.t[-1] - ik.t[0]), "derivatives": traj.derivatives},
        "model": {"parameters": str(robot.params.source),
                  "total_mass": float(robot.params.total_mass)},
        "units": {k: u for k, _, u in SIZING_FIELDS} | {"peak_force": "N", "rms_force": "N",
                                                        "peak_time": "s"},
        "sizing": duty_figures(result.columns(), robot.actuated),
        "bearings": loads.bearing_table(),
    }
    out["units"] |= {k: ("N·m" if k in ("peak_bending", "peak_torque") else "N")
                     for k, _ in BEARING_FIELDS} | {"peak_force": "N", "equivalent_force": "N"}
    if cross_check:
        result = replace(result, loads=loads)
        out["cross_check"] = {"thesis": cross_check_thesis(robot, result),
                              "mujoco": cross_check_mujoco(robot, result)}
    return out


report = sizing_report


def to_json(rep: dict) -> str:
    return finite_json(rep, "the sizing report", indent=2, ensure_ascii=False)


def _agree_row(label, a, unit):
    rel = a.get("relative")
    rel_s = f"{rel:.2e}" if rel is not None and math.isfinite(rel) else "–"
    peak = a.get("reference_peak")
    return (f"| {label} | {a['max_abs_diff']:.3e} {unit} | "
            f"{'–' if peak is None else f'{peak:.4g} {unit}'} | {rel_s} |")


def to_markdown(rep: dict) -> str:
    tr, sz = rep["trajectory"], rep["sizing"]
    lines = [f"# Actuator sizing report: {tr['name']} trajectory", "",
             f"{tr['samples']} samples over {tr['duration']:.4g} s (derivatives: "
             f"{tr['derivatives']}); model parameters {rep['model']['parameters']}, total "
             f"mass {rep['model']['total_mass']:.4g} kg.", "", "## Actuators", "",
             "| actuator | " + " | ".join(f"{h} [{u}]".replace("|", "\\|")
                                         for _, h, u in SIZING_FIELDS) + " |",
             "|---|" + "---:|" * len(SIZING_FIELDS)]
    for n, a in sz["actuators"].items():
        lines.append(f"| `{n}` | " + " | ".join(f"{a[k]:.4g}" for k, _, _ in SIZING_FIELDS)
                     + " |")
    lines += ["", "## Spherical joints (closure forces)", "",
              "| joint | peak ‖f‖ [N] | at t [s] | RMS ‖f‖ [N] |", "|---|---:|---:|---:|"]
    for n, j in sz["spherical_joints"].items():
        lines.append(f"| leg {n[-1]} ball joint | {j['peak_force']:.4g} | "
                     f"{j['peak_time']:.4g} | {j['rms_force']:.4g} |")
    lines += ["", "RMS = sqrt(∫x² dt / T); energy = ∫|τ·q̇| dt; net work = ∫τ·q̇ dt "
              "(trapezoid rule over the samples)."]
    if "bearings" in rep:
        b = rep["bearings"]
        lines += ["", "## Bearings and pins (joint loads, docs/model.md §17)", "",
                  "| joint | " + " | ".join(h for _, h in BEARING_FIELDS) + " |",
                  "|---|" + "---:|" * len(BEARING_FIELDS)]
        for n, row in b["joints"].items():
            lines.append(f"| {n} | " + " | ".join(f"{row[k]:.4g}" for k, _ in BEARING_FIELDS)
                         + " |")
        lines += ["", "| ball joint | peak ‖f‖ [N] | equiv. ‖f‖ [N] |", "|---|---:|---:|"]
        lines += [f"| {n} | {r['peak_force']:.4g} | {r['equivalent_force']:.4g} |"
                  for n, r in b["spherical"].items()]
        lines += ["", "Axial: along the joint axis; radial, bending: perpendicular to it. "
                      "Equivalent load (ISO 281, fluctuating load): (∫|F|³ dt / T)^(1/3). "
                      "The two joints of a U-joint cross carry the same wrench."]
    cc = rep.get("cross_check")
    if cc:
        th, mj = cc["thesis"], cc["mujoco"]
        lines += ["", "## Cross-checks (Pinocchio vs reference)", "",
                  "| quantity | max abs difference | reference peak \\|component\\| "
                  "| relative |",
                  "|---|---:|---:|---:|",
                  f"| joint positions, thesis closed-form IK | "
                  f"{th['joint_position_rad']['max_abs_diff']:.3e} rad | – | – |",
                  _agree_row("joint velocities, thesis IK", th["joint_velocity"], "rad/s"),
                  _agree_row("joint accelerations, thesis IK", th["joint_acceleration"],
                             "rad/s²")]
        if "torque" in th:
            lines.append(_agree_row("actuator torques, thesis Euler–Lagrange", th["torque"],
                                    "N·m"))
        if "joint_force" in th:
            lines += [_agree_row("joint forces, free bodies (closed form)", th["joint_force"],
                                 "N"),
                      _agree_row("joint moments, free bodies (closed form)",
                                 th["joint_moment"], "N·m")]
        if mj.get("available"):
            lines += [_agree_row("actuator torques, MuJoCo", mj["torque"], "N·m"),
                      _agree_row("closure forces (x, y, z components), MuJoCo",
                                 mj["closure_force"], "N"),
                      *([_agree_row("joint forces, MuJoCo cfrc_int", mj["joint_force"], "N"),
                         _agree_row("joint moments, MuJoCo cfrc_int", mj["joint_moment"],
                                    "N·m")] if "joint_force" in mj else []),
                      "", "Peaks and differences here are over single components (largest "
                          "|f_x|, |f_y|, |f_z|); the spherical-joint table above "
                          "gives the peak magnitude ‖f‖.",
                      "", f"MuJoCo's own closure residual at the Pinocchio states: "
                          f"{mj['mujoco_closure_residual_m']:.2e} m."]
        else:
            lines += ["", f"MuJoCo cross-check skipped: {mj['reason']}."]
    if "simulation" in rep:  # pollard-pin report --simulation, docs/model.md §18
        from .simulation import simulation_markdown

        lines += simulation_markdown(rep["simulation"])
    return "\n".join(lines) + "\n"
