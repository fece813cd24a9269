"""The surface planner (paint/surface_plan.py): its pieces are exact and C², a flat mesh paints
as the panel planner does, the curved example's film is within target and agrees with a
brute-force sum of the deposition model with a per-pair segment test for shade."""
import math
from pathlib import Path

import numpy as np
import pytest

from pollard_pin.analytic.taskspace import rotation
from pollard_pin.paint.deposition import gun_of
from pollard_pin.paint.film_points import SurfacePoints
from pollard_pin.paint.job import PartJob, load_job
from pollard_pin.paint.mesh import panel_part
from pollard_pin.paint.mesh_film import mesh_film
from pollard_pin.paint.stats import film_stats
from pollard_pin.paint.surface_plan import Quintic, gun_frame, plan_surface, surface_film

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def curved(robot, act):
    job = load_job(ROOT / "examples" / "parts" / "curved_panel.toml")
    plan = plan_surface(robot, job, act)
    return plan, surface_film(plan)


def test_quintic_meets_its_end_states():
    rng = np.random.default_rng(1)
    start, end = (tuple(rng.normal(size=(3, 6))), tuple(rng.normal(size=(3, 6))))
    q = Quintic("turn", start, end, 0.7)
    for tau, state in ((0.0, start), (0.7, end)):
        got = q.evaluate(np.array([tau]))
        for g, want in zip(got, state):
            assert np.abs(g[0] - want).max() < 1e-12
    # rates and accelerations are the derivatives (central differences, O(h²) ≈ 1e-8)
    tau, h = np.linspace(0.05, 0.65, 7), 1e-5
    p, d, dd = q.evaluate(tau)
    pp, dp, _ = q.evaluate(tau + h)
    pm, dm, _ = q.evaluate(tau - h)
    assert np.abs((pp - pm) / (2 * h) - d).max() < 1e-6
    assert np.abs((dp - dm) / (2 * h) - dd).max() < 1e-5


def test_gun_frame_sprays_along_the_axis():
    a = np.array([[1.0, 0.0, 0.0], [0.9, 0.3, -0.1]])
    a /= np.linalg.norm(a, axis=1, keepdims=True)
    R = gun_frame(a)
    assert np.abs(R[:, :, 0] - a).max() < 1e-15
    assert np.abs(np.einsum("kij,kil->kjl", R, R) - np.eye(3)).max() < 1e-14
    assert np.abs(np.linalg.det(R) - 1).max() < 1e-14


def test_program_is_c2_with_exact_derivatives(curved):
    plan, _ = curved
    prog = plan.program
    # across every piece boundary: pose, rate, acceleration continuous
    for b in prog.start[1:]:
        lo, hi = prog.evaluate(np.array([b - 1e-9])), prog.evaluate(np.array([b + 1e-9]))
        for x, y, tol in zip(lo, hi, (1e-8, 1e-6, 1e-3)):
            assert np.abs(x - y).max() < tol
    # the written rates and accelerations are the derivatives of the written poses
    tr = plan.trajectory
    t = np.linspace(0.01, prog.total - 0.01, 400)
    h = 1e-5
    p0, d0, dd0 = prog.evaluate(t)
    pp, dp, _ = prog.evaluate(t + h)
    pm, dm, _ = prog.evaluate(t - h)
    assert np.abs((pp - pm) / (2 * h) - d0).max() < 1e-5
    assert np.abs((dp - dm) / (2 * h) - dd0).max() < 1e-2
    assert np.all(tr.d_poses[[0, -1]] == 0) and np.all(tr.dd_poses[[0, -1]] == 0)


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


def test_flat_mesh_paints_as_the_panel(robot, act, plan, film):
    """The example panel as a two-triangle mesh: the surface planner's film on the panel
    planner's grid matches the panel planner's (same passes; the surface passes run on 3σ
    past the edges, the panel's 4σ: Φ(−3) = 0.13 % at the side edges)."""
    job = plan.job
    part = panel_part(job)
    pj = PartJob(mesh="<panel>", position=(0.0, 0.0, 0.0), standoff=job.standoff,
                 sigma=job.sigma, flow=job.flow, thickness=job.thickness, source="panel")
    sp = plan_surface(robot, pj, act, part)
    assert np.allclose(sorted(p.level for p in sp.layout.passes),
                       job.center[2] + np.sort(plan.offsets), atol=1e-9)
    U, V, grid, panel_film = film
    P = grid.reshape(-1, 3)
    zeros = np.zeros(len(P))
    points = SurfacePoints(P, np.tile(part.normals[0], (len(P), 1)), zeros + 1,
                           zeros.astype(int), np.arange(2), job.sigma / 3)
    tr = sp.trajectory
    mf = mesh_film(gun_of(pj), tr.t, tr.poses[:, :3], rotation(tr.poses)[:, :, 0], points,
                   part, sp.spray)
    rel = mf.thickness / panel_film.thickness - 1
    inner = np.abs(np.meshgrid(U, V)[0].ravel()) < job.width / 2 - 3 * job.sigma
    assert np.abs(rel).max() < 3e-3  # measured 1.45e-3 at the side edges (Φ(−3))
    assert np.abs(rel[inner]).max() < 1e-4  # measured 1.0e-6
