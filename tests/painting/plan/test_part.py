"""The surface planner (paint/plan/part.py): its program is exact and C², a flat mesh paints
as the panel planner does."""
import numpy as np

from pollard_pin.analytic.taskspace import rotation
from pollard_pin.painting.film.mesh import mesh_film
from pollard_pin.painting.film.points import SurfacePoints
from pollard_pin.painting.spray.deposition import gun_of
from pollard_pin.painting.workpiece.mesh import panel_part


def test_program_is_c2_with_exact_derivatives(curved_plan):
    plan = curved_plan
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


def test_flat_mesh_paints_as_the_panel(plan, film, panel_part_plan):
    """The example panel as a two-triangle mesh: the surface planner's film on the panel
    planner's grid matches the panel planner's (same passes; the surface passes run on 3σ
    past the edges, the panel's 4σ: Φ(−3) = 0.13 % at the side edges)."""
    job = plan.job
    sp = panel_part_plan  # the panel as two triangles (panel_part), by the surface planner
    part, pj = sp.part, sp.job
    assert pj.mesh == "<panel>" and np.array_equal(part.vertices, panel_part(job).vertices)
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
