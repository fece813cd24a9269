"""The film a planned path leaves on its panel: the grid, the integration and the statistics
(docs/model.md §20–21)."""
from __future__ import annotations

import numbers

import numpy as np

from ...analytic.taskspace import rotation
from ..errors import PlanError, ResolutionError
from ..job import PaintJob
from ..plan.panel import PaintPlan
from ..spray.deposition import Film, film, gun_of

# Budgets of the film map, checked before the grid is made: its points (the table, the figure)
# and the point × path-sample pairs the integration evaluates (≈ 70 ns each: 5e9 ≈ 6 min).
MAX_FILM_POINTS = 2_000_000
MAX_FILM_PAIRS = 5e9


def film_spacing(sigma: float, resolution: float | None = None,
                 what: str = "film grid spacing") -> float:
    """The spacing [m] of the points a film is computed at, panel grid or part points:
    ``resolution`` (default σ/3), which must be > 0 and at most σ: coarser points cannot show
    the ripple between passes (some 2σ apart, docs/model.md §21)."""
    res = sigma / 3 if resolution is None else resolution
    if isinstance(res, bool) or not (isinstance(res, numbers.Real) and 0 < res <= sigma):
        raise ResolutionError(f"{what} {res!r} m must be > 0 and at most the spray spot's "
                        f"σ = {sigma:g} m (a coarser one cannot show the film between "
                        "passes)")
    return float(res)


def film_resolution(job: PaintJob, resolution: float | None = None) -> float:
    """The panel's film grid spacing [m] (:func:`film_spacing`), and the grid it makes within
    MAX_FILM_POINTS."""
    res = film_spacing(job.sigma, resolution)
    points = _axis_points(job.width, res) * _axis_points(job.height, res)
    if points > MAX_FILM_POINTS:
        raise ResolutionError(f"film grid spacing {res:.4g} m makes {points:.4g} film points "
                              f"on the {job.width:g} × {job.height:g} m panel, budget "
                              f"{MAX_FILM_POINTS:.3g}: a coarser resolution")
    return res


def _axis_points(length: float, res: float) -> float:
    """Grid points along a side (a float: 1e-300 m overflows no integer)."""
    return float(np.ceil(length / res - 1e-9)) + 1


def film_grid(plan_or_frame, job: PaintJob, resolution: float | None = None):
    """The regular grid over the panel, edges included, spacing ≤ ``resolution`` (default
    σ/3, at most σ: :func:`film_resolution`): (U (nu,), V (nv,), world points (nv, nu, 3))."""
    frame = plan_or_frame.frame if isinstance(plan_or_frame, PaintPlan) else plan_or_frame
    res = film_resolution(job, resolution)
    U = np.linspace(-job.width / 2, job.width / 2, int(_axis_points(job.width, res)))
    V = np.linspace(-job.height / 2, job.height / 2, int(_axis_points(job.height, res)))
    UU, VV = np.meshgrid(U, V)
    return U, V, frame.world(UU, VV)


def plan_film(plan: PaintPlan, resolution: float | None = None):
    """The film a still panel's plan leaves, on a grid over the panel (edges included).

    Parameters
    ----------
    plan : PaintPlan
        From :func:`~pollard_pin.painting.plan.plan_paint`.
    resolution : float or None, optional
        The grid spacing [m], at most σ (None: σ/3).

    Returns
    -------
    U, V : ndarray
        The grid's coordinates along the panel's u and v axes [m].
    points : ndarray
        (nv, nu, 3) the grid points, world frame [m].
    film : pollard_pin.painting.spray.deposition.Film
        The thickness [m] over the flattened grid and its error estimate.

    Raises
    ------
    PlanError
        A grid too fine for the path (over the point × sample budget).
    """
    U, V, pts = film_grid(plan, plan.job, resolution)
    tr = plan.trajectory
    pairs = float(pts.shape[0] * pts.shape[1]) * len(tr.t)
    if pairs > MAX_FILM_PAIRS:
        raise PlanError(f"the film map needs {pairs:.3g} point × sample pairs ({len(U)} × "
                        f"{len(V)} points, {len(tr.t)} path samples), budget "
                        f"{MAX_FILM_PAIRS:.3g}: a coarser film grid")
    axes = rotation(tr.poses)  # the spot turns with the gun (docs/model.md §20)
    f: Film = film(gun_of(plan.job), tr.t, tr.poses[:, :3], axes, pts.reshape(-1, 3),
                   plan.frame.n, origin=plan.frame.c)
    return U, V, pts, f
