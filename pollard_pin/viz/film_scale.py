"""The one colour scale of a film, shared by thickness.png, film.ply's vertex colours and the
viewer (its legend included): matplotlib's ``RdBu_r`` over target × (1 ± FILM_BAND), blue
thin, white on target, red thick, clipped beyond. Fixed rather than fitted to each film, so
the same colour means the same thickness in every file of every job."""
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
    """RGBA bytes (n, 4) of ``thickness`` [m] on the film scale of ``target`` [m]."""
    return (scale_rgba(thickness, *film_range(target)) * 255).round().astype(np.uint8)


def legend_html(target: float, stops: int = 11) -> str:
    """A colour bar for a web page (the static viewer): the scale's gradient with its ends,
    target and label in µm, fixed at the bottom left."""
    lo, hi = film_range(target)
    rgb = (scale_rgba(np.linspace(lo, hi, stops), lo, hi)[:, :3] * 255).round().astype(int)
    grad = ", ".join(f"rgb({r},{g},{b})" for r, g, b in rgb)
    ticks = "".join(f'<span>{x * 1e6:.4g}</span>' for x in (lo, target, hi))
    return (
        '<div id="film-legend" style="position:fixed;left:12px;bottom:12px;z-index:10;'
        'padding:6px 10px;background:rgba(255,255,255,0.92);border-radius:4px;'
        'font:12px sans-serif;color:#222">'
        f'<div>{film_label(target)}</div>'
        f'<div style="width:260px;height:14px;margin:4px 0;border:1px solid #444;'
        f'background:linear-gradient(to right, {grad})"></div>'
        f'<div style="width:262px;display:flex;justify-content:space-between">{ticks}</div>'
        '<div>beyond the ends: the end colour</div></div>')


__all__ = ["FILM_BAND", "FILM_CMAP", "film_label", "film_range", "film_rgba", "legend_html",
           "scale_rgba"]
