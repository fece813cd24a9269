"""Film points on a part: their areas sum to the faces' exactly, no surface point lies
further than the resolution allows from one, and the lattice integrates linear functions
exactly."""
import math
import warnings

import numpy as np
import pytest
import trimesh
from scipy.spatial import cKDTree

from pollard_pin.painting.errors import MeshError
from pollard_pin.painting.film import points as fp_module
from pollard_pin.painting.film.points import lattice, surface_points
from pollard_pin.painting.workpiece import shapes
from pollard_pin.painting.workpiece.mesh import make_part

SIGMA = 0.010


@pytest.fixture(scope="module", params=["curved_panel", "bent_plate", "ribbed_plate"])
def part(request):
    m = getattr(shapes, request.param)()
    return make_part(m.vertices, m.faces, source=request.param)


@pytest.mark.parametrize("n", [1, 2, 3, 7])
def test_lattice_shares_and_linear_exactness(n):
    bary, share = lattice(n)
    assert len(bary) == (n + 1) * (n + 2) // 2
    assert np.allclose(bary.sum(axis=1), 1.0, atol=1e-15)
    assert share.sum() == pytest.approx(1.0, rel=1e-14)
    # a linear function's mean over the triangle is its mean at the corners: exact
    f = bary @ np.array([0.3, -1.7, 2.9])
    assert share @ f == pytest.approx((0.3 - 1.7 + 2.9) / 3, rel=1e-13)
    # a quadratic one (mean of x² over the triangle: 1/6) to O(1/n²)
    if n > 1:
        err = abs(share @ bary[:, 0] ** 2 - 1 / 6)
        assert 0 < err < 0.2 / n ** 2


@pytest.mark.parametrize("faces", ["painted", "all"])
def test_areas_sum_to_the_faces_area(part, faces):
    sp = surface_points(part, sigma=SIGMA, faces=faces)
    want = part.painted_area if faces == "painted" else part.areas.sum()
    # achieved ~1e-16 relative (summation order); asserted 1e-13
    assert abs(sp.area / want - 1) < 1e-13
    assert (sp.areas > 0).all()
    assert np.allclose(np.linalg.norm(sp.normals, axis=1), 1.0, atol=1e-14)
    # each point lies on its face's plane, and has that face's normal
    v0 = part.vertices[part.faces[sp.faces, 0]]
    assert np.abs(np.einsum("ij,ij->i", sp.points - v0, part.normals[sp.faces])).max() < 1e-12
    assert np.array_equal(sp.normals, part.normals[sp.faces])


def test_no_surface_point_is_far_from_a_film_point(part):
    """Sub-triangle edges ≤ h: every point of a painted face lies within h/√3 of a lattice
    point (the equilateral sub-triangle's centre is the worst case)."""
    h = SIGMA / 3
    sp = surface_points(part, sigma=SIGMA)
    painted = trimesh.Trimesh(part.vertices, part.faces[part.painted], process=False)
    rng = np.random.default_rng(1)
    samples, _ = trimesh.sample.sample_surface(painted, 20000, seed=rng)
    dist, _ = cKDTree(sp.points).query(samples)
    assert dist.max() <= h / math.sqrt(3) * (1 + 1e-9)
    # and the points are not needlessly dense: the nearest neighbour is ≥ h/4 away on average
    nn, _ = cKDTree(sp.points).query(sp.points, k=2)
    assert nn[:, 1].mean() > h / 4


def test_a_flat_square_is_one_grid():
    """Two triangles of a 30 mm square at h = 10 mm: n = ⌈42.4/10⌉ = 5 per face, the shared
    diagonal merged: the 6 × 6 grid of 6 mm, each point once."""
    v = np.array([[0.7, 0.0, 0.0], [0.7, 0.03, 0.0], [0.7, 0.03, 0.03], [0.7, 0.0, 0.03]])
    part = make_part(v, [[0, 2, 1], [0, 3, 2]])
    sp = surface_points(part, resolution=0.01)
    assert len(sp) == 36
    grid = np.round(sp.points[:, 1:] / 0.006).astype(int)
    assert sorted(map(tuple, grid)) == [(i, j) for i in range(6) for j in range(6)]
    assert sp.area == pytest.approx(0.03 ** 2, rel=1e-14)


def test_resolution_and_size_rules(monkeypatch):
    v = np.array([[0.7, 0.0, 0.0], [0.7, 0.03, 0.0], [0.7, 0.0, 0.03]])
    part = make_part(v, [[0, 2, 1]])
    for bad in (0.0, -1.0, math.nan, True, "1"):
        with pytest.raises(MeshError, match="resolution .* must be a number > 0"):
            surface_points(part, resolution=bad)
    with pytest.raises(MeshError, match="need a resolution"):
        surface_points(part)
    with pytest.raises(MeshError, match="faces = 'front'"):
        surface_points(part, 0.01, faces="front")
    monkeypatch.setattr(fp_module, "MAX_POINTS", 100)
    with pytest.raises(MeshError, match="film points at resolution 0.001 m, more than 100"):
        surface_points(part, 0.001)
    # subdivisions past an int64: counted in floats, refused, not wrapped round to a few
    with warnings.catch_warnings():  # and no RuntimeWarning on the way
        warnings.simplefilter("error")
        with pytest.raises(MeshError, match="inf film points at resolution 1e-300 m"):
            surface_points(part, 1e-300)


def test_the_budget_checked_before_planning_is_the_painted_points(part, monkeypatch):
    """check_film_points (run before a plan) refuses exactly when building the painted
    faces' points would: the same count, at the threshold and on both sides of it."""
    def refuses(fn) -> bool:
        try:
            fn()
        except MeshError:
            return True
        return False

    monkeypatch.setattr(fp_module, "MAX_POINTS", 1)
    with pytest.raises(MeshError) as info:
        surface_points(part, 0.004, faces="painted")
    count = int(float(str(info.value).split(": ")[1].split(" film")[0]))  # e.g. 1.152e+04
    for budget in (count // 2, count - 100, count + 100, 2 * count):
        monkeypatch.setattr(fp_module, "MAX_POINTS", budget)
        built = refuses(lambda: surface_points(part, 0.004, faces="painted"))
        assert refuses(lambda: fp_module.check_film_points(part, 0.004)) == built
        assert built == (budget < count - 50)


def test_strips_cover_each_face_within_the_spacing():
    """A sliver 0.76 m long and 13 mm wide and a right triangle 0.1 m a side cut in strips:
    the shares sum to 1 (achieved ~1e-16), every point lies inside its triangle, every point
    of the triangle within the spacing of a strip point, linear and quadratic functions
    integrate to O(spacing²), and the sliver takes m·k = 77 × 2 points where the lattice
    would take (m + 1)(m + 2)/2 = 3081."""
    tri = np.array([[[0.0, 0.0, 0.0], [0.76, 0.0, 0.0], [0.76, 0.013, 0.0]],
                    [[0.0, 0.0, 0.0], [0.1, 0.0, 0.0], [0.0, 0.1, 0.0]]])
    area = np.array([0.5 * 0.76 * 0.013, 0.5 * 0.1 * 0.1])
    for spacing in (0.01, 0.005):
        at, owner, share = fp_module.strips(tri, spacing)
        np.testing.assert_allclose(np.bincount(owner, weights=share), 1.0, rtol=1e-13)
        assert (share > 0).all() and (np.abs(at[:, 2]) == 0).all()
        for f in (0, 1):
            inside = trimesh.triangles.points_to_barycentric(
                np.repeat(tri[f:f + 1], np.count_nonzero(owner == f), axis=0), at[owner == f])
            assert inside.min() > 0
            rng = np.random.default_rng(f)
            r = rng.random((4000, 2))
            r = np.where(r.sum(axis=1, keepdims=True) > 1, 1 - r, r)
            x = tri[f, 0] + r[:, :1] * (tri[f, 1] - tri[f, 0]) + r[:, 1:] * (tri[f, 2] - tri[f, 0])
            dist, _ = cKDTree(at[owner == f]).query(x)
            assert dist.max() < spacing
            # a linear function: the trapezoid rule on u·f(u), to O((spacing / longest)²)
            lin = share[owner == f] @ (at[owner == f] @ [0.3, -1.7, 0.0])
            want = tri[f].mean(axis=0) @ [0.3, -1.7, 0.0]
            longest = np.linalg.norm(tri[f] - np.roll(tri[f], -1, axis=0), axis=1).max()
            assert 0 < abs(lin / want - 1) < 2 * (spacing / longest) ** 2  # 1.3×, 0.5× it
        quad = (share[owner == 1] * area[1]) @ at[owner == 1, 0] ** 2  # ∫x² = 0.1⁴/12
        assert 0 < abs(quad / (0.1 ** 4 / 12) - 1) < 2 * (spacing / 0.1) ** 2
    # m = ⌈76.01⌉, k = ⌈1.3⌉
    assert np.count_nonzero(fp_module.strips(tri[:1], 0.01)[1] == 0) == 77 * 2


def test_coarse_faces_take_strip_points():
    """surface_points with ``coarse``: the lattice faces keep their points exactly; the
    coarse ones get their strip points, their areas summing to the faces' (~1e-16, asserted
    1e-13); the sliver has a few hundred points where the lattice gives it 52,901."""
    v = np.array([[0.7, 0.0, 0.0], [0.7, 0.76, 0.0], [0.7, 0.76, 0.12], [0.7, 0.0, 0.12],
                  [0.713, 0.0, 0.12], [0.713, 0.76, 0.12]])
    # the front (two faces, facing −x) and its top edge, a sliver 13 mm wide (facing +z)
    part = make_part(v, [[0, 2, 1], [0, 3, 2], [3, 5, 2], [3, 4, 5]], facing=(-1.0, 0.0, 0.0),
                     max_angle=45.0)
    front, top = part.painted, ~part.painted
    h = SIGMA / 3
    fine = surface_points(part, h, faces="all")
    sp = surface_points(part, h, faces="all", coarse=(top, SIGMA))
    on_f, on_c = front[fine.faces], front[sp.faces]
    np.testing.assert_array_equal(sp.points[on_c], fine.points[on_f])
    np.testing.assert_array_equal(sp.areas[on_c], fine.areas[on_f])
    assert abs(sp.areas[~on_c].sum() / part.areas[top].sum() - 1) < 1e-13
    assert np.count_nonzero(~on_f) > 50_000 and np.count_nonzero(~on_c) < 1000
    assert (np.abs(sp.points[~on_c, 2] - 0.12) < 1e-15).all()
    with pytest.raises(MeshError, match="coarse film point spacing 0.001 m must be at least"):
        surface_points(part, h, faces="all", coarse=(top, 0.001))
