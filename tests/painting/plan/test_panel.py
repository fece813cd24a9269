"""The raster planner (paint/plan/panel.py, docs/model.md §21): the example's plan against
independent checks (run's pipeline and the motor model on its samples, the film it leaves),
and one test per way a job can fail."""
import math
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import pollard_pin as pp
import pollard_pin.dynamics.inverse as inverse
from pollard_pin.dynamics.averages import time_rms
from pollard_pin.dynamics.motors import motor_load_of, motor_torque
from pollard_pin.painting.checks.motion import motion, reach
from pollard_pin.painting.errors import PlanError, ReachError
from pollard_pin.painting.film.grid import plan_film
from pollard_pin.painting.film.stats import film_stats
from pollard_pin.painting.passes.raster import SPOT_RADIUS
from pollard_pin.painting.plan import panel as planner
from pollard_pin.painting.plan.layout import panel_layout
from pollard_pin.painting.plan.panel import plan_paint
from pollard_pin.run import run_pipeline

NAIVE_CYCLE = 17.3  # s: a constant-speed raster with slow semicircle turns


def test_cycle_beats_the_naive_raster(plan):
    assert plan.cycle_time < 0.7 * NAIVE_CYCLE
    assert plan.cycle_time > plan.lower_bound


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


def test_coats_split_the_film(robot, job, act, plan, film):
    """Two coats of the example's film: twice the one-coat speed (the session's plan) over
    the same passes, there and back, and each coat lays half the film. The film of the 2-coat
    plan (integrated over its samples) is the target within ±2 % (achieved −0.81 % / +0.50 %,
    the layout's ripple and edges); split at the turnaround between the coats, each coat's
    film is half the 1-coat plan's, point by point, and the two add up to the 2-coat film
    (achieved 3.9e-6 relative: the turnarounds' spray tails, 4σ off the panel; asserted
    1e-3)."""
    from pollard_pin.analytic.taskspace import rotation
    from pollard_pin.painting.spray.deposition import film as integrate
    from pollard_pin.painting.spray.deposition import gun_of

    target, one = job.thickness, plan
    two = plan_paint(robot, replace(job, coats=2), act)
    assert two.coats == 2 and two.passes == 2 * len(two.offsets)
    assert np.array_equal(two.offsets, one.offsets) and two.spacing == one.spacing
    assert two.speed == pytest.approx(2 * one.speed, rel=1e-12)
    _, _, pts, f1 = film
    _, _, _, f2 = plan_film(two)
    st = film_stats(f2.thickness, target)
    assert -0.02 <= st["deviation_min"] and st["deviation_max"] <= 0.02
    assert st["mean"] == pytest.approx(target, rel=2e-3)  # achieved 3.6e-4
    assert np.abs(f2.thickness / f1.thickness - 1).max() < 1e-3
    # the turnaround between the coats, the last one of the first coat's passes
    seg, tr = two.segments, two.trajectory
    k = [i for i, kind in enumerate(seg.kind) if kind == "turn"][len(two.offsets) - 1]
    assert seg.kind[k - 1] == seg.kind[k + 1] == "pass"
    split = int(np.searchsorted(tr.t, seg.start[k] + seg.duration[k] / 2))
    axes = rotation(tr.poses)[:, :, 0]
    coats = [integrate(gun_of(two.job), tr.t[s], tr.poses[s, :3], axes[s], pts.reshape(-1, 3),
                       two.frame.n, origin=two.frame.c).thickness
             for s in (slice(0, split + 1), slice(split, None))]
    for coat in coats:
        assert np.abs(coat / (f1.thickness / 2) - 1).max() < 1e-3
    assert coats[0] + coats[1] == pytest.approx(f2.thickness, rel=1e-12)


# --- one test per way a job fails -------------------------------------------------------------
def test_out_of_reach_names_where_and_what_fits(robot, job, act):
    with pytest.raises(PlanError) as info:
        plan_paint(robot, replace(job, width=0.6), act)
    msg = str(info.value)
    assert "\n" not in msg
    for w in ("leaves the workspace", "panel (u, v) = (", "cannot reach",
              "the largest panel that fits (same centre, proportions) is"):
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


def test_inconsistent_speed_spacing_coats(robot, job, act):
    with pytest.raises(PlanError, match="not the target"):
        plan_paint(robot, replace(job, speed=0.3, spacing=0.015), act)


def test_motors_too_weak_to_hold_the_gun(robot, job, act):
    weak = replace(act, units=tuple(replace(u, peak_torque=1e-4, continuous_torque=1e-4)
                                    for u in act.units))
    with pytest.raises(PlanError, match="cannot hold the gun"):
        plan_paint(robot, job, weak)


EXAMPLES = Path(__file__).resolve().parents[3] / "examples"


def yawed(job, degrees):
    a = math.radians(degrees)
    return replace(job, normal=(-math.cos(a), -math.sin(a), 0.0))


def printed(msg: str) -> tuple[float, float]:
    """The panel a PlanError names as the largest that fits, (width, height) [m]."""
    return tuple(float(x) for x in re.search(r"is ([\d.]+) × ([\d.]+) m", msg).groups())


def test_the_suggested_panel_plans(robot, act, job):
    # Yawed −30° the panel is out of reach; the bisection's crude raster said 0.516 of it
    # fits, and that panel (0.134 × 0.062 m) left the workspace in a turnaround when planned.
    far = yawed(job, -30)
    with pytest.raises(PlanError) as err:
        planner.plan_paint(robot, far, act)
    scale = planner.largest_scale(robot, far, act)
    assert 0 < scale < 1
    w, h = printed(str(err.value))
    fit = planner.printed_panel(far, scale)
    assert (w, h) == (fit.width, fit.height)  # the sides rounded down to the mm
    assert scale * far.width - 1e-3 < w <= scale * far.width
    assert scale * far.height - 1e-3 < h <= scale * far.height
    plan = planner.plan_paint(robot, replace(far, width=w, height=h), act)  # must not raise
    assert plan.cycle_time > 0


def test_the_printed_panel_is_the_one_planned(robot, act, job):
    """The yawed panel of centre (0.68, −0.075, 0.16) m, normal (−0.866, 0.5, 0): the panel
    printed as the largest that fits plans as printed (0.183 × 0.084 m; rounded to the
    nearest mm it read 0.183 × 0.085 m, which leaves the workspace in a turnaround)."""
    far = replace(job, center=(0.68, -0.075, 0.16), normal=(-math.sqrt(0.75), 0.5, 0.0))
    with pytest.raises(PlanError) as err:
        planner.plan_paint(robot, far, act)
    w, h = printed(str(err.value))
    assert 0 < w < far.width and 0 < h < far.height
    planner.plan_paint(robot, replace(far, width=w, height=h), act)  # must not raise


def test_reach_only_is_motions_ik_without_dynamics(robot, act, job, monkeypatch):
    frame, offsets, half, speed, coats, _ = panel_layout(job)
    poses, d, dd = planner.task_motion(frame, job.standoff, [-half, 0.0, half],
                                       [offsets[0]] * 3, [speed] * 3, [0.0] * 3, [0.0] * 3,
                                       [0.0] * 3)
    full = motion(robot, act, poses, d, dd)
    only = reach(robot, poses, d, dd)
    assert (only.q == full.ik.q).all() and (only.v == full.ik.v).all()
    vmax = planner.max_pass_speed(robot, act, frame, job, offsets, half, True)

    def refused(*args, **kwargs):
        raise AssertionError("inverse dynamics where only reach is asked")

    # max_pass_speed's own motor question is path_dynamics'; its reach check needs none
    monkeypatch.setattr(inverse, "inverse_dynamics", refused)
    assert planner.max_pass_speed(robot, act, frame, job, offsets, half, True) == vmax
    with pytest.raises(ReachError, match="cannot reach"):
        reach(robot, *planner.task_motion(frame, job.standoff, [3.0], [0.0], [0.0], [0.0],
                                          [0.0], [0.0]))


def _small_three_coats():
    """A 0.10 × 0.06 m panel in three coats: many short passes, the fastest turnarounds put
    theta21_2 at 113.7 % of its continuous torque."""
    job = pp.load_job(EXAMPLES / "paint.toml")
    return replace(job, width=0.10, height=0.06, coats=3)


def _rms_use(robot, result, act) -> np.ndarray:
    """Each motor's RMS torque over the cycle / its continuous rating, from run's result
    (IK and inverse dynamics of the trajectory alone): the motor model, the trapezoid rule."""
    ia = robot.actuated_v
    tm = motor_torque(act, result.dynamics.tau, result.ik.v[:, ia], result.ik.a[:, ia])
    return time_rms(result.trajectory.t, tm) / act.column("continuous_torque")


def test_the_planned_cycle_keeps_the_continuous_ratings(robot, act):
    plan = plan_paint(robot, _small_three_coats(), act)
    result = pp.run_pipeline(robot, plan.trajectory)
    use = _rms_use(robot, result, act)
    assert use.max() <= 1.0 + 1e-3  # 0.970 (the planner's 97 %); 1.137 before
    assert np.abs(use - plan.ratios["rms_torque"]).max() < 2e-3  # its own figure: 4e-5 apart
    # size's verdict on the given motion (actuator_sizing's given_within_ratings: every
    # ratio of motor_load_of to its rating ≤ 1), without its time-optimal cycle of the
    # program (TOPP-RA, seconds; not asserted here: tests/dynamics/test_passes.py)
    ratios = motor_load_of(robot, act, result.ik, result.dynamics).ratios()
    assert all((ratios[k] <= 1.0).all() for k in ("peak_torque", "rms_torque", "speed")), ratios
    assert plan.ratios["peak_torque"].max() <= 1.0


def test_a_cycle_no_turnaround_can_cool_is_refused(robot, act):
    """Continuous ratings 0.3× the shipped ones: turnarounds long enough to cool the base
    motors would reach out of the workspace (a turnaround's excursion grows with its
    duration), so the job is refused in one line naming the motor and its RMS use."""
    weak = replace(act, units=tuple(replace(u, continuous_torque=0.3 * u.continuous_torque)
                                    for u in act.units))
    with pytest.raises(PlanError, match=r"^motor theta21 runs at 1\d\d(\.\d+)? % of its "
                                        r"continuous \(RMS\) torque over the cycle with "
                                        r"turnarounds and ramps \d+× their fastest .*longer "
                                        r"ones leave the workspace"):
        plan_paint(robot, _small_three_coats(), weak)


def test_the_cli_prints_the_rms_use(tmp_path, capsys):
    from cli_run import run_cli

    job = tmp_path / "job.toml"
    job.write_text((EXAMPLES / "paint.toml").read_text().replace(
        "width = 0.26 ", "width = 0.10 ").replace("height = 0.12 ", "height = 0.06 ")
        + "coats = 3\n")
    code, out, err = run_cli(["paint", "--job", job, "--out", tmp_path / "p"], capsys)
    assert code == 0, err
    line = next(x for x in out.splitlines() if x.startswith("motor peak torque/RMS torque"))
    assert "theta21_2 " in line
    rms = [int(x.split()[-1].split("/")[1]) for x in line.split(": ", 1)[1].split(", ")]
    assert max(rms) == 97  # the planner's 97 % (113.7 % before)
