"""The film of a paint cell (docs/model.md §26.1, §26.3): every robot's gun seen from the part
(its base-frame path less the line's displacement, turned into the world), integrated on
the part at its t = 0 pose in world coordinates, summed over the robots. The trigger's
fractions at the seam samples weigh the trapezoid rule, so each robot's film stops exactly
at its seam."""
from __future__ import annotations

import numpy as np

from ...analytic.taskspace import rotation
from ...dynamics.averages import trapezoid_weights
from ..errors import PlanError
from ..progress import bar
from ..spray.deposition import (
    BLOCK_ELEMENTS,
    Film,
    Reach,
    coarse_weights,
    gun_of,
    sources,
    spot_block,
)
from .grid import MAX_FILM_PAIRS, film_grid
from .mesh import MeshFilm, film_groups, mesh_film


def world_gun(rp) -> tuple:
    """(t, tips (N, 3), gun rotations (N, 3, 3), spray (N,)) of a robot's plan
    (:class:`.cell.plan.RobotPlan`) seen from the part at its t = 0 pose, world coordinates
    (the rotations' first column the spray axis)."""
    plan, cr = rp.plan, rp.robot
    tr = plan.trajectory
    tips = tr.poses[:, :3] - plan.speed * tr.t[:, None] * plan.direction[None, :]
    R = rotation(tr.poses)  # each column turned as the axis always was, row by row
    frames = np.stack([R[:, :, i] @ cr.R.T for i in range(3)], axis=2)
    return tr.t, cr.to_world(tips), frames, plan.spray


def run_weights(t, spray) -> tuple:
    """The trapezoid weights (and the coarse rule's) over each run of samples where the
    trigger is open, a seam's sample (a fraction) ending its run: the rule of a trigger that
    switches exactly at the run's end samples, as :func:`.film.line.line_film` integrates
    the sprayed samples."""
    on = np.concatenate([[False], spray > 0, [False]])
    edges = np.flatnonzero(np.diff(on.astype(int)))
    w, w2 = np.zeros(len(t)), np.zeros(len(t))
    for a, b in zip(edges[::2], edges[1::2]):
        w[a:b], w2[a:b] = trapezoid_weights(t[a:b]), coarse_weights(t[a:b])
    return w, w2


def weighted_film(gun, t, p, a, spray, s, n, origin) -> Film:
    """The film at points ``s`` (P, 3) of normal ``n`` (3,) of the tips ``p`` and axes ``a``
    at times ``t``, the trapezoid rule over each run of open trigger (:func:`run_weights`;
    :func:`.spray.deposition.film` over the sprayed samples where there is one run)."""
    w, w2 = run_weights(t, spray)
    live = np.flatnonzero(w > 0)
    p, s = p - origin, s - origin
    total, coarse = np.zeros(len(s)), np.zeros(len(s))
    block = max(1, BLOCK_ELEMENTS // max(len(s), 1))
    groups, centres, radii = film_groups(s, [np.arange(len(s))])
    for start in bar(range(0, len(live), block), "film"):
        i = live[start:start + block]
        # near_spot's points: keep's test, point by point, on the points of the groups whose
        # bounding balls may hold one (holds is False only where keep keeps none), so the
        # same points (a part's film likewise, film/mesh.py)
        cull = Reach(gun, *spot_block(p[i], a[i]))
        k, r, _ = cull.rate_near(gun, sources(gun, p[i], a[i]), s, n, groups[0],
                                 cull.holds(centres, radii))
        total[k] += w[i] @ r
        coarse[k] += w2[i] @ r
    return Film(total, np.abs(total - coarse), float(gun.flow * w.sum()))


def cell_panel_film(cell, resolution: float | None = None):
    """(U, V, points (nv, nu, 3), Film) of a panel cell: the world panel's grid, the film of
    every robot summed (each robot's own: its ``robots``)."""
    from ..workpiece.panel import panel_frame

    job = cell.job
    frame = panel_frame(job)
    U, V, pts = film_grid(frame, job, resolution)
    flat = pts.reshape(-1, 3)
    total, err, films = np.zeros(len(flat)), np.zeros(len(flat)), []
    for rp in cell.robots:
        t, p, a, spray = world_gun(rp)
        pairs = float(len(flat)) * int((spray > 0).sum())
        if pairs > MAX_FILM_PAIRS:
            raise PlanError(f"the film map needs {pairs:.3g} point × sample pairs for robot "
                            f"{rp.robot.name!r}, budget {MAX_FILM_PAIRS:.3g}: a coarser film "
                            "grid")
        f = weighted_film(gun_of(job), t, p, a, spray, flat, frame.n, frame.c)
        total += f.thickness
        err += f.error_estimate
        films.append(f)
    return U, V, pts, Film(total, err, sum(f.sprayed for f in films), tuple(films))


def cell_part_film(cell, resolution: float | None = None):
    """(film points (:func:`.film.part.film_points` of every robot's tips), the
    :class:`.film.mesh.MeshFilm` summed over the robots, painted mask, transfer efficiency)
    of a part cell: the world part at t = 0 (``cell.part``), every robot's film with shadows
    and its trigger."""
    from .part import film_points

    job, part = cell.job, cell.part
    guns = [world_gun(rp) for rp in cell.robots]
    pts = film_points(part, np.concatenate([p[s > 0] for _, p, _, s in guns]), job, resolution)
    films = [mesh_film(gun_of(job), t, p, a, pts, part, s) for t, p, a, s in guns]
    f = MeshFilm(sum(x.thickness for x in films), sum(x.error_estimate for x in films),
                 sum(x.pairs for x in films), sum(x.shaded for x in films),
                 sum(x.sprayed for x in films), sum(x.landed for x in films),
                 films[0].whole_part, sum(x.switches for x in films), robots=tuple(films))
    efficiency = f.landed / f.sprayed if f.sprayed > 0 else float("nan")
    return pts, f, part.painted[pts.faces], efficiency


__all__ = ["cell_panel_film", "cell_part_film", "weighted_film", "world_gun"]
