"""The film of a part's plan (paint/film/part.py): the curved example's film is within
target and agrees with a brute-force sum of the deposition model with a per-pair segment
test for shade."""
import math

import numpy as np
import pytest

from pollard_pin.analytic.taskspace import rotation
from pollard_pin.painting.film.part import surface_film
from pollard_pin.painting.film.stats import film_stats
from pollard_pin.painting.spray.deposition import gun_of


@pytest.fixture(scope="module")
def curved(curved_plan):
    return curved_plan, surface_film(curved_plan)


def test_curved_panel_film_within_target(curved):
    plan, (pts, film, painted, efficiency) = curved
    st = film_stats(film.thickness[painted], plan.job.thickness, pts.areas[painted])
    # measured: all within ±0.7 %
    assert st["within_5pct"] >= 0.99 and st["within_10pct"] == 1.0
    assert abs(st["mean"] / plan.job.thickness - 1) < 0.01
    assert 0.3 < efficiency < 0.9
    assert plan.layout.incidence < 5.0
    for r in plan.ratios.values():
        assert r.max() <= 1.0


def _brute_film(gun, tips, axes, w, point, normal, mesh):
    """The deposition model written out per pair (docs/model.md §20), the shade by a
    segment test per pair: trimesh's ray from the point (lifted 1e-5 m) towards the nozzle,
    any hit nearer than the nozzle shading it."""
    total = 0.0
    for p, a, wk in zip(tips, axes, w):
        if wk == 0:
            continue
        d = point - p
        h = d @ a
        if h <= 0:
            continue
        sig = gun.sigma * h / gun.standoff
        rho2 = d @ d - h * h
        cos_i = max(0.0, -d @ normal) / math.sqrt(d @ d)
        cos_a = h / math.sqrt(d @ d)
        rate = gun.flow / (2 * math.pi * sig ** 2) * math.exp(-rho2 / (2 * sig ** 2)) \
            * cos_i / cos_a
        if rate < 1e-9 * gun.flow / (2 * math.pi * gun.sigma ** 2):
            continue
        origin = point + 1e-5 * normal
        u = p - origin
        length = np.linalg.norm(u)
        locs, _, _ = mesh.ray.intersects_location([origin], [u / length])
        if len(locs) and (np.linalg.norm(locs - origin, axis=1) < length).any():
            continue
        total += wk * rate
    return total


def test_film_agrees_with_brute_force(curved):
    plan, (pts, film, painted, _) = curved
    tr = plan.trajectory
    axes = rotation(tr.poses)[:, :, 0]
    w = np.zeros(len(tr.t))
    dt = np.diff(tr.t)
    w[:-1] += dt / 2
    w[1:] += dt / 2
    w *= plan.spray
    rng = np.random.default_rng(3)
    for k in rng.choice(np.flatnonzero(painted), 4, replace=False):
        # only the samples near the point matter: the spot is a few σ across
        near = np.linalg.norm(tr.poses[:, :3] - pts.points[k], axis=1) < 0.3
        got = _brute_film(gun_of(plan.job), tr.poses[near, :3], axes[near], w[near],
                          pts.points[k], pts.normals[k], plan.part.mesh)
        # measured ≤ 1.1e-9: the brute force's rate floor (1e-9 of the spot's peak)
        assert abs(got / film.thickness[k] - 1) < 1e-7


def _drawer():
    """A closed box 0.2 m deep (more than the standoff) behind a wider front plate (a drawer,
    made of overlapping slabs), the front at x = 0 facing −x: its inside and the slabs'
    overlaps are hidden from every nozzle."""
    import trimesh

    from pollard_pin.painting.workpiece.mesh import make_part

    def slab(x0, x1, y0, y1, z0, z1):
        b = trimesh.creation.box((x1 - x0, y1 - y0, z1 - z0))
        b.apply_translation(((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2))
        return b

    w = 0.003
    m = trimesh.util.concatenate([
        slab(0.0, 0.004, -0.05, 0.05, -0.02, 0.02),  # the front
        slab(0.004, 0.20, -0.045, -0.045 + w, -0.015, 0.015),
        slab(0.004, 0.20, 0.045 - w, 0.045, -0.015, 0.015),
        slab(0.20 - w, 0.20, -0.045, 0.045, -0.015, 0.015),  # the back
        slab(0.004, 0.20, -0.045, 0.045, -0.015, -0.015 + w),
        slab(0.004, 0.20, -0.045, 0.045, 0.015 - w, 0.015)])
    return make_part(m.vertices, m.faces, facing=(-1.0, 0.0, 0.0), max_angle=45.0)


def test_a_drawer_inside_gets_no_film_points_and_is_not_painted():
    """docs/model.md §23: the inner back face (its standoff point inside the box) is not
    painted, the faces no tip sees (the inside) get no film points, and the front's film is
    the film computed with the points of every face a tip lies in front of."""
    from pollard_pin.painting.film.mesh import mesh_film
    from pollard_pin.painting.film.part import live_faces, seen_from_tips
    from pollard_pin.painting.film.points import surface_points
    from pollard_pin.painting.spray.deposition import Gun
    from pollard_pin.painting.spray.occlusion import painted_part

    part = _drawer()
    c = part.vertices[part.faces].mean(axis=1)
    x, n = c[:, 0], part.normals
    inside = (x > 0.004 + 1e-9) & (x < 0.20 - 1e-9) & (np.abs(c[:, 1]) < 0.045 - 1e-9) & (
        np.abs(c[:, 2]) < 0.015 - 1e-9) | (np.isclose(x, 0.197) & (n[:, 0] < -0.5))
    front = np.isclose(x, 0.0) & (n[:, 0] < -0.99)
    assert front.sum() == 2 and part.painted[inside].any()  # the inner back face faces −x
    painted = painted_part(part, 0.15)
    assert np.array_equal(painted.painted, front)
    gun = Gun(standoff=0.15, sigma=0.010, flow=1.5e-7)
    rows = [np.column_stack([np.full(61, -0.15), np.linspace(-0.06, 0.06, 61), np.full(61, z)])
            for z in (-0.01, 0.01)]
    p = np.vstack(rows)
    t = np.arange(len(p)) * 0.002 / 0.3
    a = np.tile((1.0, 0.0, 0.0), (len(p), 1))
    live = live_faces(painted, p)
    assert live[inside].any()  # the inside's −x, ±y faces lie before some tip
    seen = seen_from_tips(painted, p, live & ~painted.painted)
    assert not seen[inside].any() and seen[~inside & live & ~front].any()
    kept = surface_points(painted, 0.004, faces=seen | painted.painted)
    every = surface_points(painted, 0.004, faces=live | painted.painted)
    assert not np.isin(kept.faces, np.flatnonzero(inside)).any()
    assert np.isin(every.faces, np.flatnonzero(inside)).any()
    on_k, on_e = front[kept.faces], front[every.faces]
    assert np.array_equal(kept.points[on_k], every.points[on_e])
    fk = mesh_film(gun, t, p, a, kept, painted).thickness[on_k]
    fe = mesh_film(gun, t, p, a, every, painted).thickness[on_e]
    assert fk.max() > 1e-6  # the front is painted
    np.testing.assert_allclose(fk, fe, rtol=1e-12, atol=0.0)
