"""Shadows: the spray-spot pairs and their visibility against a brute-force segment–triangle
test (Möller–Trumbore over every face, float64), with Embree and with trimesh's numpy
intersector."""
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest
import trimesh
from trimesh.ray.ray_triangle import RayMeshIntersector

from pollard_pin.painting.film.mesh import mesh_film
from pollard_pin.painting.film.points import surface_points
from pollard_pin.painting.spray.deposition import Gun
from pollard_pin.painting.spray.occlusion import SPOT_SIGMAS, occlusion, offset
from pollard_pin.painting.workpiece import shapes
from pollard_pin.painting.workpiece.mesh import make_part

GUN = Gun(standoff=0.15, sigma=0.010, flow=1.5e-7)
X0, ZC = shapes.FRONT_X, shapes.CENTRE_Z


@pytest.fixture(scope="module")
def rib_part():
    m = shapes.ribbed_plate(width=0.08, height=0.04, step=0.01)
    return make_part(m.vertices, m.faces, source="rib")


def _gun_pass(z=shapes.CENTRE_Z, y0=-0.05, y1=0.05, step=0.004, tilt_deg=0.0):
    """Tips at the standoff in front of the plate along y, the axis +x turned about z."""
    y = np.arange(y0, y1 + 1e-12, step)
    p = np.column_stack([np.full(len(y), shapes.FRONT_X - GUN.standoff), y,
                         np.full(len(y), z)])
    t = np.radians(tilt_deg)
    a = np.tile([np.cos(t), np.sin(t), 0.0], (len(y), 1))
    return p, a


def _segment_blocked(o, e, tri):
    """Möller–Trumbore: does the segment o → e (K, 3) cross any triangle (F, 3, 3)?"""
    blocked = np.zeros(len(o), dtype=bool)
    v0, e1, e2 = tri[:, 0], tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    for k in range(len(o)):
        d = e[k] - o[k]
        pv = np.cross(d, e2)
        det = np.einsum("ij,ij->i", e1, pv)
        ok = np.abs(det) > 1e-300
        inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
        tv = o[k] - v0
        u = np.einsum("ij,ij->i", tv, pv) * inv
        qv = np.cross(tv, e1)
        v = (qv @ d) * inv
        t = np.einsum("ij,ij->i", e2, qv) * inv
        blocked[k] = np.any(ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0) & (t < 1))
    return blocked


def test_spot_pairs_are_the_spot(rib_part):
    """For a point at the standoff facing the gun, the pairs tested are those within 5σ of
    the spray axis, and only those."""
    y = np.linspace(-0.06, 0.06, 240)  # no point on the spot's edge
    s = np.column_stack([np.full(len(y), X0), y, np.full(len(y), ZC)])
    p, a = _gun_pass(z=ZC, y0=0.0, y1=0.0)
    occ = occlusion(rib_part, GUN, p, a, s, [-1.0, 0.0, 0.0])
    assert sorted(occ.point) == list(np.flatnonzero(np.abs(y) < SPOT_SIGMAS * GUN.sigma))


@pytest.mark.parametrize("engine", ["default", "numpy"])
def test_visibility_matches_brute_force(rib_part, engine):
    """Random points on every face of a ribbed plate (a 15 mm rib), a gun pass across it
    spraying straight and 25° askew: identical verdicts on every pair in the spot."""
    rng = np.random.default_rng(7)
    s, fi = trimesh.sample.sample_surface(rib_part.mesh, 600, seed=rng)
    n = rib_part.normals[fi]
    eng = None if engine == "default" else RayMeshIntersector(rib_part.mesh)
    tri = rib_part.vertices[rib_part.faces]
    total = shaded = 0
    for tilt in (0.0, 25.0):
        p, a = _gun_pass(tilt_deg=tilt)
        occ = occlusion(rib_part, GUN, p, a, s, n, intersector=eng)
        o = s[occ.point] + offset(rib_part) * n[occ.point]
        want = ~_segment_blocked(o, p[occ.sample], tri)
        assert np.array_equal(occ.visible, want), np.flatnonzero(occ.visible != want)[:10]
        total, shaded = total + len(want), shaded + int((~want).sum())
    # the rib shades a real share of the pairs, not all of them
    assert total > 5000 and 0.02 * total < shaded < 0.5 * total, (total, shaded)


def test_a_flat_part_shades_nothing():
    v = np.array([[0.7, -0.05, 0.1], [0.7, 0.05, 0.1], [0.7, 0.05, 0.2], [0.7, -0.05, 0.2]])
    part = make_part(v, [[0, 2, 1], [0, 3, 2]])
    g = np.meshgrid(np.linspace(-0.05, 0.05, 21), np.linspace(0.1, 0.2, 21))
    s = np.column_stack([np.full(g[0].size, 0.7), g[0].ravel(), g[1].ravel()])
    p, a = _gun_pass(z=0.15)
    occ = occlusion(part, GUN, p, a, s, [-1.0, 0.0, 0.0])
    assert len(occ.visible) > 1000 and occ.visible.all()


def test_without_embree_the_numpy_intersector_gives_the_same_film():
    """embreex hidden: Part.mesh.ray is trimesh's numpy intersector, and the film on the
    ribbed example part is the same as with Embree: to 1e-3 of its largest value (achieved
    4.6e-4, at the foot of the rib's wall: the shadow's edge there is the gun crossing the
    wall's plane, and the rays bisecting it graze the wall, which Embree's float32 resolves
    to ~1e-7 m; docs/model.md §23). The shaded pairs at the samples are the same."""
    code = (
        "import sys; sys.modules['embreex'] = None\n"
        "import numpy as np, trimesh\n"
        "from pollard_pin.painting.workpiece import shapes\n"
        "from pollard_pin.painting.spray.deposition import Gun\n"
        "from pollard_pin.painting.film.points import surface_points\n"
        "from pollard_pin.painting.workpiece.mesh import make_part\n"
        "from pollard_pin.painting.film.mesh import mesh_film\n"
        "m = shapes.ribbed_plate(width=0.08, height=0.04, step=0.01)\n"
        "part = make_part(m.vertices, m.faces)\n"
        "print(type(part.mesh.ray).__module__)\n"
        "y = np.arange(-0.05, 0.05, 0.0025)\n"
        "p = np.column_stack([np.full(len(y), 0.55), y, np.full(len(y), 0.16)])\n"
        "a = np.tile([1.0, 0, 0], (len(y), 1))\n"
        "f = mesh_film(Gun(0.15, 0.01, 1.5e-7), np.arange(len(y)) * 0.01, p, a,\n"
        "              surface_points(part, 0.004), part)\n"
        "np.save(sys.argv[1], f.thickness); print(f.shaded)\n")
    root = Path(__file__).resolve().parents[3]
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "film.npy"
        r = subprocess.run([sys.executable, "-c", code, str(out)], cwd=root,
                           capture_output=True, text=True, timeout=120)
        assert r.returncode == 0, r.stderr
        module, shaded = r.stdout.split()
        slow = np.load(out)
    assert module == "trimesh.ray.ray_triangle" and int(shaded) > 0
    m = shapes.ribbed_plate(width=0.08, height=0.04, step=0.01)
    part = make_part(m.vertices, m.faces)
    assert type(part.mesh.ray).__module__ == "trimesh.ray.ray_pyembree"
    y = np.arange(-0.05, 0.05, 0.0025)
    p = np.column_stack([np.full(len(y), 0.55), y, np.full(len(y), 0.16)])
    fast = mesh_film(GUN, np.arange(len(y)) * 0.01, p, np.tile([1.0, 0, 0], (len(y), 1)),
                     surface_points(part, 0.004), part)
    assert fast.shaded == int(shaded)
    assert np.abs(fast.thickness - slow).max() < 1e-3 * slow.max()


def test_without_any_ray_engine_paint_says_what_to_install(tmp_path):
    """embreex and rtree both hidden: trimesh's numpy intersector would fail inside its first
    query; paint on a part is one line naming what to install, and writes nothing."""
    root = Path(__file__).resolve().parents[3]
    code = ("import sys; sys.modules['embreex'] = None; sys.modules['rtree'] = None\n"
            "from pollard_pin.cli import main\n"
            "sys.exit(main(sys.argv[1:]))\n")
    out = tmp_path / "out"
    r = subprocess.run([sys.executable, "-c", code, "paint", "--job",
                        str(root / "examples/parts/ribbed_plate.toml"), "--out", str(out)],
                       cwd=root, capture_output=True, text=True, timeout=300)
    lines = r.stderr.strip().splitlines()
    assert r.returncode == 2 and len(lines) == 1, r.stderr
    assert "neither is installed: pip install rtree" in lines[0]
    assert not out.exists()


def _slab(x0, x1, half=0.05):
    return trimesh.creation.box(bounds=[[x0, -half, 0.11], [x1, half, 0.21]])


def test_faces_the_gun_cannot_see_are_not_painted():
    """A closed slab in front (x 0.60–0.61) and one behind it (0.70–0.71), both 0.10 m
    square: the back slab's face towards the robot (an open box's inside far wall) lies
    wholly behind the front slab, so by hand only the front slab's two −x triangles are
    seen at 0.15 m standoff; the normals alone chose four."""
    from pollard_pin.painting.spray.occlusion import painted_part, seen_faces

    m = trimesh.util.concatenate([_slab(0.60, 0.61), _slab(0.70, 0.71)])
    part = make_part(m.vertices, m.faces)
    facing = part.normals @ [-1.0, 0.0, 0.0] > 0.99
    front = part.vertices[part.faces].mean(axis=1)[:, 0] < 0.65
    assert np.array_equal(part.painted, facing) and facing.sum() == 4
    seen = seen_faces(part, 0.15)
    assert np.array_equal(seen, facing & front)
    assert np.array_equal(painted_part(part, 0.15).painted, facing & front)
    # the two slabs side by side: nothing hides either
    side = trimesh.util.concatenate([_slab(0.60, 0.61), _slab(0.70, 0.71).apply_translation(
        [0.0, 0.2, 0.0])])
    part = make_part(side.vertices, side.faces)
    assert np.array_equal(seen_faces(part, 0.15), part.painted)


def test_a_wall_deeper_than_the_standoff_behind_the_front_is_not_painted():
    """A drawer's front (x 0.60–0.61, 0.4 × 0.1 m) and, 0.39 m behind it, its box's back wall
    (x 1.00–1.01), both facing the robot: the wall's −x face lies wholly behind the front but
    further behind it than the 0.15 m standoff, so a nozzle at the standoff alone sees it
    (nothing between); the gun would stand inside the drawer. The ray runs on out of the part's
    box and meets the front: only the front's two −x triangles are painted."""
    from pollard_pin.painting.spray.occlusion import painted_part, seen_faces, visible

    m = trimesh.util.concatenate([_slab(0.60, 0.61, half=0.2), _slab(1.00, 1.01, half=0.2)])
    part = make_part(m.vertices, m.faces)
    centre = part.vertices[part.faces].mean(axis=1)
    facing = part.normals @ [-1.0, 0.0, 0.0] > 0.99
    front, wall = facing & (centre[:, 0] < 0.65), facing & (centre[:, 0] > 0.95)
    assert front.sum() == 2 and wall.sum() == 2 and np.array_equal(part.painted, front | wall)
    at_standoff = visible(part, centre[wall] + 0.15 * part.normals[wall], centre[wall],
                          part.normals[wall])
    assert at_standoff.all()  # the standoff point lies between the two: not enough
    assert np.array_equal(seen_faces(part, 0.15), front)
    assert np.array_equal(painted_part(part, 0.15).painted, front)
    assert painted_part(part, 0.15).painted_area == pytest.approx(0.4 * 0.1, rel=1e-12)


def test_a_part_wholly_hidden_is_one_line():
    """The slab behind a sheet turned away from the robot (normal +x, not painted itself):
    every face towards the robot is hidden."""
    from pollard_pin.painting.errors import MeshError
    from pollard_pin.painting.spray.occlusion import painted_part

    slab = _slab(0.70, 0.71)
    sheet = np.array([[0.60, -0.2, 0.0], [0.60, 0.2, 0.0], [0.60, 0.2, 0.4], [0.60, -0.2, 0.4]])
    v = np.vstack([slab.vertices, sheet])
    k = len(slab.vertices)
    f = np.vstack([slab.faces, [[k, k + 1, k + 2], [k, k + 2, k + 3]]])
    part = make_part(v, f)
    assert part.normals[-1] @ [1.0, 0, 0] > 0.99 and part.painted.sum() == 2
    with pytest.raises(MeshError) as exc:
        painted_part(part, 0.15)
    msg = str(exc.value)
    assert "all 2 faces within 45° of facing are hidden" in msg and "\n" not in msg, msg
    assert len(msg) <= 250


def test_open_pairs_are_lit_and_need_no_ray(rib_part):
    """Random points on every face of the ribbed plate, a gun pass straight and 25° askew:
    every pair open_pairs calls lit is lit by the brute-force segment test, it marks some
    pairs (the rib's top and the plate's back, which the part lies behind) and not the
    plate's front beside the rib; visible with the points' faces gives every verdict of
    visible without them."""
    from pollard_pin.painting.spray.occlusion import open_pairs, visible

    rng = np.random.default_rng(11)
    s, fi = trimesh.sample.sample_surface(rib_part.mesh, 600, seed=rng)
    n = rib_part.normals[fi]
    tri = rib_part.vertices[rib_part.faces]
    marked = 0
    for tilt in (0.0, 25.0):
        p, a = _gun_pass(tilt_deg=tilt)
        k, q = np.divmod(np.arange(len(p) * len(s)), len(s))
        height = np.einsum("ij,ij->i", p[k] - s[q], n[q])
        sure = open_pairs(rib_part, fi[q], height)
        grid = open_pairs(rib_part, fi, (p @ n.T) - np.einsum("ij,ij->i", s, n))
        assert np.array_equal(grid.ravel(), sure)  # one rule, pair by pair or every pair
        o = s[q[sure]] + offset(rib_part) * n[q[sure]]
        assert not _segment_blocked(o, p[k[sure]], tri).any()
        assert np.array_equal(visible(rib_part, p[k], s[q], n[q], faces=fi[q]),
                              visible(rib_part, p[k], s[q], n[q]))
        marked += int(sure.sum())
        assert not sure[rib_part.rise[fi[q]] > 1e-3].any()
    assert marked > 1000


def test_a_box_opens_every_pair_facing_the_gun():
    """A closed slab (convex): every pair whose nozzle lies in front of the point's face
    by more than offset/2 is open, those behind are not."""
    from pollard_pin.painting.spray.occlusion import open_pairs

    m = _slab(0.60, 0.61)
    part = make_part(m.vertices, m.faces)
    assert np.all(np.abs(part.rise) < 1e-15)
    faces = np.arange(len(part.faces))
    eps = offset(part)
    got = open_pairs(part, faces, np.array([[eps], [0.49 * eps], [-1.0]]) * np.ones(len(faces)))
    assert got[0].all() and not got[1:].any()
