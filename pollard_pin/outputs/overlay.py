"""A paint output folder as the viewer's overlay (``view --paint DIR``): the film on the panel
or on the part, on the film's colour scale, with its default view and legend, riding the line
when there is one (docs/model.md §24); the folder read by :mod:`.folder`."""
from __future__ import annotations

from pathlib import Path

import numpy as np


def paint_overlay(folder, path: str = "path.csv"):
    """The film of a ``paint`` output folder as a viewer overlay: a callable drawing it, with
    ``view`` (the default ``viz.film_view.FilmView``, or None) and
    ``moving`` (the nodes the line carries, or None); ``path`` the program it needs (a
    cell's: "<name>/path.csv")."""
    from ..film_scale import film_range
    from ..viz.film_view import film_view, grid_faces
    from ..viz.viewer import film_mesh, film_panel
    from .folder import conveyor, film_tables, read_film, read_report

    folder = Path(folder)
    found = film_tables(folder, path)
    report = read_report(folder)
    film = read_film(folder, report, found)
    pts, th, target = film.points, film.thickness, film.target
    if film.faces is not None:  # a part's mesh
        def draw(vis):
            film_mesh(vis, pts, film.faces, th, *film_range(target))

        draw.view = film_view(pts, film.faces, th, target)
    else:
        def draw(vis):
            film_panel(vis, pts, th, *film_range(target))

        nv, nu = th.shape  # a grid of one row has no faces to frame: the default view
        draw.view = film_view(pts.reshape(-1, 3), grid_faces(nv, nu), th.ravel(),
                              target) if min(nu, nv) > 1 else None
    line = conveyor(folder, report)
    draw.moving = None if line is None else riding(line)
    return draw


def riding(line) -> dict:
    """The viewer's moving nodes of a film the ``line`` carries (a
    :class:`~pollard_pin.painting.line.conveyor.Line`): translation speed·t·direction at path
    time t (docs/model.md §24)."""
    from ..viz.viewer import ROOT

    speed, e = line.speed, np.asarray(line.direction)

    def place(t: float) -> np.ndarray:
        T = np.eye(4)
        T[:3, 3] = speed * t * e
        return T

    return {f"{ROOT}/paint": place}


__all__ = ["paint_overlay", "riding"]
