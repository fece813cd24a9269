"""Figures and report section of a closed-loop simulation (``pollard-pin simulate``, docs/model.md
§18), from its table (:meth:`TrackingResult.columns` or the file read back with
:func:`pollard_pin.io.table.read_result`). Each plotted line carries its column's name as its
matplotlib ``gid``.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..dynamics.control import ControlError
from ..dynamics.tracking_result import tracking_summary
from ..names import ACTUATED
from .plots import COLOURS, LABELS, figure_maker, finish_axes, plot_line

SIMULATION_FIGURES = ("simulation_tracking", "simulation_torques", "simulation_path")
# a simulation with flexible drives (docs/model.md §28) adds the springs' deflections
FLEXIBLE_FIGURES = ("simulation_deflection",)
REQUIRED = ("t", "x", "y", "z", "desired_x", "desired_y", "desired_z", "tip_position_error",
            "tip_orientation_error", "closure_residual")


def check_simulation_columns(cols: dict, source: str = "the table") -> None:
    """Raise :class:`ControlError` (one line) unless ``cols`` is a simulation table."""
    missing = [c for c in REQUIRED if c not in cols]
    taus = [c for c in cols if c.startswith("tau_")]
    if missing or not taus:
        raise ControlError(f"{source}: not a simulation table (written by pollard-pin "
                           f"simulate): missing column(s) {', '.join(missing or ['tau_*'])}")
    if len(cols["t"]) < 2:
        raise ControlError(f"{source}: a simulation table needs at least 2 rows")
    for name, col in cols.items():  # simulate never writes these: an edited or damaged table
        bad = ~np.isfinite(col)
        if bad.any():
            k = int(np.argmax(bad))
            raise ControlError(f"{source}: sample {k}, column {name!r}: {col[k]} is not finite")
    t = np.asarray(cols["t"])
    back = np.diff(t) <= 0
    if back.any():
        k = int(np.argmax(back)) + 1
        raise ControlError(f"{source}: sample {k}: time {float(t[k])!r} s does not follow "
                           f"{float(t[k - 1])!r} s (times must increase strictly)")


def simulation_summary(cols: dict, metadata: dict | None = None) -> dict:
    """Max and time-weighted RMS tool errors, peak |τ| per actuator, settings (JSON-ready):
    :func:`~pollard_pin.dynamics.tracking_result.tracking_summary` of the table."""
    check_simulation_columns(cols)
    meta = dict(metadata or {})
    summary = meta.pop("summary", {})
    t = np.asarray(cols["t"])
    return {"samples": int(len(t)), "duration": float(t[-1] - t[0]),
            **tracking_summary(t, cols["tip_position_error"], cols["tip_orientation_error"],
                               {c[4:]: cols[c] for c in cols if c.startswith("tau_")},
                               np.max(cols["closure_residual"]),
                               summary.get("saturation_time")),
            "settings": meta}


def simulation_markdown(sim: dict) -> list[str]:
    """The report's "Closed-loop simulation" section (markdown lines)."""
    s = sim["settings"]
    keys = ("controller", "wn", "zeta", "dt", "control_period", "payload", "mass_error",
            "torque_limit", "noise")
    lines = ["", "## Closed-loop simulation (docs/model.md §18)", "",
             f"{sim['samples']} samples over {sim['duration']:.4g} s; "
             + ", ".join(f"{k} {s[k]}" for k in keys if k in s) + ".", "",
             "| quantity | max | RMS |", "|---|---:|---:|",
             f"| tool-tip position error [m] | {sim['max_tip_position_error']:.3e} | "
             f"{sim['rms_tip_position_error']:.3e} |",
             f"| tool orientation error [rad] | {sim['max_tip_orientation_error']:.3e} | "
             f"{sim['rms_tip_orientation_error']:.3e} |", "",
             "| actuator | peak \\|τ\\| [N·m] |", "|---|---:|"]
    lines += [f"| `{n}` | {p:.4g} |" for n, p in sim["peak_torque"].items()]
    sat = sim.get("saturation_time")
    lines += ["", f"Max closure residual {sim['max_closure_residual']:.2e} m"
              + ("" if sat is None else f"; torque saturated during {sat:.4g} s") + "."]
    return lines


def _tracking_figure(plt, cols, name):
    t = cols["t"]
    fig, axes = plt.subplots(3, 1, figsize=(8, 7), sharex=True)
    plot_line(axes[0], t, 1e3 * np.asarray(cols["tip_position_error"]), "tip_position_error",
          color="tab:blue", label="|p − p_d|")
    finish_axes(axes[0], "[mm]", "Tool-tip position error")
    plot_line(axes[1], t, np.degrees(cols["tip_orientation_error"]), "tip_orientation_error",
          color="tab:orange", label="|log(R R_dᵀ)|")
    finish_axes(axes[1], "[deg]", "Tool orientation error")
    plot_line(axes[2], t, cols["closure_residual"], "closure_residual", color="tab:green",
          label="max |p_A − p_B|")
    axes[2].set_yscale("log")
    finish_axes(axes[2], "[m]", "Loop-closure residual")
    axes[-1].set_xlabel("t [s]")
    fig.suptitle(f"Closed-loop tracking ({name})")
    fig.tight_layout()
    return fig


def _torque_figure(plt, cols, name):
    t = cols["t"]
    fig, axes = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for i, n in enumerate(ACTUATED):
        col = f"tau_{n}"
        if col in cols:
            ax = axes[0] if i < 3 else axes[1]
            plot_line(ax, t, cols[col], col, color=COLOURS[i], label=LABELS.get(n, n))
    finish_axes(axes[0], "τ [N·m]", "Applied actuator torques, base actuators")
    finish_axes(axes[1], "τ [N·m]", "Applied actuator torques, wrist actuators")
    axes[-1].set_xlabel("t [s]")
    fig.suptitle(f"Applied torques ({name})")
    fig.tight_layout()
    return fig


def _path_figure(plt, cols, name):
    fig, axes = plt.subplots(3, 1, figsize=(8, 7), sharex=True)
    t = cols["t"]
    for ax, c in zip(axes, "xyz"):
        plot_line(ax, t, cols[f"desired_{c}"], f"desired_{c}", color="tab:gray", lw=2.5,
              alpha=0.6, label="desired")
        plot_line(ax, t, cols[c], c, color="tab:purple", lw=1, label="actual")
        finish_axes(ax, f"{c} [m]")
    axes[-1].set_xlabel("t [s]")
    fig.suptitle(f"Desired and actual tool path ({name})")
    fig.tight_layout()
    return fig


def _deflection_figure(plt, cols, name):
    t = cols["t"]
    fig, axes = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for i, n in enumerate(ACTUATED):
        col = f"deflection_{n}"
        if col in cols:
            ax = axes[0] if i < 3 else axes[1]
            plot_line(ax, t, 1e3 * np.asarray(cols[col]), col, color=COLOURS[i],
                      label=LABELS.get(n, n))
    finish_axes(axes[0], "φ − q [mrad]", "Drive spring deflections, base actuators")
    finish_axes(axes[1], "φ − q [mrad]", "Drive spring deflections, wrist actuators")
    axes[-1].set_xlabel("t [s]")
    fig.suptitle(f"Flexible drives ({name})")
    fig.tight_layout()
    return fig


def simulation_figures(cols: dict, name: str = "simulation") -> dict:
    """``{name: Figure}``: tracking errors and residual, applied torques, desired vs actual
    tool path; with flexible drives (``deflection_*`` columns) the springs' deflections."""
    check_simulation_columns(cols)
    plt = figure_maker()
    figs = {"simulation_tracking": _tracking_figure(plt, cols, name),
            "simulation_torques": _torque_figure(plt, cols, name),
            "simulation_path": _path_figure(plt, cols, name)}
    if any(c.startswith("deflection_") for c in cols):
        figs["simulation_deflection"] = _deflection_figure(plt, cols, name)
    return figs


def write_simulation_figures(cols: dict, out_dir, dpi: int = 100,
                             name: str = "simulation") -> list[Path]:
    """Write :func:`simulation_figures` as ``out_dir/<name>.png``; returns the paths."""
    from ..io.atomic import atomic_open, make_folder

    figs = simulation_figures(cols, name)
    out = make_folder(out_dir)
    plt = figure_maker()
    paths = []
    try:
        for key, fig in figs.items():
            path = out / f"{key}.png"
            with atomic_open(path, binary=True) as f:
                fig.savefig(f, dpi=dpi, format="png")
            paths.append(path)
    finally:
        for fig in figs.values():
            plt.close(fig)
    return paths
