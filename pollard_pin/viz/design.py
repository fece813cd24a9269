"""A design study's front as a figure: every evaluation faint, the front's designs by their
number of robots, the thesis robot as a star and the chosen design ringed. It draws the
numbers it is given; it computes nothing. Matplotlib's object API (no pyplot)."""
from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path

# (x, y) of each panel: the line's output against its cost, and the motors against stiffness
PANELS = (("moving_mass", "parts_per_hour"), ("motor_use", "kmin"))
AXIS = {"parts_per_hour": "parts per hour [1/h]", "moving_mass": "moving mass [kg]",
        "motor_use": "worst motor use [1]", "kmin": "kmin [N/m]", "robots": "robots"}
MARKERS = "os^Dvp*"


def _xy(rows: Sequence[Mapping], x: str, y: str):
    pts = [(r[x], r[y]) for r in rows
           if r.get(x) is not None and r.get(y) is not None
           and math.isfinite(r[x]) and math.isfinite(r[y])]
    return [p[0] for p in pts], [p[1] for p in pts]


def front_figure(front: Sequence[Mapping], others: Sequence[Mapping] = (),
                 baseline: Mapping | None = None, chosen: int | None = None):
    """A matplotlib Figure of the front. Artists carry gids: ``evaluations``,
    ``front_<robots>``, ``baseline``, ``chosen``.

    Parameters
    ----------
    front : Sequence of Mapping
        The front designs' objectives (``parts_per_hour``, ``robots``, ``motor_use``,
        ``kmin``, ``moving_mass``).
    others : Sequence of Mapping, optional
        The other feasible evaluations' objectives (drawn faint).
    baseline : Mapping or None, optional
        The thesis robot's objectives (None: it cannot paint the job).
    chosen : int or None, optional
        The chosen design's index in ``front``.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from .plots import figure_maker

    fig, axes = figure_maker().subplots(1, len(PANELS), figsize=(11, 4.5),
                                        constrained_layout=True)
    counts = sorted({int(r["robots"]) for r in front})
    for ax, (x, y) in zip(axes, PANELS):
        if others:
            ax.scatter(*_xy(others, x, y), s=10, c="0.75", label="evaluated",
                       gid="evaluations")
        for k, n in enumerate(counts):
            rows = [r for r in front if int(r["robots"]) == n]
            ax.scatter(*_xy(rows, x, y), s=40, marker=MARKERS[k % len(MARKERS)],
                       label=f"front: {n} robot{'s' if n != 1 else ''}", gid=f"front_{n}",
                       zorder=3)
        if baseline is not None:
            ax.scatter(*_xy([baseline], x, y), s=160, marker="*", c="k", label="thesis robot",
                       gid="baseline", zorder=4)
        if chosen is not None:
            ax.scatter(*_xy([front[chosen]], x, y), s=220, facecolors="none",
                       edgecolors="tab:red", linewidths=2, label="chosen", gid="chosen",
                       zorder=5)
        ax.set_xlabel(AXIS[x])
        ax.set_ylabel(AXIS[y])
        ax.grid(True, alpha=0.3)
    axes[0].legend(loc="best", fontsize=8)
    fig.suptitle(f"design front: {len(front)} designs")
    return fig


def write_front_png(path, front, others=(), baseline=None, chosen=None,
                    dpi: int = 100) -> Path:
    """Write :func:`front_figure` to ``path`` (PNG), atomically.

    Parameters
    ----------
    path : str or Path
        The PNG file.
    front, others, baseline, chosen
        As :func:`front_figure`'s.
    dpi : int, optional
        Resolution.

    Returns
    -------
    Path
        ``path``.
    """
    from .plots import save_png

    return save_png(front_figure(front, others, baseline, chosen), path, dpi)
