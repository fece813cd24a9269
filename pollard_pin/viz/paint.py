"""The paint figure: the film over the panel as a heat map, with the gun's path drawn over it.
It draws what :mod:`pollard_pin.paint` computed; nothing here computes."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..film_scale import FILM_BAND as BAND
from ..film_scale import FILM_CMAP, film_label, film_range


def thickness_figure(U, V, thickness, target: float, path_uv=None,
                     width: float | None = None, height: float | None = None,
                     title: str = "Film thickness"):
    """Heat map of ``thickness`` (nv, nu) [m] on the panel grid ``U`` (nu,), ``V`` (nv,) [m],
    coloured on the film scale (:mod:`pollard_pin.film_scale`, target ± BAND), with
    ``path_uv`` (2, N) [m] (the tool tip in panel coordinates) drawn over it, clipped to a
    margin around the panel. Artist gids: ``film``, ``path``, ``panel``."""
    from matplotlib.figure import Figure

    U, V = np.asarray(U) * 1e3, np.asarray(V) * 1e3
    th = np.asarray(thickness) * 1e6
    t0 = target * 1e6
    fig = Figure(figsize=(9, 5.2), constrained_layout=True)
    ax = fig.add_subplot()
    lo, hi = film_range(t0)
    mesh = ax.pcolormesh(U, V, th, shading="nearest", cmap=FILM_CMAP, vmin=lo, vmax=hi)
    mesh.set_gid("film")
    cb = fig.colorbar(mesh, ax=ax, extend="both")
    cb.set_label(film_label(target))
    w = (U[-1] - U[0]) if width is None else width * 1e3
    h = (V[-1] - V[0]) if height is None else height * 1e3
    (edge,) = ax.plot([-w / 2, w / 2, w / 2, -w / 2, -w / 2],
                      [-h / 2, -h / 2, h / 2, h / 2, -h / 2], color="k", lw=1.2)
    edge.set_gid("panel")
    if path_uv is not None:
        pu, pv = np.asarray(path_uv) * 1e3
        (ln,) = ax.plot(pu, pv, color="0.25", lw=0.7, alpha=0.8, label="gun path (tool tip)")
        ln.set_gid("path")
        ax.legend(loc="upper right", fontsize=8)
    margin = 0.35 * max(w, h)
    ax.set_xlim(-w / 2 - margin, w / 2 + margin)
    ax.set_ylim(-h / 2 - margin / 2, h / 2 + margin / 2)
    ax.set_aspect("equal")
    ax.set_xlabel("u [mm] (panel width)")
    ax.set_ylabel("v [mm] (panel height)")
    ax.set_title(f"{title}: min {th.min():.4g}, max {th.max():.4g} µm")
    return fig


def write_thickness_png(path, *args, dpi: int = 100, **kwargs) -> Path:
    """:func:`thickness_figure` written to ``path`` as PNG, atomically."""
    from .plots import save_png

    return save_png(thickness_figure(*args, **kwargs), path, dpi)


__all__ = ["BAND", "thickness_figure", "write_thickness_png"]
