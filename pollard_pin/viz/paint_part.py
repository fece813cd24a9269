"""The film on a part (``paint`` of a [part] job): the film points projected on the passes'
plane (along, across the passes: the part seen from the robot) coloured by thickness, the
passes' spot tracks drawn over them; and the film's vertex colours for ``film.ply``. It draws
what :mod:`pollard_pin.paint` computed; nothing here computes."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .film_scale import FILM_BAND as PLY_BAND
from .film_scale import FILM_CMAP as PLY_CMAP
from .film_scale import film_label, film_range, film_rgba


def ply_colours(target: float) -> dict:
    """What film.ply's colours mean, for paint.json: the colour map and the range [m]."""
    return {"colour_map": PLY_CMAP, "range": list(film_range(target))}


def film_colours(thickness, target: float) -> np.ndarray:
    """RGBA bytes (P, 4) of ``thickness`` [m] on the film scale (:mod:`.film_scale`)."""
    return film_rgba(thickness, target)


def part_figure(points, thickness, target: float, along, across, tracks=(),
                title: str = "Film thickness on the part"):
    """Scatter of the film ``points`` (P, 3) [m] projected on the unit ``along`` and
    ``across`` axes, coloured by ``thickness`` [m] on the film scale, with ``tracks`` (each
    (K, 3) [m], the spray spot's centre along a pass) drawn over them. Artist gids: ``film``,
    ``passes``."""
    from matplotlib.figure import Figure

    pts = np.asarray(points, float)
    x, y = pts @ along * 1e3, pts @ across * 1e3
    lo, hi = film_range(target * 1e6)
    fig = Figure(figsize=(9, 5.2), constrained_layout=True)
    ax = fig.add_subplot()
    sc = ax.scatter(x, y, c=np.asarray(thickness) * 1e6, s=4, cmap=PLY_CMAP, vmin=lo,
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
    ax.set_xlabel("along the passes [mm]")
    ax.set_ylabel("across the passes [mm]")
    ax.set_title(title)
    return fig


def write_part_png(path, *args, dpi: int = 100, **kwargs) -> Path:
    """:func:`part_figure` written to ``path`` as PNG, atomically."""
    from .plots import save_png

    return save_png(part_figure(*args, **kwargs), path, dpi)


__all__ = ["PLY_BAND", "PLY_CMAP", "film_colours", "part_figure", "write_part_png"]
