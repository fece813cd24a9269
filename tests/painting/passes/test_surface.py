"""Passes on a part's surface (paint/passes/surface.py): spacing held on the surface, the arc length
of a pass, the gun at the standoff along the normal, the smoothing where the surface turns."""
import math

import numpy as np
import pytest

from pollard_pin.painting.errors import PlanError
from pollard_pin.painting.job import PartJob
from pollard_pin.painting.passes.surface import EXTENSION, surface_layout
from pollard_pin.painting.workpiece import shapes
from pollard_pin.painting.workpiece.mesh import make_part

JOB = PartJob(mesh="<test>", position=(0.0, 0.0, 0.0), standoff=0.15, sigma=0.01, flow=1.5e-7,
              thickness=25e-6, source="test")


def plate(tilt_about_y=0.0, yaw=0.0, width=0.24, height=0.10):
    """A flat rectangle at x ≈ 0.7 facing −x, pitched by ``tilt_about_y`` and yawed by
    ``yaw`` (degrees) about its centre (0.7, 0, 0.16)."""
    u = np.array([-math.sin(math.radians(yaw)), math.cos(math.radians(yaw)), 0.0])
    v = np.array([math.sin(math.radians(tilt_about_y)), 0.0, math.cos(math.radians(tilt_about_y))])
    c = np.array([0.7, 0.0, 0.16])
    corners = [c - width / 2 * u - height / 2 * v, c + width / 2 * u - height / 2 * v,
               c + width / 2 * u + height / 2 * v, c - width / 2 * u + height / 2 * v]
    n = np.cross(corners[1] - corners[0], corners[2] - corners[0])
    faces = [[0, 1, 2], [0, 2, 3]] if n[0] < 0 else [[0, 2, 1], [0, 3, 2]]
    return make_part(np.array(corners), np.array(faces))


def lipped_plate(lip=0.0005, rise=0.006, width=0.24, height=0.10):
    """plate()'s rectangle (facing −x, centre (0.7, 0, 0.16)) with a lip ``lip`` wide along
    its top and bottom edges standing ``rise`` nearer the robot, its walls hidden from it
    (the edge of trimesh's featuretype.STL): narrower than a section sample, so only the
    section's end sample lies on it."""
    x, z0, y = 0.7, 0.16, width / 2
    profile = [(x - rise, z0 - height / 2), (x - rise, z0 - height / 2 + lip),
               (x, z0 - height / 2 + lip), (x, z0 + height / 2 - lip),
               (x - rise, z0 + height / 2 - lip), (x - rise, z0 + height / 2)]
    verts = np.array([(px, sy * y, pz) for px, pz in profile for sy in (-1.0, 1.0)])
    faces = []
    for k in range(len(profile) - 1):
        a, b, c, d = 2 * k, 2 * k + 1, 2 * k + 2, 2 * k + 3  # (−y, +y) at k, then k + 1
        faces += [[a, c, b], [b, c, d]]  # outward: −x on the flats, the walls away from them
    return make_part(verts, np.array(faces))


def test_outer_passes_keep_the_spacing_past_an_edge_lip():
    """Every adjacent pair of passes lies the spacing apart across the lipped plate (its
    faces all face the robot, so the surface distance is the step in z), the outer pair
    beyond the edges included; the film from Gaussians at those levels stays within the
    layout's 1 % over the plate. (The tangent from the section's last two samples took the
    lip's 6 mm wall for the slope: the outer passes 2.2 mm past the edges, 6.8 mm from
    their neighbours, +45 % film at the edges.)"""
    lay = surface_layout(lipped_plate(), JOB)
    levels = np.array([p.level for p in lay.passes])
    assert abs(lay.extent - 0.10) < 1e-9  # the walls add no arc
    assert levels[0] < 0.11 and levels[-1] > 0.21  # passes beyond both edges
    assert np.abs(np.diff(levels) / lay.spacing - 1).max() < 1e-6
    z = np.linspace(0.11, 0.21, 1001)
    film = lay.spacing / (math.sqrt(2 * math.pi) * JOB.sigma) * np.exp(
        -0.5 * ((z[:, None] - levels[None, :]) / JOB.sigma) ** 2).sum(1)
    assert np.abs(film - 1).max() < 0.011  # pass_offsets' tolerance


@pytest.mark.parametrize("tilt", [0.0, 30.0])
def test_spacing_is_held_on_the_surface(tilt):
    """A plate pitched by θ across the passes: the planes step by spacing·cos θ in z so the
    passes lie the spacing apart along the plate."""
    lay = surface_layout(plate(tilt_about_y=tilt), JOB)
    steps = np.diff([p.level for p in lay.passes])
    assert np.abs(steps / (lay.spacing * math.cos(math.radians(tilt))) - 1).max() < 1e-6
    assert abs(lay.extent - 0.10) < 1e-9  # the plate's height along its surface


def test_pass_length_is_the_arc_on_the_surface():
    """A yawed plate's passes are its width long (plus the run-on), not its projection."""
    lay = surface_layout(plate(yaw=25.0), JOB)
    for p in lay.passes:
        assert abs(p.length - (0.24 + 2 * EXTENSION * JOB.sigma)) < 2e-3  # one sample step
        assert np.abs(np.diff(p.s)).max() < 1.01e-3


def test_curved_panel_gun_along_the_normal():
    """On the convex example the gun stays at the standoff along the normal (averaged over
    a few facets only)."""
    mesh = shapes.curved_panel(radius=0.4, width=0.24, height=0.10)
    part = make_part(mesh.vertices, mesh.faces, max_angle=45.0)
    lay = surface_layout(part, JOB)
    assert lay.smoothing <= 0.006 and lay.incidence < 1.0
    for p in lay.passes:
        on = p.on_part
        # the tip is the standoff from the surface point, up to the averaging's chord sag
        gap = np.linalg.norm(p.tip[on] - p.surface[on], axis=1)
        assert np.abs(gap - JOB.standoff).max() < 2e-4
        # the surface point lies on the cylinder of radius 0.4 (facets: sag ≤ 1e-4 m)
        axis_x = 0.70 + 0.4
        r = np.hypot(p.surface[on, 0] - axis_x, p.surface[on, 1])
        assert np.abs(r - 0.4).max() < 2e-4


def test_fillet_tighter_than_the_standoff_is_smoothed():
    """The concave 30 mm fillet folds the normal offset (hκ = 5): the normal is averaged
    until the tip moves forwards everywhere, and the incidence that costs is reported."""
    mesh = shapes.bent_plate(flat=0.12, wing=0.11, angle_deg=30.0, fillet=0.030, height=0.10)
    part = make_part(mesh.vertices, mesh.faces, max_angle=45.0)
    lay = surface_layout(part, JOB)
    assert lay.smoothing >= 0.02
    assert 5.0 < lay.incidence < 30.0
    for p in lay.passes:
        step = np.diff(p.tip, axis=0)
        ahead = np.diff(p.tip + JOB.standoff * p.axis, axis=0)
        assert (np.einsum("ij,ij->i", step, ahead) > 0).all()


def test_rib_walls_add_no_arc():
    """A rib's walls are hidden along the pass: the pass is the plate's width long."""
    mesh = shapes.ribbed_plate(width=0.24, height=0.10, rib_height=0.015, rib_width=0.006,
                               step=0.01)
    part = make_part(mesh.vertices, mesh.faces, max_angle=45.0)
    lay = surface_layout(part, JOB)
    for p in lay.passes:
        assert abs(p.length - (0.24 + 2 * EXTENSION * JOB.sigma)) < 2e-3


def test_part_smaller_than_the_spot_names_the_units():
    small = plate(width=0.24e-3, height=0.10e-3)
    with pytest.raises(PlanError, match="read as millimetres"):
        surface_layout(small, JOB)


def test_passes_are_timed_by_the_spots_footprint():
    """Where the averaged gun looks off the normal (the fillet), a pass's arc parameter is
    where its spray axis meets the surface: that point lies on the axis line; on a flat plate
    the footprint is the normal's foot."""
    mesh = shapes.bent_plate(flat=0.12, wing=0.11, angle_deg=30.0, fillet=0.030, height=0.10)
    part = make_part(mesh.vertices, mesh.faces, max_angle=45.0)
    lay = surface_layout(part, JOB)
    p = lay.passes[3]
    assert (np.diff(p.s) > 0).all()
    # the foot arc of each sample: uniform, 1 mm apart; the footprint's arc differs
    foot = np.linspace(0.0, p.s[-1] - p.s[0], len(p.s))
    assert np.abs((p.s - p.s[0]) - foot).max() > 2e-4  # measured 0.43 mm
    inner = slice(20, -20)
    spot = np.column_stack([np.interp(p.s[inner], p.s[0] + foot, p.surface[:, k])
                            for k in range(3)])
    d = spot - p.tip[inner]
    off_axis = np.linalg.norm(d - np.einsum("ij,ij->i", d, p.axis[inner])[:, None]
                              * p.axis[inner], axis=1)
    assert off_axis.max() < 1e-4  # the polyline between 1 mm samples
    flat = surface_layout(plate(), JOB).passes[2]
    assert np.abs(np.diff(flat.s) - np.diff(flat.s).mean()).max() < 5e-8  # measured 4.4e-10


def test_a_spacing_far_too_fine_is_refused_before_planning():
    """0.10 m of surface at spacing 1e-5 m: (0.10/1e-5 + 1) = 1.0e4 passes > max_passes,
    refused with the figure (the cross profile of 1e4 passes took minutes)."""
    from dataclasses import replace

    from pollard_pin.painting.errors import BudgetError
    from pollard_pin.painting.policy import DEFAULT_POLICY, PlannerPolicy

    with pytest.raises(BudgetError) as exc:
        surface_layout(plate(), replace(JOB, spacing=1e-5))
    msg = str(exc.value)
    assert "1e+04 passes" in msg and f"budget {DEFAULT_POLICY.max_passes}" in msg, msg
    assert "\n" not in msg
    # the budget is the policy's: a smaller one refuses the job's own spacing
    with pytest.raises(BudgetError, match="budget 2: "):
        surface_layout(plate(), JOB, policy=PlannerPolicy(max_passes=2))


@pytest.mark.parametrize("facing", [(0.0, 0.0, 1.0), (0.0, 0.0, -1.0), (0.3, 0.0, -1.0)])
def test_a_horizontal_part_has_a_finite_frame(facing):
    """A table top: the frame refers to world x (z lies along the facing), orthonormal and
    right-handed (checked against numpy's cross product)."""
    from pollard_pin.painting.passes.surface import reference_axis, surface_frame

    n = np.asarray(facing) / np.linalg.norm(facing)
    v = np.array([[0.0, 0, 0], [0.1, 0, 0], [0, 0.1, 0]])
    tri = [[0, 1, 2]] if n[2] > 0 else [[0, 2, 1]]
    part = make_part(v + [0.6, 0, 0], np.array(tri), facing=n)
    f = surface_frame(part)
    assert np.array_equal(reference_axis(n), [1.0, 0.0, 0.0])
    basis = np.array([f.along, f.across, f.n])
    assert np.abs(basis @ basis.T - np.eye(3)).max() < 1e-12  # achieved ~1e-16
    assert np.abs(np.cross(f.n, f.across) - f.along).max() < 1e-12
    assert np.array_equal(reference_axis([-1.0, 0.0, 0.0]), [0.0, 0.0, 1.0])


@pytest.mark.parametrize("given, says", [
    # a flow in mm³/s read as m³/s: the pass speed flow/(thickness·spacing) 2.2e306 m/s
    ({"flow": 1e300}, "needs a gun speed of 2.222e+306 m/s (gun.flow 1e+300 m³/s, 1 coat(s) of "
                      "25 µm at spacing 18 mm), 2.22e+305 times the 10 m/s"),
    ({"thickness": 1e-300}, "needs a gun speed of 8.333e+294 m/s"),
    ({"speed": 1e300}, "needs a gun speed of 1e+300 m/s (job.speed)"),
])
def test_an_absurd_pass_speed_is_refused(given, says):
    """A pass speed no robot runs is one line naming it (was an OverflowError where the
    motors' check squares it, or the path's 'd_y absurd' far from the cause); the speed of
    the example's numbers is flow/(thickness·spacing)."""
    from types import SimpleNamespace

    from pollard_pin.painting.passes.surface import pass_speed

    job = SimpleNamespace(**{"coats": None, "speed": None, "flow": 1.5e-7, "thickness": 25e-6,
                             "source": "j.toml", **given})
    with pytest.raises(PlanError) as info:
        pass_speed(job, 0.018)
    assert str(info.value).startswith("j.toml: the target needs") and says in str(info.value)
    ok = SimpleNamespace(coats=2, speed=None, flow=1.5e-7, thickness=25e-6, source="j.toml")
    assert pass_speed(ok, 0.018) == pytest.approx(1.5e-7 * 2 / (25e-6 * 0.018), rel=1e-12)
    # 40 coats: 13.3 m/s, over the bound, but the film in one coat asks 0.33 m/s: too many
    # coats are the motors' to refuse (the panel's "at most N coat(s)"), not a unit slip
    many = SimpleNamespace(coats=40, speed=None, flow=1.5e-7, thickness=25e-6, source="j.toml")
    assert pass_speed(many, 0.018) == pytest.approx(40 * 1.5e-7 / (25e-6 * 0.018), rel=1e-12)
