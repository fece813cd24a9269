"""The film on a part (``paint`` of a [part] job): the film points projected on the passes'
plane (along, across the passes: the part seen from the robot) coloured by thickness, the
passes' spot tracks drawn over them, on the film scale (:mod:`pollard_pin.film_scale`). It
draws what :mod:`pollard_pin.painting` computed; nothing here computes."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..film_scale import FILM_CMAP, film_label, film_range

# the axes' names of a still part's or a part's on a line (the layout's along and across)
PASS_AXES = ("along the passes [mm]", "across the passes [mm]")


def part_figure(points, thickness, target: float, along, across, tracks=(),
                title: str = "Film thickness on the part", labels=PASS_AXES):
    """Scatter of the film ``points`` (P, 3) [m] projected on the unit ``along`` and
    ``across`` axes, coloured by ``thickness`` [m] on the film scale, with ``tracks`` (each
    (K, 3) [m], the spray spot's centre along a pass) drawn over them; ``labels`` name the
    two axes (x, y; a cell's: the line and across it). Artist gids: ``film``, ``passes``."""
    from matplotlib.figure import Figure

    pts = np.asarray(points, float)
    x, y = pts @ along * 1e3, pts @ across * 1e3
    lo, hi = film_range(target * 1e6)
    fig = Figure(figsize=(9, 5.2), constrained_layout=True)
    ax = fig.add_subplot()
    sc = ax.scatter(x, y, c=np.asarray(thickness) * 1e6, s=4, cmap=FILM_CMAP, vmin=lo,
                    vmax=hi, linewidths=0)
    sc.set_gid("film")
    cb = fig.colorbar(sc, ax=ax, extend="both")
    cb.set_label(film_label(target))
    for k, tr in enumerate(tracks):
        tr = np.asarray(tr, float)
        (ln,) = ax.plot(tr @ along * 1e3, tr @ across * 1e3, color="0.25", lw=0.7, alpha=0.8,
                        label="passes (spot centre)" if k == 0 else None)
        ln.set_gid("passes")
    if len(tracks):
        ax.legend(loc="upper right", fontsize=8)
    ax.set_aspect("equal")
    ax.set_xlabel(labels[0])
    ax.set_ylabel(labels[1])
    ax.set_title(title)
    return fig


def write_part_png(path, *args, dpi: int = 100, **kwargs) -> Path:
    """:func:`part_figure` written to ``path`` as PNG, atomically."""
    from .plots import save_png

    return save_png(part_figure(*args, **kwargs), path, dpi)


__all__ = ["PASS_AXES", "part_figure", "write_part_png"]
