"""The raster planner (docs/model.md §21): the example's plan against independent checks,
and one test per way a job can fail."""
import math
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from pollard_pin.dynamics.motors import load_actuators, motor_load_of
from pollard_pin.paint.errors import PlanError
from pollard_pin.paint.film import film_resolution, film_stats, plan_film
from pollard_pin.paint.job import load_job
from pollard_pin.paint.plan import plan_paint
from pollard_pin.paint.raster import (
    SPOT_RADIUS,
    _turn_u,
    cross_profile,
    pass_offsets,
    ripple_spacing,
)
from pollard_pin.run import run_pipeline

ROOT = Path(__file__).resolve().parents[2]
NAIVE_CYCLE = 17.3  # s: the constant-speed raster with slow semicircle turns


@pytest.fixture(scope="module")
def act():
    return load_actuators(ROOT / "examples" / "actuators.toml")


@pytest.fixture(scope="module")
def job():
    return load_job(ROOT / "examples" / "paint.toml")


@pytest.fixture(scope="module")
def plan(robot, job, act):
    return plan_paint(robot, job, act)


@pytest.fixture(scope="module")
def film(plan):
    return plan_film(plan)


def test_film_within_two_percent_edges_included(plan, film, job):
    """Issue target ±2 %; the layout allows 1 % and the film achieves −0.81 % / +0.50 %."""
    U, V, _, f = film
    assert U[0] == -job.width / 2 and U[-1] == job.width / 2  # edges on the grid
    assert V[0] == -job.height / 2 and V[-1] == job.height / 2
    step = job.sigma / 3 * (1 + 1e-12)  # σ/3, to round-off
    assert np.diff(U).max() <= step and np.diff(V).max() <= step
    st = film_stats(f.thickness, job.thickness)
    assert -0.02 <= st["deviation_min"] and st["deviation_max"] <= 0.02
    assert st["within_10pct"] == 1.0
    assert f.error_estimate.max() < 1e-3 * job.thickness  # the integration's 0.1 %


def test_interior_film_is_flow_over_speed_times_spacing(plan, film, job):
    """Away from the edges the film is flow/(speed·spacing) within the ripple bound."""
    U, V, _, f = film
    th = f.thickness.reshape(len(V), len(U))
    inner = th[np.abs(V) < job.height / 4][:, np.abs(U) < job.width / 4]
    expected = job.flow * plan.coats / (plan.speed * plan.spacing)
    assert expected == pytest.approx(job.thickness, rel=1e-12)
    # the spacing rule's ripple, 2·exp(−2π²σ²/Δ²) = 0.5 % (leading Poisson term)
    assert np.abs(inner / expected - 1).max() < 0.0051


def test_cycle_beats_the_naive_raster(plan):
    assert plan.cycle_time < 0.7 * NAIVE_CYCLE
    assert plan.cycle_time > plan.lower_bound


def test_exact_derivatives_rest_to_rest_and_c2(plan):
    tr = plan.trajectory
    seg = plan.segments
    h = 1e-5  # s: central differences of the path itself, inside the pieces
    t = np.clip(tr.t, h, seg.total - h)
    plus, minus = (np.array(seg.evaluate(t + s)) for s in (h, -h))
    mid = np.array(seg.evaluate(t))
    fd, fdd = (plus[:2] - minus[:2]) / (2 * h), (plus[2:4] - minus[2:4]) / (2 * h)
    # achieved 6e-8 m/s and 5e-6 m/s² (h²·jerk/6, h²·snap/6 in the 23 ms ramps)
    assert np.abs(fd - mid[2:4]).max() < 6e-6
    assert np.abs(fdd - mid[4:6]).max() < 5e-4
    speeds = np.linalg.norm(tr.d_poses[:, :3], axis=1)
    assert np.abs(speeds - np.hypot(*seg.evaluate(tr.t)[2:4])).max() < 1e-15
    assert np.abs(tr.d_poses[[0, -1]]).max() < 1e-12
    assert np.abs(tr.dd_poses[[0, -1]]).max() < 1e-12
    seg = plan.segments
    b = seg.start[1:]
    before, after = (np.array(seg.evaluate(b + s)) for s in (-1e-10, 1e-10))
    # C²: position, rate, acceleration continuous at every piece boundary
    assert np.abs(before - after).max() < 1e-6
    assert np.ptp(tr.poses[:, 3:], axis=0).max() == 0  # the gun keeps its orientation


def test_constant_speed_while_the_spot_is_over_the_panel(plan, job):
    tr = plan.trajectory
    p = tr.poses[:, :3] - plan.frame.c - job.standoff * plan.frame.n
    U = p @ plan.frame.u
    over = np.abs(U) <= job.width / 2 + SPOT_RADIUS * job.sigma - 1e-9
    speed = np.linalg.norm(tr.d_poses[over, :3], axis=1)
    assert np.abs(speed / plan.speed - 1).max() < 1e-12


def test_run_solves_it_within_the_motors(robot, plan, act):
    """An independent replay: run's pipeline and the motor model on the written samples."""
    result = run_pipeline(robot, plan.trajectory)
    load = motor_load_of(robot, act, result.ik, result.dynamics)
    r = load.ratios()
    assert r["peak_torque"].max() <= 1.0 and r["speed"].max() <= 1.0
    assert r["peak_torque"].max() == pytest.approx(plan.ratios["peak_torque"].max(), abs=0.02)
    assert r["peak_torque"].max() > 0.9  # the turnarounds use the motors


def test_pass_layout_meets_its_tolerance():
    sigma = 0.01
    d = ripple_spacing(sigma, 0.005)
    off = pass_offsets(0.12, d, sigma, 0.01)
    y = np.linspace(-0.06, 0.06, 1201)
    assert np.abs(cross_profile(off, d, sigma, y) - 1).max() <= 0.01
    # one pass fewer breaks it
    fewer = (np.arange(len(off) - 1) - (len(off) - 2) / 2) * d
    assert np.abs(cross_profile(fewer, d, sigma, y) - 1).max() > 0.01
    # interior ripple: Poisson's 2·exp(−2π²σ²/Δ²) = 0.5 % at the chosen spacing
    many = (np.arange(41) - 20) * d
    mid = np.linspace(-d, d, 401)
    ripple = np.abs(cross_profile(many, d, sigma, mid) - 1).max()
    assert ripple == pytest.approx(0.005, rel=1e-3)


@pytest.mark.parametrize("m", [1, 2, 3])
def test_turn_shape_boundary_conditions(m):
    f = _turn_u(m)
    fd, fdd = f.deriv(), f.deriv(2)
    assert [f(0), f(1), fd(0), fd(1), fdd(0), fdd(1)] == pytest.approx([0, 0, 1, -1, 0, 0],
                                                                        abs=1e-13)


@pytest.mark.parametrize("change", [
    {"normal": (-math.cos(math.radians(15)), 0.0, -math.sin(math.radians(15)))},  # tilted
    {"normal": (-math.cos(0.1), -math.sin(0.1), 0.0), "width": 0.2, "height": 0.1},  # yawed
    {"direction": "vertical", "width": 0.16, "height": 0.10},
])
def test_other_panels(robot, job, act, change):
    """Tilted, yawed and vertical-pass panels: film within ±2 % (achieved ±0.8 %), the gun
    along −n, passes along the chosen direction."""
    j = replace(job, **change)
    p = plan_paint(robot, j, act)
    f = plan_film(p)[3]
    st = film_stats(f.thickness, j.thickness)
    assert -0.02 <= st["deviation_min"] and st["deviation_max"] <= 0.02
    a = p.frame.rotation[:, 0]
    assert a == pytest.approx(-np.asarray(j.normal), abs=1e-15)
    R = p.frame.rotation
    assert R.T @ R == pytest.approx(np.eye(3), abs=1e-15) and np.linalg.det(R) > 0
    passes = [i for i, k in enumerate(p.segments.kind) if k == "pass"]
    t = p.segments.start[passes[0]] + 0.5 * p.segments.duration[passes[0]]
    i = int(np.searchsorted(p.trajectory.t, t))
    along = p.frame.u if j.direction == "horizontal" else p.frame.v
    velocity = p.trajectory.d_poses[i, :3]
    assert abs(velocity @ along) == pytest.approx(p.speed, rel=1e-12)


# --- one test per way a job fails -------------------------------------------------------------
def test_out_of_reach_names_where_and_what_fits(robot, job, act):
    with pytest.raises(PlanError) as info:
        plan_paint(robot, replace(job, width=0.6), act)
    msg = str(info.value)
    assert "\n" not in msg
    for w in ("leaves the workspace", "panel (u, v) = (", "cannot reach",
              "the largest panel that fits at standoff 0.15 m"):
        assert w in msg
    # the panel it names plans, and one 5 % larger does not
    w, h = (float(x) for x in re.search(r"is ([\d.]+) × ([\d.]+) m", msg).groups())
    assert w / h == pytest.approx(0.6 / job.height, rel=0.02)
    plan_paint(robot, replace(job, width=w, height=h), act)
    with pytest.raises(PlanError):
        plan_paint(robot, replace(job, width=1.05 * w, height=1.05 * h), act)


def test_too_thin_a_film(robot, job, act):
    with pytest.raises(PlanError, match="the thinnest film per coat is"):
        plan_paint(robot, replace(job, thickness=3e-6), act)


def test_too_fast_a_speed(robot, job, act):
    with pytest.raises(PlanError, match="the motors allow .* m/s"):
        plan_paint(robot, replace(job, speed=3.0), act)


def test_too_wide_a_spacing(robot, job, act):
    with pytest.raises(PlanError, match=r"job\.spacing: spacing 0\.04 m is too wide"):
        plan_paint(robot, replace(job, spacing=0.04), act)
    # A speed that implies too wide a spacing names the speed (flow/(thickness·speed) = 0.2 m).
    with pytest.raises(PlanError, match=r"job\.speed: spacing 0\.2 m is too wide"):
        plan_paint(robot, replace(job, speed=job.flow / (job.thickness * 0.2)), act)


def test_inconsistent_speed_spacing_coats(robot, job, act):
    with pytest.raises(PlanError, match="not the target"):
        plan_paint(robot, replace(job, speed=0.3, spacing=0.015), act)


def test_motors_too_weak_to_hold_the_gun(robot, job, act):
    weak = replace(act, units=tuple(replace(u, peak_torque=1e-4, continuous_torque=1e-4)
                                    for u in act.units))
    with pytest.raises(PlanError, match="cannot hold the gun"):
        plan_paint(robot, job, weak)


@pytest.mark.parametrize("resolution", [0.0, -1.0, math.nan, math.inf, 0.0101, "0.005"])
def test_a_film_grid_coarser_than_the_spot_or_not_a_spacing(job, resolution):
    # coarser than σ, the grid would miss the ripple between passes (some 2σ apart)
    with pytest.raises(PlanError, match="must be > 0 and at most the spray spot's σ = 0.01 m"):
        film_resolution(job, resolution)


def test_film_resolution_default_and_limit(job):
    assert film_resolution(job) == job.sigma / 3 and film_resolution(job, job.sigma) == job.sigma


def test_coats_split_the_film(robot, job, act):
    p = plan_paint(robot, replace(job, coats=2, thickness=50e-6), act)
    assert p.coats == 2 and p.passes == 2 * len(p.offsets)
    assert p.speed == pytest.approx(job.flow * 2 / (50e-6 * p.spacing), rel=1e-12)


def test_film_integration_converged(plan, film, job):
    """The film of the written samples against the same path integrated at 4× the sampling
    (exact segment positions): the planner's 2 ms steps are converged far below the issue's
    0.1 % of the target (achieved 5e-11 relative); the a-posteriori estimate (achieved 1.4e-9
    of the target) bounds it."""
    from pollard_pin.paint.deposition import film as integrate
    from pollard_pin.paint.plan import gun_of
    from pollard_pin.paint.raster import task_motion

    U, V, pts, f = film
    pick = np.r_[0:len(U) * len(V):37, len(U) * len(V) - 1]  # a spread of points, a corner
    s = pts.reshape(-1, 3)[pick]
    seg = plan.segments
    t = np.linspace(0, seg.total, 4 * (len(plan.trajectory) - 1) + 1)
    poses = task_motion(plan.frame, job.standoff, *seg.evaluate(t))[0]
    axes = np.tile(-plan.frame.n, (len(t), 1))
    fine = integrate(gun_of(job), t, poses[:, :3], axes, s, plan.frame.n, origin=plan.frame.c)
    rel = np.abs(f.thickness[pick] / fine.thickness - 1).max()
    assert rel < 5e-9
    assert f.error_estimate.max() < 1.4e-7 * job.thickness
    assert f.error_estimate.max() > rel * f.thickness.min()


def test_breakaway_counted_at_rest(robot, plan, act):
    """At the rest-to-rest ends every motor must overcome Coulomb friction in either
    direction: utilisation (|τ/N + Jm·N·q̈| + c)/peak there, not sign(0) = 0 (exact)."""
    from pollard_pin.paint.motion import motion

    tr = plan.trajectory
    ends = [0, len(tr) - 1]
    m = motion(robot, act, tr.poses[ends], tr.d_poses[ends], tr.dd_poses[ends])
    ia = robot.actuated_v
    assert np.all(m.ik.v[:, ia] == 0)
    n, jm, c = (act.column(k) for k in ("gear_ratio", "rotor_inertia", "coulomb"))
    rest = m.tau / n + jm * n * m.ik.a[:, ia]
    expected = (np.abs(rest) + c) / act.column("peak_torque")
    assert m.torque_ratio == pytest.approx(expected, rel=1e-14)
