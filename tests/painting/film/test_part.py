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


def _rows(z_values, x=-0.15, n=61, half=0.06):
    """Tips (n·len(z_values), 3) on rows along y at x, one row a height."""
    return np.vstack([np.column_stack([np.full(n, x), np.linspace(-half, half, n),
                                       np.full(n, z)]) for z in z_values])


def _brute_seen(part, tips, faces, probes, owner):
    """seen_from_tips written out: a face is seen where one of the rays from each of its
    probes to each tip in front of it, all cast, is clear."""
    from pollard_pin.painting.spray.occlusion import visible

    out = np.zeros(len(part.faces), dtype=bool)
    idx = np.flatnonzero(faces)
    for k, f in enumerate(idx):
        n = part.normals[f]
        front = tips[tips @ n > part.vertices[part.faces[f, 0]] @ n]
        pk = probes[owner == k]
        out[f] = visible(part, np.repeat(front, len(pk), axis=0), np.tile(pk, (len(front), 1)),
                         np.tile(n, (len(front) * len(pk), 1))).any()
    return out


def test_seen_faces_agree_with_every_tip_tried_at_every_probe():
    """The faces seen_from_tips keeps (nearest tips first, all faces at once, then face by
    face in growing blocks) are those a ray from some probe to some tip in front finds clear,
    tried in full on the drawer (dark and lit faces both)."""
    from pollard_pin.painting.film import part as fp
    from pollard_pin.painting.spray.occlusion import painted_part

    part = painted_part(_drawer(), 0.15)
    tips = _rows((-0.03, -0.01, 0.01, 0.03))
    live = fp.live_faces(part, tips) & ~part.painted
    seen = fp.seen_from_tips(part, tips, live)
    probes, owner = fp.face_probes(part, np.flatnonzero(live))
    assert len(probes) == 7 * live.sum()  # the centroid, the corners and the midpoints
    want = _brute_seen(part, tips, live, probes, owner)
    assert want.any() and (live & ~want).any()  # both kinds are there
    np.testing.assert_array_equal(seen, want)


def _slot():
    """A square 0.2 m wide (two triangles) facing −x at x = 0.2, behind a screen at x = 0
    whose only opening is a slot 8 mm wide along y, 0.045 m above the square's centre: from
    tips level with the slot no probe of the square's (its centroids, corners and edges'
    midpoints) lies behind it."""
    import trimesh

    from pollard_pin.painting.workpiece.mesh import make_part

    def slab(x0, x1, y0, y1, z0, z1):
        b = trimesh.creation.box((x1 - x0, y1 - y0, z1 - z0))
        b.apply_translation(((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2))
        return b

    back = trimesh.Trimesh([[0.2, -0.1, -0.1], [0.2, 0.1, -0.1], [0.2, 0.1, 0.1],
                            [0.2, -0.1, 0.1]], [[0, 2, 1], [0, 3, 2]])
    m = trimesh.util.concatenate([back, slab(0.0, 0.004, -0.2, 0.2, -0.2, 0.041),
                                  slab(0.0, 0.004, -0.2, 0.2, 0.049, 0.2)])
    return make_part(m.vertices, m.faces, facing=(-1.0, 0.0, 0.0), max_angle=45.0)


def test_a_face_lit_only_through_a_slot_is_seen_at_probes_as_fine_as_the_slot():
    """docs/model.md §23: the square behind the slot gets film through it (the film at its
    points, every face's points kept), yet its seven probes a face are dark; probes on a
    lattice as fine as the slot (spacing) see it, and its film points then carry the film."""
    from pollard_pin.painting.film import part as fp
    from pollard_pin.painting.film.mesh import mesh_film
    from pollard_pin.painting.film.points import surface_points
    from pollard_pin.painting.spray.deposition import Gun
    from pollard_pin.painting.spray.occlusion import painted_part

    part = painted_part(_slot(), 0.15)
    square = np.zeros(len(part.faces), dtype=bool)
    square[:2] = True
    assert not part.painted[square].any()  # its standoff ray meets the screen
    p = _rows((0.045,), n=81, half=0.08)  # one row, level with the slot
    live = fp.live_faces(part, p) & ~part.painted
    assert live[square].all()
    pts = surface_points(part, 0.004, faces=square)
    gun = Gun(standoff=0.15, sigma=0.010, flow=1.5e-7)
    t = np.arange(len(p)) * 0.004 / 0.3
    film = mesh_film(gun, t, p, np.tile((1.0, 0.0, 0.0), (len(p), 1)), pts, part)
    assert film.thickness.max() > 1e-3 * 25e-6  # paint lands through the slot
    assert not fp.seen_from_tips(part, p, live)[square].any()  # the seven probes: dark
    fine = fp.seen_from_tips(part, p, live, spacing=0.004)
    assert fine[square].all()
    np.testing.assert_array_equal(fine[square], _brute_seen(
        part, p, square, *fp.face_probes(part, np.flatnonzero(square), 0.004))[square])


def _screened():
    """A front plate (x 0 to 4 mm, y ±30 mm, z ±20 mm) and 0.1 m behind it a wall rising
    12 mm above it: the wall's face towards the gun is not painted (its centroid behind the
    front), its top lit over the front's edge, its foot in the front's shadow."""
    import trimesh

    from pollard_pin.painting.workpiece.mesh import make_part

    def slab(x0, x1, y0, y1, z0, z1):
        b = trimesh.creation.box((x1 - x0, y1 - y0, z1 - z0))
        b.apply_translation(((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2))
        return b

    m = trimesh.util.concatenate([slab(0.0, 0.004, -0.03, 0.03, -0.02, 0.02),
                                  slab(0.1, 0.104, -0.03, 0.03, -0.02, 0.032)])
    return make_part(m.vertices, m.faces, facing=(-1.0, 0.0, 0.0), max_angle=45.0)


def test_faces_not_painted_at_spot_sigma_land_what_a_fine_lattice_lands():
    """docs/model.md §23: the faces not painted carry strip points σ apart (surface_film's
    rule) instead of the lattice at h = σ/3: the painted points and their film are the same
    bit for bit (achieved: equal), and the volume landed on the part (the transfer
    efficiency's numerator, a quarter of it on the wall, lit in part) agrees with the lattice
    at h/3 on every face a tip lies in front of, every pair's ray cast, to 1e-2 of it
    (achieved 2.4e-3; the lattices at h, h/2, h/3, h/4 themselves spread over 6e-3: the
    wall's shadow edge is first order in the spacing)."""
    from pollard_pin.painting.film import part as fp
    from pollard_pin.painting.film.mesh import mesh_film
    from pollard_pin.painting.film.points import surface_points
    from pollard_pin.painting.spray.deposition import Gun
    from pollard_pin.painting.spray.occlusion import painted_part

    part = painted_part(_screened(), 0.15)
    wall = np.isclose(part.vertices[part.faces].mean(axis=1)[:, 0], 0.1) & (
        part.normals[:, 0] < -0.99)
    assert wall.sum() == 2 and not part.painted[wall].any()
    gun = Gun(standoff=0.15, sigma=0.010, flow=1.5e-7)
    p = _rows((-0.01, 0.01, 0.03, 0.05), n=41, half=0.04)
    t = np.arange(len(p)) * 0.002 / 0.3
    a = np.tile((1.0, 0.0, 0.0), (len(p), 1))
    live = fp.live_faces(part, p) & ~part.painted
    seen = fp.seen_from_tips(part, p, live)
    assert seen[wall].all()
    h = gun.sigma / 3
    fine = surface_points(part, h / 3, faces=live | part.painted)
    rule = surface_points(part, h, faces=seen | part.painted, coarse=(seen, gun.sigma))
    same = surface_points(part, h, faces=part.painted)
    assert len(rule) < len(same) + 250
    ff, fr, fs = (mesh_film(gun, t, p, a, x, part) for x in (fine, rule, same))
    on_r = part.painted[rule.faces]
    np.testing.assert_array_equal(rule.points[on_r], same.points)
    np.testing.assert_allclose(fr.thickness[on_r], fs.thickness, rtol=1e-12, atol=0.0)
    lit = ff.thickness[wall[fine.faces]]
    assert lit.max() > 0.05 * fs.thickness.max() and (lit == 0).any()  # lit in part
    assert ff.landed - fs.landed > 0.1 * ff.landed  # what lands off the painted faces
    assert abs(fr.landed / ff.landed - 1) < 1e-2
