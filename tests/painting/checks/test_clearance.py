"""The gun body's clearance from the part (docs/model.md §25) against figures computed by
hand (a flat plate, the gun normal or parallel to it), a brute-force replay (trimesh's
closest point of every sphere centre) and the example plans."""
import math
from pathlib import Path

import numpy as np
import pytest
import trimesh

from pollard_pin.analytic.taskspace import angles_from_rotation, rotation
from pollard_pin.errors import InputError
from pollard_pin.painting.checks.clearance import (
    check_clearance,
    clearance_of,
    job_clearance,
    strided,
    surface_samples,
)
from pollard_pin.painting.errors import ClearanceError, JobError, PlanError
from pollard_pin.painting.job import job_from_dict, load_job
from pollard_pin.painting.plan.part import plan_surface
from pollard_pin.painting.spray.gun_body import GunBody
from pollard_pin.painting.workpiece import shapes
from pollard_pin.painting.workpiece.mesh import load_part

ROOT = Path(__file__).resolve().parents[3]
# The default body by hand (model/urdf.py's gun link, x1918 = 0.06 m): the nozzle, r 4 mm
# over 18 mm, sampled every 3.6 mm (ceil(18/4) = 5 steps); the box 22 × 30 mm over 42 mm,
# held by r = √(11² + 15²) mm, sampled every 14 mm (ceil(42/18.6) = 3 steps).
NOZZLE_SPHERE = math.hypot(0.004, 0.0018)
BODY_SPHERE = math.hypot(math.hypot(0.011, 0.015), 0.007)


def plate(size=0.4, x=0.7):
    """A square plate in the plane x = ``x``, facing −x, two triangles."""
    h = size / 2
    v = np.array([[x, -h, -h], [x, h, -h], [x, h, h], [x, -h, h]])
    return trimesh.Trimesh(v, [[0, 2, 1], [0, 3, 2]], process=False)


def poses_along(axis, tips):
    """Tool poses spraying along ``axis`` from ``tips`` (N, 3)."""
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    b = np.cross(a, [0.0, 0.0, 1.0])
    b = b / np.linalg.norm(b) if np.linalg.norm(b) > 1e-9 else np.array([0.0, 1.0, 0.0])
    R = np.column_stack([a, b, np.cross(a, b)])
    return np.column_stack([tips, np.tile(angles_from_rotation(R), (len(tips), 1))])


def test_a_flat_plate_normal_gun_is_the_standoff_less_the_front_sphere():
    s = 0.15
    tips = np.column_stack([np.full(50, 0.7 - s), np.linspace(-0.1, 0.1, 50), np.zeros(50)])
    c = clearance_of(plate(), poses_along([1, 0, 0], tips), np.arange(50.0))
    assert c.distance == pytest.approx(s - NOZZLE_SPHERE, abs=1e-9)  # achieves ~1e-16
    assert c.point[0] == pytest.approx(0.7, abs=1e-12)


def test_a_gun_parallel_to_the_plate_is_its_height_less_the_body_sphere():
    h = 0.03
    tips = np.column_stack([np.full(20, 0.7 - h), np.zeros(20), np.linspace(-0.05, 0.05, 20)])
    c = clearance_of(plate(), poses_along([0, 0, 1], tips), np.arange(20.0))
    assert c.distance == pytest.approx(h - BODY_SPHERE, abs=1e-9)  # achieves ~1e-17


def test_the_figure_against_a_brute_force_replay():
    mesh = load_part(ROOT / "examples" / "parts" / "ribbed_plate.obj").mesh
    rng = np.random.default_rng(3)
    n = 400
    tips = np.column_stack([rng.uniform(0.55, 0.66, n), rng.uniform(-0.1, 0.1, n),
                            rng.uniform(0.1, 0.2, n)])
    axes = np.array([1.0, 0.0, 0.0]) + rng.normal(scale=0.3, size=(n, 3))
    poses = np.vstack([poses_along(a, t[None]) for a, t in zip(axes, tips)])
    c = clearance_of(mesh, poses, np.arange(float(n)))
    offs, radii = GunBody().axis_points()
    ax = rotation(poses)[:, :, 0]
    centres = (tips[:, None] - offs[None, :, None] * ax[:, None]).reshape(-1, 3)
    _, dist, _ = trimesh.proximity.closest_point(mesh, centres)
    brute = (dist.reshape(n, -1) - radii).min()
    # never below the brute force; above it by no more than the stated bound
    assert c.distance >= brute - 1e-12
    assert c.distance - brute <= c.between


@pytest.mark.parametrize("mesh", [plate(), shapes.bent_plate(step=0.02)])
def test_surface_samples_cover_every_face_within_delta(mesh):
    from scipy.spatial import cKDTree

    pts, owner, delta = surface_samples(mesh.vertices, mesh.faces, 0.01)
    probe, face = trimesh.sample.sample_surface(mesh, 4000, seed=1)
    for f in np.unique(face)[:50]:  # within δ of a sample of its own face
        d, _ = cKDTree(pts[owner == f]).query(probe[face == f])
        assert d.max() <= delta  # achieves about delta / 2
    assert set(np.unique(owner)) == set(range(len(mesh.faces)))


def test_a_surface_index_made_once_measures_as_one_made_each_time():
    """least_distance given the mesh's SurfaceIndex (made once for several sets of spheres)
    answers exactly as made inside for each set, and against trimesh's closest point."""
    from pollard_pin.painting.checks.clearance import least_distance, surface_index

    mesh = shapes.bent_plate(step=0.02)
    index = surface_index(mesh)
    rng = np.random.default_rng(3)
    lo, hi = mesh.bounds
    for _ in range(3):
        centres = rng.uniform(lo - 0.05, hi + 0.05, (40, 3, 3))
        radii = np.array([0.002, 0.005, 0.01])
        own = least_distance(mesh, centres, radii)
        given = least_distance(mesh, centres, radii, index)
        assert own[:2] == given[:2] and np.array_equal(own[2], given[2]) and own[3] == given[3]
        _, dist, _ = trimesh.proximity.closest_point(mesh, centres.reshape(-1, 3))
        brute = float((dist.reshape(40, 3) - radii).min())
        assert given[0] - given[3] - 1e-12 <= brute <= given[0] + 1e-12


def test_distinct_rows_are_numpys_unique_rows():
    """distinct_rows (the index's distinct samples) gives np.unique(axis=0)'s rows in its
    order, on a part's surface samples (shared corners and edges repeated) and on rows that
    tie in their first columns, with −0.0 among them."""
    from pollard_pin.painting.checks.clearance import distinct_rows, surface_samples

    mesh = shapes.bent_plate(step=0.02)
    pts = surface_samples(mesh.vertices, mesh.faces)[0]
    rng = np.random.default_rng(5)
    ties = rng.integers(-2, 3, (3000, 3)).astype(float) * 0.5
    ties[rng.random(ties.shape) < 0.1] = -0.0
    for p in (pts, ties, pts[:1]):
        mine, theirs = distinct_rows(p), np.unique(p, axis=0)
        assert mine.shape == theirs.shape and np.array_equal(mine, theirs)
    assert len(distinct_rows(pts)) < len(pts)  # the case holds repeats


def test_a_surface_index_is_kept_by_the_meshs_content():
    """surface_index keeps the last meshes' indexes by content (a study measures every
    design against one part): a copy of a mesh gets the same index, a moved one its own,
    whose samples are the first's moved (as made afresh), and one made again after others
    pushed it out equals the first."""
    from pollard_pin.painting.checks import clearance

    mesh = shapes.bent_plate(step=0.02)
    first = clearance.surface_index(mesh)
    assert clearance.surface_index(mesh.copy()) is first
    moved = mesh.copy()
    moved.apply_translation([0.0, 0.0, 0.25])
    other = clearance.surface_index(moved)
    assert other is not first
    assert np.array_equal(other.samples, clearance._index(moved).samples)
    assert np.allclose(other.samples - first.samples, [0.0, 0.0, 0.25], atol=1e-15)
    for k in range(clearance._INDEXES_KEPT):
        clearance.surface_index(plate(0.1 + 0.05 * k))
    again = clearance.surface_index(mesh)
    assert again is not first and np.array_equal(again.samples, first.samples)
    assert again.delta == first.delta and np.array_equal(again.owner, first.owner)


def test_a_mesh_of_many_faces_is_sampled_at_its_vertices(monkeypatch):
    from pollard_pin.painting.checks import clearance

    monkeypatch.setattr(clearance, "MAX_SURFACE_POINTS", 10)
    mesh = plate()
    pts, owner, delta = surface_samples(mesh.vertices, mesh.faces)
    assert len(pts) == 6 and delta == pytest.approx(0.4 * math.sqrt(2), rel=1e-12)


def test_a_close_pass_is_refused_naming_the_place():
    s = 0.012
    tips = np.column_stack([np.full(10, 0.7 - s), np.linspace(-0.1, 0.1, 10), np.zeros(10)])
    with pytest.raises(ClearanceError) as e:
        check_clearance(plate(), poses_along([1, 0, 0], tips), np.arange(10.0),
                        where=lambda i: f"on pass {i}")
    msg = str(e.value)
    assert "comes 7.6 mm from the part" in msg and "(700, " in msg and "on pass" in msg
    assert "clearance 10 mm" in msg and len(msg) <= 250 and "\n" not in msg


def test_a_stride_takes_every_kth_sample_and_its_bound_holds():
    """PlannerPolicy.clearance_stride: the gun dips to 30 mm from the plate at sample 21 of
    41; every 4th sample (and the last) sees 20 and 24, never closer than every sample, and
    their bound between samples covers the dip; a refusal names the path's own sample."""
    assert strided(41, 4).tolist() == list(range(0, 41, 4))
    assert strided(42, 4).tolist() == [*range(0, 42, 4), 41] and strided(5, 1).tolist() == [
        0, 1, 2, 3, 4]
    k = np.arange(41)
    depth = 0.03 + 0.001 * np.abs(k - 21)  # the tip's distance from the plate [m]
    tips = np.column_stack([0.7 - depth, np.linspace(-0.1, 0.1, 41), np.zeros(41)])
    poses, t = poses_along([1, 0, 0], tips), 0.1 * k
    every = job_clearance(None, None, plate(), poses, t)
    fourth = job_clearance(None, None, plate(), poses, t, stride=4)
    assert every.sample == 21 and every.distance == pytest.approx(0.03 - NOZZLE_SPHERE,
                                                                    abs=1e-9)
    assert fourth.sample == 20 and fourth.time == t[20]
    assert fourth.distance == pytest.approx(0.031 - NOZZLE_SPHERE, abs=1e-9)
    assert fourth.distance - fourth.between <= every.distance < fourth.distance
    assert fourth.between > every.between  # chords 4 samples long
    with pytest.raises(ClearanceError, match="at sample 20; clearance 40 mm"):
        job = job_from_dict({"panel": {"center": [0.7, 0, 0], "normal": [-1, 0, 0],
                                       "width": 0.2, "height": 0.1},
                             "gun": {"standoff": 0.05, "sigma": 0.01, "flow": 1e-7,
                                     "clearance": 0.04},
                             "job": {"thickness": 2.5e-5}})
        job_clearance(None, job, plate(), poses, t, lambda i: f"at sample {i}", stride=4)


def asked_everywhere(known, at, way, limit, rows=None):
    """A stand-in for clearance.may_come_within that proves nothing: every sample asked."""
    return np.ones((len(way) if rows is None else len(rows),) + np.broadcast_shapes(
        np.shape(known)[1:], np.shape(limit)), bool)


def dip_path():
    """48 samples of a gun normal to the plate stepping 30 mm a sample towards and away from
    it: 40 mm off at sample 8 (between the coarse samples 0 and 16, 280 mm off), 50 mm at
    the coarse sample 32 (the ceiling of the bounded queries)."""
    k = np.arange(48)
    depth = np.minimum(0.04 + 0.03 * np.abs(k - 8), 0.05 + 0.03 * np.abs(k - 32))
    tips = np.column_stack([0.7 - depth, np.linspace(-0.05, 0.05, 48), np.zeros(48)])
    return poses_along([1, 0, 0], tips), 0.1 * k


def test_may_come_within_keeps_every_sample_within_the_limit():
    """Points walking about a fixed point: every sample whose distance is at most the limit
    is kept, from the distances at every 8th sample and the way travelled; some are left
    out; with half the way travelled one within the limit is lost."""
    from pollard_pin.painting.checks.clearance import may_come_within, travelled

    rng = np.random.default_rng(5)
    x = np.cumsum(rng.normal(scale=0.01, size=(203, 4, 3)), axis=0)  # 4 points, 203 samples
    d = np.linalg.norm(x - [0.05, 0.0, 0.0], axis=2)
    steps = np.linalg.norm(np.diff(x, axis=0), axis=2).max(axis=1)
    limit = np.quantile(d, 0.2, axis=0)  # each point's own
    keep = may_come_within(d[::8], np.arange(0, 203, 8), travelled(steps), limit)
    assert keep.shape == d.shape and keep[d <= limit].all()
    assert 0.2 < keep.mean() < 0.9  # some left out, each more than the limit away
    assert not may_come_within(d[::8], np.arange(0, 203, 8), travelled(steps) / 2,
                               limit)[d <= limit].all()


def test_may_come_within_is_its_bounds_formula_to_the_bit():
    """The bounds computed in place on the gathered rows: the same answer as the formula
    written out (the larger of the bounds from the coarse samples around each sample, the
    last one's alone), for one distance a sample and several, every row and some."""
    from pollard_pin.painting.checks.clearance import SLACK, may_come_within, travelled

    def formula(known, at, way, limit, rows=None):
        n = np.arange(len(way)) if rows is None else np.asarray(rows)
        i = np.searchsorted(at, n, side="right") - 1
        after = np.minimum(i + 1, len(at) - 1)
        shape = (-1,) + (1,) * (known.ndim - 1)
        low = known[i] - (way[n] - way[at[i]]).reshape(shape)
        later = known[after] - (way[at[after]] - way[n]).reshape(shape)
        low = np.where((i + 1 < len(at)).reshape(shape), np.maximum(low, later), low)
        return low <= np.asarray(limit, float) + SLACK

    rng = np.random.default_rng(11)
    way = travelled(rng.uniform(0.0, 0.01, 300))
    at = np.arange(0, 301, 16)
    for known, limit in ((rng.uniform(0.0, 0.2, len(at)), 0.08),
                         (rng.uniform(0.0, 0.2, (len(at), 7)), rng.uniform(0.0, 0.2, 7))):
        for rows in (None, np.sort(rng.choice(301, 90, replace=False))):
            got = may_come_within(known, at, way, limit, rows)
            want = formula(known, at, way, limit, rows)
            assert got.shape == want.shape and np.array_equal(got, want)
            assert 0.0 < want.mean() < 1.0  # both answers occur


def test_the_skip_answers_as_every_sample_asked(monkeypatch):
    """clearance_of asks the k-d tree only what the way travelled cannot prove past the
    bound (module notes): on a dip between coarse samples, a raster over the ribbed plate and
    random jumps, the Clearance (figure, sample, point, bound) is the one of every sphere
    asked, to the bit; a way half as long would miss the dip."""
    from pollard_pin.painting.checks import clearance

    rib = load_part(ROOT / "examples" / "parts" / "ribbed_plate.obj").mesh
    u = np.linspace(0.0, 6 * np.pi, 900)  # three strokes up and down across the rib
    raster = np.column_stack([0.58 + 0.01 * np.sin(5 * u), 0.1 * np.sin(u),
                              np.linspace(0.1, 0.2, 900)])
    rng = np.random.default_rng(3)
    jumps = np.column_stack([rng.uniform(0.55, 0.66, 300), rng.uniform(-0.1, 0.1, 300),
                             rng.uniform(0.1, 0.2, 300)])
    paths = [(plate(), *dip_path()),
             (rib, poses_along([1, 0, 0], raster), np.arange(900.0)),
             (rib, np.vstack([poses_along(a, t[None]) for a, t in zip(
                 [1.0, 0.0, 0.0] + rng.normal(scale=0.3, size=(300, 3)), jumps)]),
              np.arange(300.0)),
             # a slow sweep (0.6 mm a step, its least between coarse samples): the first
             # ceiling's bound is tight
             (plate(), poses_along([1, 0, 0], np.column_stack([
                 0.55 - 0.02 * np.cos(np.linspace(0.3, 6 * np.pi + 0.3, 600)),
                 np.linspace(-0.05, 0.05, 600), np.zeros(600)])), np.arange(600.0))]
    real, asked = clearance.may_come_within, []

    def counted(*args):
        keep = real(*args)
        asked.append(keep.mean())
        return keep

    for mesh, poses, t in paths:
        monkeypatch.setattr(clearance, "may_come_within", counted)
        skipped = clearance_of(mesh, poses, t)
        monkeypatch.setattr(clearance, "may_come_within", asked_everywhere)
        assert clearance_of(mesh, poses, t) == skipped
        with monkeypatch.context() as m:  # no way: every coarse sphere asked unbounded too
            m.setattr(clearance, "travelled", lambda steps: None)
            assert clearance_of(mesh, poses, t) == skipped
    assert asked[0] < 0.6 and asked[1] < 0.2  # the skip did skip (0.48, 0.06)
    monkeypatch.setattr(clearance, "may_come_within", real)
    dip = clearance_of(plate(), *dip_path())
    assert dip.sample == 8 and dip.distance == pytest.approx(0.04 - NOZZLE_SPHERE, abs=1e-9)
    way = clearance.travelled
    monkeypatch.setattr(clearance, "travelled", lambda steps: way(steps) / 2)
    assert clearance_of(plate(), *dip_path()).sample == 32  # the wrong bound is caught


def test_the_example_panel_and_line_keep_the_standoff_less_the_front_sphere(plan, line_plan):
    for p in (plan, line_plan):  # the gun normal to the panel: by hand
        assert p.clearance.distance == pytest.approx(p.job.standoff - NOZZLE_SPHERE,
                                                     abs=1e-9)  # achieves ~1e-16


def test_the_example_parts_clearance_pinned(ribbed_plan, line_part_plan):
    c = ribbed_plan.clearance  # examples/parts/ribbed_plate.toml
    # the rib's top edge (15 mm high) beside pass 2: standoff − rib − the nozzle's sphere
    # at the tip's offset from the edge; figure of this code, rel 1e-6 (its bound 3 mm)
    assert c.distance == pytest.approx(0.13227581686404988, rel=1e-6)
    assert c.point[0] == pytest.approx(0.685, abs=1e-9)
    assert line_part_plan.clearance.distance == pytest.approx(0.14384285944179728, rel=1e-6)
    assert line_part_plan.in_part_frame().clearance is line_part_plan.clearance


def test_a_tall_rib_is_refused_naming_the_pass(robot, act, tmp_path):
    shapes.ribbed_plate(rib_height=0.2, step=0.01).export(tmp_path / "rib.obj")
    text = (ROOT / "examples" / "parts" / "ribbed_plate.toml").read_text()
    (tmp_path / "rib.toml").write_text(text.replace("ribbed_plate.obj", "rib.obj"))
    with pytest.raises(ClearanceError) as e:
        plan_surface(robot, load_job(tmp_path / "rib.toml"), act)
    msg = str(e.value)
    assert "cuts" in msg and "into the part at (" in msg and "on pass 2 of" in msg
    assert len(msg) <= 250
    assert isinstance(e.value, PlanError)


def _job(**gun):
    return {"panel": {"center": [0.7, 0, 0.16], "normal": [-1, 0, 0], "width": 0.2,
                      "height": 0.1},
            "gun": {"standoff": 0.15, "sigma": 0.01, "flow": 1.5e-7, **gun},
            "job": {"thickness": 25e-6}}


def test_the_job_clearance_is_checked_once():
    assert job_from_dict(_job(clearance=0.02)).clearance == 0.02
    assert job_from_dict(_job()).clearance is None
    assert job_from_dict(_job(clearance=0.02)).to_dict()["gun"]["clearance"] == 0.02
    for bad in (-0.01, "1 cm", float("nan"), 20.0):
        with pytest.raises(JobError, match="gun.clearance"):
            job_from_dict(_job(clearance=bad))
    with pytest.raises(InputError, match="GunBody.radius"):
        GunBody(radius=-1.0)


def test_a_clearance_beyond_the_standoff_refuses_the_panel(robot, act):
    from pollard_pin.painting.plan.panel import plan_paint

    with pytest.raises(ClearanceError, match="comes 145.6 mm from the part"):
        plan_paint(robot, job_from_dict(_job(clearance=0.16)), act)
