"""Figures like the thesis' chapter 4 (positions, velocities, accelerations; torque, power and
work of the actuators) plus closure forces, singularity margins and the tool path.

Every curve is a column of the ``run`` CSV (:meth:`RunResult.columns`): each plotted line
carries that column's name as its matplotlib ``gid`` (``|f1|`` for a force magnitude), and
angles are drawn in degrees where the axis label says ``[deg…]``. Matplotlib's non-interactive
``Agg`` backend is used, so no display is needed.

With the joint loads (``run_pipeline(..., loads=True)``, docs/model.md §17) a further figure,
``joint_loads``, draws the axial and radial force and the bending moment of every tree joint,
derived from the ``F_<joint>_*``/``M_<joint>_*`` columns (gid ``axial_<joint>`` etc.).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..checks import instance
from ..errors import InputError
from ..names import ACTUATED, CHAIN_JOINTS, SPHERICAL
from ..run.pipeline import RunResult

# Figure name → file name (without .png), in the order they are written.
FIGURES = ("chain0_joints", "wrist_joints", "leg1_joints", "leg2_joints", "spherical_joints",
           "actuators", "closure_forces", "conditioning", "tool_path")

LABELS = {  # thesis symbols
    "theta21": "θ21", "theta43": "θ43", "theta54": "θ54", "theta1615": "θ1615",
    "theta1716": "θ1716", "theta1817": "θ1817",
    **{f"{n}_{i}": f"{s}{i}" for i in (1, 2) for n, s in
       (("theta21", "θ21_"), ("theta65", "θ65_"), ("theta76", "θ76_"), ("theta98", "θ98_"),
        ("theta109", "θ109_"), ("theta1110", "θ1110_"))},
}
LOAD_FIGURES = ("joint_loads",)  # written when the result has its joint loads
BASE, WRIST = ACTUATED[:3], ACTUATED[3:]
COLOURS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown")


class _Figures:
    """pyplot's ``figure``/``subplots``/``close`` without pyplot: each figure is a
    :class:`matplotlib.figure.Figure` on its own Agg canvas, so drawing here switches no global
    backend and registers no figure (nothing to close; ``close`` is a no-op)."""

    @staticmethod
    def figure(**kw):
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure

        fig = Figure(**kw)
        FigureCanvasAgg(fig)
        return fig

    def subplots(self, nrows=1, ncols=1, *, figsize=None, constrained_layout=False, **kw):
        fig = self.figure(figsize=figsize, constrained_layout=constrained_layout)
        return fig, fig.subplots(nrows, ncols, **kw)

    @staticmethod
    def close(fig) -> None:
        pass


def figure_maker() -> _Figures:
    """The figure factory every viz module draws with (see :class:`_Figures`)."""
    return _Figures()


def plot_line(ax, x, y, gid, **kw):
    (ln,) = ax.plot(x, y, **kw)
    ln.set_gid(gid)
    return ln


def finish_axes(ax, ylabel, title=None, legend=True):
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title, fontsize=10)
    ax.grid(True, alpha=0.3)
    if legend:
        ax.legend(fontsize=8, loc="upper right", ncol=3, framealpha=0.85)


def _joint_figure(plt, cols, joints, title, roles):
    """Three rows: position [deg], velocity [deg/s], acceleration [deg/s²]."""
    t = cols["t"]
    fig, axes = plt.subplots(3, 1, figsize=(8, 7.5), sharex=True)
    for row, (prefix, label, name) in enumerate(
            (("", "position [deg]", "Position"), ("d_", "velocity [deg/s]", "Velocity"),
             ("dd_", "acceleration [deg/s²]", "Acceleration"))):
        ax = axes[row]
        for j, n in enumerate(joints):
            plot_line(ax, t, np.degrees(cols[prefix + n]), prefix + n, color=COLOURS[j],
                  label=f"{LABELS[n]} ({roles[j]})")
        finish_axes(ax, label, f"{name}")
    axes[-1].set_xlabel("t [s]")
    fig.suptitle(title)
    fig.tight_layout()
    return fig


def _spherical_figure(plt, cols):
    t = cols["t"]
    fig, axes = plt.subplots(2, 2, figsize=(10, 6), sharex=True)
    for i in (1, 2):
        names = SPHERICAL[3 * (i - 1):3 * i]
        for row, (prefix, label) in enumerate((("", "angle [deg]"),
                                               ("d_", "rate [deg/s]"))):
            ax = axes[row, i - 1]
            for j, n in enumerate(names):
                plot_line(ax, t, np.degrees(cols[prefix + n]), prefix + n, color=COLOURS[j],
                      label=LABELS[n])
            kind = "angles" if row == 0 else "rates"
            finish_axes(ax, label, f"Leg {i} spherical joint (ZYZ), {kind}")
        axes[1, i - 1].set_xlabel("t [s]")
    fig.suptitle("Cut spherical joints: the legs' ball joints on the platform arm "
                 "(docs/model.md §4)")
    fig.tight_layout()
    return fig


def _actuator_figure(plt, cols):
    t = cols["t"]
    fig, axes = plt.subplots(3, 2, figsize=(11, 8), sharex=True)
    rows = (("tau_", "torque [N·m]", "Torque"), ("power_", "power [W]", "Power τ·q̇"),
            ("work_", "cumulative work [J]", "Work ∫τ·q̇ dt"))
    for c, (group, gname) in enumerate(((BASE, "base actuators"), (WRIST, "wrist actuators"))):
        for r, (prefix, label, name) in enumerate(rows):
            ax = axes[r, c]
            for j, n in enumerate(group):
                plot_line(ax, t, cols[prefix + n], prefix + n, color=COLOURS[3 * c + j],
                      label=LABELS[n])
            finish_axes(ax, label, f"{name}, {gname}")
        axes[-1, c].set_xlabel("t [s]")
    fig.suptitle("Actuators (docs/model.md §6): torque, power and work along the trajectory")
    fig.tight_layout()
    return fig


def _closure_figure(plt, cols):
    t = cols["t"]
    fig, axes = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for i in (1, 2):
        ax = axes[i - 1]
        comps = [cols[f"f{i}_{c}"] for c in "xyz"]
        for j, c in enumerate("xyz"):
            plot_line(ax, t, comps[j], f"f{i}_{c}", color=COLOURS[j], label=f"f{i},{c}")
        plot_line(ax, t, np.sqrt(sum(x * x for x in comps)), f"|f{i}|", color="k", lw=1.2,
              label=f"|f{i}|")
        finish_axes(ax, "force [N]", f"Leg {i} ball joint: force of the platform on link_{i} "
                                 "(world axes)")
    axes[-1].set_xlabel("t [s]")
    fig.suptitle("Closure (spherical-joint) reaction forces")
    fig.tight_layout()
    return fig


def _loads_figure(plt, loads, name):
    """One row per chain (docs/model.md §17): axial force, radial force, bending moment."""

    t = loads.t
    quantities = (("axial", loads.axial, "axial force [N]"),
                  ("radial", loads.radial, "radial force [N]"),
                  ("bending", loads.bending, "bending moment [N·m]"))
    fig, axes = plt.subplots(len(CHAIN_JOINTS), 3, figsize=(12, 10), sharex=True)
    for r, (chain, joints) in enumerate(CHAIN_JOINTS):
        for c, (key, arr, ylabel) in enumerate(quantities):
            ax = axes[r, c]
            for k, joint in enumerate(joints):
                plot_line(ax, t, arr[:, loads.joints.index(joint)], f"{key}_{joint}",
                      color=COLOURS[k], label=LABELS.get(joint, joint))
            finish_axes(ax, ylabel, f"{chain}: {key}", legend=c == 0)
    for ax in axes[-1]:
        ax.set_xlabel("t [s]")
    fig.suptitle(f"Joint loads ({name} trajectory): force and moment of the parent on the "
                 "child at each joint origin; the two joints of a U-joint cross carry one "
                 "wrench", fontsize=10)
    fig.tight_layout()
    return fig


def _conditioning_figure(plt, cols):
    from ..kinematics.singularity import SINGULARITY_MARGIN, WRIST_MARGIN

    t = cols["t"]
    fig, axes = plt.subplots(3, 1, figsize=(8, 7), sharex=True)
    for ax, (col, label, title, limit) in zip(axes, (
            ("wrist_margin", "|sin θ1716| [-]",
             "Wrist margin (XZX wrist singular at θ1716 = 0, π)", WRIST_MARGIN),
            ("sigma_parallel", "σ_min [m/rad]",
             "Parallel (closure) conditioning: σ_min of Jc over the passive joints",
             SINGULARITY_MARGIN),
            ("sigma_serial", "σ_min [SI]",
             "Serial conditioning: σ_min of the actuator-rate → tool-twist map",
             SINGULARITY_MARGIN))):
        plot_line(ax, t, cols[col], col, color="tab:blue", label=col)
        ax.axhline(limit, color="tab:red", ls="--", lw=1, label=f"IK limit {limit:g}")
        ax.set_ylim(bottom=0)
        finish_axes(ax, label, title)
    axes[-1].set_xlabel("t [s]")
    fig.suptitle("Distance to singularities along the trajectory")
    fig.tight_layout()
    return fig


def _path_figure(plt, cols, name):
    fig = plt.figure(figsize=(7, 6))
    ax = fig.add_subplot(projection="3d")
    x, y, z = cols["x"], cols["y"], cols["z"]
    (ln,) = ax.plot(x, y, z, color="tab:purple", lw=1, label="tool tip")
    ln.set_gid("tool_path")
    ax.scatter([x[0]], [y[0]], [z[0]], color="tab:green", s=30, label="start")
    ax.scatter([x[-1]], [y[-1]], [z[-1]], color="tab:red", s=30, label="end")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    ax.set_title(f"Tool path ({name}): tip position in world axes")
    ax.legend(fontsize=8)
    from matplotlib.ticker import MaxNLocator

    ext = np.array([np.ptp(x), np.ptp(y), np.ptp(z)])
    ax.set_box_aspect(np.maximum(ext, 0.35 * max(ext.max(), 1e-6)))
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(4))
    fig.tight_layout()
    return fig


def figures(result) -> dict:
    """``{name: matplotlib Figure}`` for a :class:`~pollard_pin.run.RunResult` (with its
    dynamics). They are not registered with pyplot: nothing to close."""
    instance(result, "result", RunResult, "a RunResult (pollard_pin.run_pipeline)")
    if result.dynamics is None:
        raise InputError("plots need the dynamics: run_pipeline(..., dynamics=True)")
    plt = figure_maker()
    cols = result.columns()
    name, chains = result.trajectory.name, dict(CHAIN_JOINTS)
    out = {
        "chain0_joints": _joint_figure(
            plt, cols, chains["chain 0"],
            f"Chain 0 joints ({name} trajectory)", ("actuated", "U joint", "U joint")),
        "wrist_joints": _joint_figure(
            plt, cols, chains["wrist"],
            f"Wrist joints, chain 0 ({name} trajectory)", ("actuated",) * 3),
    }
    for i in (1, 2):
        out[f"leg{i}_joints"] = _joint_figure(
            plt, cols, chains[f"leg {i}"],
            f"Leg {i} joints, chain {i} ({name} trajectory)",
            ("actuated", "U joint", "U joint"))
    out["spherical_joints"] = _spherical_figure(plt, cols)
    out["actuators"] = _actuator_figure(plt, cols)
    out["closure_forces"] = _closure_figure(plt, cols)
    out["conditioning"] = _conditioning_figure(plt, cols)
    out["tool_path"] = _path_figure(plt, cols, name)
    assert tuple(out) == FIGURES
    if getattr(result, "loads", None) is not None:
        out["joint_loads"] = _loads_figure(plt, result.loads, name)
    return out


def save_png(fig, path, dpi: int = 100) -> Path:
    """Write ``fig`` to ``path`` as PNG, atomically (an existing file stays as it was if the
    writing fails), and close it."""
    from ..io.atomic import atomic_open

    try:
        with atomic_open(path, binary=True) as f:
            fig.savefig(f, dpi=dpi, format="png")
    finally:
        figure_maker().close(fig)
    return Path(path)


def write_figures(result, out_dir, dpi: int = 100) -> list[Path]:
    """Write every figure of ``pollard_pin.viz.plots.figures`` as ``out_dir/<name>.png``
    (the ``pollard-pin plot`` figures, like the thesis' chapter 4), with matplotlib's
    non-interactive backend.

    Parameters
    ----------
    result : RunResult
        :func:`~pollard_pin.run_pipeline`'s result, with its dynamics.
    out_dir : str or pathlib.Path
        The folder (made if missing).
    dpi : int, optional
        The PNGs' resolution (default 100).

    Returns
    -------
    list of pathlib.Path
        The files written: ``chain0_joints.png``, ``wrist_joints.png``, ``leg1_joints.png``,
        ``leg2_joints.png``, ``spherical_joints.png``, ``actuators.png``,
        ``closure_forces.png``, ``conditioning.png``, ``tool_path.png``, ...

    Raises
    ------
    pollard_pin.errors.InputError
        ``result`` is no :class:`~pollard_pin.run.RunResult` or has no dynamics
        (``run_pipeline(..., dynamics=False)``); nothing is written.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> result = pp.run_pipeline(pp.load(), pp.thesis_trajectory(samples=101))
    >>> sorted(p.name for p in pp.write_figures(result, "plots", dpi=40))[:3]
    ['actuators.png', 'chain0_joints.png', 'closure_forces.png']
    """
    from ..io.atomic import make_folder

    made = figures(result)  # first: a result that cannot be drawn leaves no folder behind
    out_dir = make_folder(out_dir)
    return [save_png(fig, out_dir / f"{name}.png", dpi) for name, fig in made.items()]
