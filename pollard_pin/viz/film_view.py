"""How the viewer shows a film: the default camera frames the painted faces, the background
contrasts with the film's white (on target) and the page carries the colour scale's legend.

The camera rule: the orbit centre is the painted faces' area-weighted centroid; the camera
looks at it along the painted faces' mean normal (area-weighted, turned towards the gun), from
the distance at which the sphere about that centre holding every painted vertex fills MeshCat's
vertical field of view with :data:`FIT_MARGIN` to spare. Painted faces: those whose mean
vertex film is at least :data:`PAINTED_SHARE` of the target (shadowed and unreached faces
would pull the view off the film); with none, every face."""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..film_scale import film_label, film_range, scale_rgba

MESHCAT_FOV = 75.0  # degrees, the vertical field of view of MeshCat's default camera
FIT_MARGIN = 1.1  # the painted faces' sphere fills 1 / FIT_MARGIN of the view's height
PAINTED_SHARE = 0.5
# background (top, bottom) of a scene with a film: mid slate, against white film and the
# dark gun alike
FILM_BACKGROUND = ((0.50, 0.53, 0.58), (0.27, 0.29, 0.32))


@dataclass(frozen=True)
class FilmView:
    """The viewer's default view of a film (world frame, m)."""

    centre: tuple  # the orbit centre: painted faces' area-weighted centroid
    normal: tuple  # unit, from the centre towards the camera
    radius: float  # of the sphere about the centre holding the painted vertices
    legend: str = ""  # HTML colour bar for the static page
    scale: str = ""  # the colour scale in words (pollard_pin.film_scale.film_label)
    background: tuple = FILM_BACKGROUND

    @property
    def distance(self) -> float:
        return FIT_MARGIN * self.radius / math.sin(math.radians(MESHCAT_FOV) / 2)

    @property
    def offset(self) -> np.ndarray:
        """Camera position − centre."""
        return self.distance * np.asarray(self.normal)

    def seen_from(self, tips, t=None, place=None) -> FilmView:
        """This view from the gun's side of the film: the normal turned towards the mean of
        the tool tips ``tips`` (N, 3) [m] at the times ``t`` (N,) [s]. With ``place(t)`` (4×4,
        a line carrying the film from its drawn pose), the tips are taken relative to the
        moving film and the view is centred on its mean placement, the sphere grown to hold
        the travel."""
        tips = np.asarray(tips, float).reshape(-1, 3)
        shifts = np.zeros_like(tips)
        if place is not None:
            shifts = np.array([np.asarray(place(float(s)))[:3, 3] for s in np.ravel(t)])
        centre, n = np.asarray(self.centre), np.asarray(self.normal)
        if n @ ((tips - shifts).mean(axis=0) - centre) < 0:
            n = -n
        mid = shifts.mean(axis=0)
        travel = float(np.linalg.norm(shifts - mid, axis=1).max())
        return replace(self, centre=tuple(centre + mid), normal=tuple(n),
                       radius=self.radius + travel)


def legend_html(target: float, stops: int = 11) -> str:
    """A colour bar for a web page (the static viewer): the film scale's gradient
    (:mod:`pollard_pin.film_scale`) with its ends, target and label in µm, fixed at the bottom
    left."""
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


def grid_faces(nv: int, nu: int) -> np.ndarray:
    """Triangles (2 (nv − 1)(nu − 1), 3) over a surface grid's points flattened row by row
    (nv rows of nu), two per cell."""
    k = np.arange(nv * nu).reshape(nv, nu)
    a, b, c, d = k[:-1, :-1].ravel(), k[:-1, 1:].ravel(), k[1:, 1:].ravel(), k[1:, :-1].ravel()
    return np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])


def painted_faces(faces, thickness, target: float) -> np.ndarray:
    """Indices of the faces whose mean vertex film is at least PAINTED_SHARE × target
    (every face if none is)."""
    mean = np.asarray(thickness, float)[np.asarray(faces)].mean(axis=1)
    keep = np.flatnonzero(mean >= PAINTED_SHARE * target)
    return keep if len(keep) else np.arange(len(mean))


def film_view(vertices, faces, thickness, target: float, toward=None) -> FilmView:
    """The default view of the film ``thickness`` (V,) [m] on ``faces`` (M, 3) over
    ``vertices`` (V, 3) [m] for the film ``target`` [m], along the faces' winding unless
    ``toward`` (3,) [m], a point on the gun's side, is given: then turned towards it (see
    also :meth:`FilmView.seen_from`), and standing in when the painted normals cancel."""
    v, f = np.asarray(vertices, float), np.asarray(faces)[painted_faces(faces, thickness,
                                                                          target)]
    tri = v[f]
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])  # 2 × area × normal
    area = np.linalg.norm(cross, axis=1)
    centre = (tri.mean(axis=1) * area[:, None]).sum(axis=0) / max(area.sum(), 1e-300)
    n = cross.sum(axis=0)
    gun = None if toward is None else np.asarray(toward, float) - centre
    if np.linalg.norm(n) < 0.05 * area.sum():  # normals cancel: look from the gun's side
        n = gun if gun is not None and np.linalg.norm(gun) > 0 else np.array([0.0, 0.0, 1.0])
    elif gun is not None and n @ gun < 0:
        n = -n
    radius = float(np.linalg.norm(v[np.unique(f)] - centre, axis=1).max())
    return FilmView(centre=tuple(centre), normal=tuple(n / np.linalg.norm(n)),
                    radius=max(radius, 1e-3), legend=legend_html(target),
                    scale=film_label(target))


__all__ = ["FIT_MARGIN", "FILM_BACKGROUND", "FilmView", "MESHCAT_FOV", "PAINTED_SHARE",
           "film_view", "grid_faces", "legend_html", "painted_faces"]
