"""The one colour scale of a film, shared by thickness.png, film.ply's vertex colours,
paint.json's ``film_ply`` and the viewer (its legend included): matplotlib's ``RdBu_r`` over
target × (1 ± FILM_BAND), blue thin, white on target, red thick, clipped beyond. Fixed rather
than fitted to each film, so the same colour means the same thickness in every file of every
job. A leaf: the colour arithmetic only (numpy, matplotlib's colour map), so that the writers
of every layer use it; the figures and the legend that draw it are in :mod:`pollard_pin.viz`."""
from __future__ import annotations

import numpy as np

FILM_CMAP = "RdBu_r"
# ±10 %: a real part's film (edges, curvature) mostly stays inside it, and a panel's ±2 %
# aim still shows as a visible tint rather than one flat white
FILM_BAND = 0.10


def film_range(target: float) -> tuple[float, float]:
    """The thickness [m] at each end of the colour scale."""
    return target * (1 - FILM_BAND), target * (1 + FILM_BAND)


def film_label(target: float) -> str:
    """The scale as stated on every figure and in the viewer's legend."""
    return f"film thickness [µm] (target {target * 1e6:.4g} ± {100 * FILM_BAND:g} %)"


def scale_rgba(values, lo: float, hi: float) -> np.ndarray:
    """RGBA in [0, 1] (n, 4) of ``values`` on FILM_CMAP from ``lo`` to ``hi``, clipped."""
    from matplotlib import colormaps

    x = (np.asarray(values, float).ravel() - lo) / (hi - lo)
    return colormaps[FILM_CMAP](np.clip(x, 0.0, 1.0))


def film_rgba(thickness, target: float) -> np.ndarray:
    """RGBA bytes (n, 4) of ``thickness`` [m] on the film scale of ``target`` [m] (film.ply's
    vertex colours)."""
    return (scale_rgba(thickness, *film_range(target)) * 255).round().astype(np.uint8)


def ply_colours(target: float) -> dict:
    """What film.ply's colours mean, for paint.json's ``film_ply``: the colour map and the
    range [m]."""
    return {"colour_map": FILM_CMAP, "range": list(film_range(target))}


__all__ = ["FILM_BAND", "FILM_CMAP", "film_label", "film_range", "film_rgba", "ply_colours",
           "scale_rgba"]
