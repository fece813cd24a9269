"""The cell planner (paint/cell/plan.py, docs/model.md §26): one robot at the origin is
today's line job, a rigid motion of the whole scene leaves the film as it was, the seam's
film is the target's (and would not be if a robot sprayed past it), a robot turned about z
on the far side of the line paints the part's back."""
import math
from dataclasses import replace

import numpy as np
import pytest
from cell_jobs import cell_job, moved, panel_cell

from pollard_pin.painting.cell.plan import plan_cell, plan_cell_job
from pollard_pin.painting.cell.robots import CellRobot
from pollard_pin.painting.cell.zones import Split, Zone
from pollard_pin.painting.film.cell import cell_panel_film


@pytest.fixture(scope="module")
def cell(robot, act):
    return plan_cell_job(robot, cell_job(panel_cell()), act)


@pytest.fixture(scope="module")
def cell_film(cell):
    return cell_panel_film(cell)


def seam_rows(cell, film, seam: float, half: float):
    """(heights, each grid row's mean film over the target) of the rows within ``half`` [m]
    of the seam (the row mean takes out the ripple along the travel)."""
    U, V, pts, f = film
    z = pts[:, 0, 2]
    rows = f.thickness.reshape(len(V), len(U)).mean(axis=1) / cell.job.thickness
    near = np.abs(z - seam) <= half
    return z[near], rows[near]


def test_one_robot_at_the_origin_is_todays_line_job(line_job, line_plan, line_plan_film,
                                                    line_cell):
    cell = line_cell  # examples/line.toml as a cell of one robot at the origin
    assert [rp.robot for rp in cell.robots] == [CellRobot("only")]
    p = cell.robots[0].plan
    assert np.array_equal(p.trajectory.t, line_plan.trajectory.t)
    assert np.array_equal(p.trajectory.poses, line_plan.trajectory.poses)
    assert np.array_equal(p.spray, line_plan.spray)
    today = line_plan_film[3].thickness
    ours = cell_panel_film(cell)[3].thickness
    # the same samples and weights: equal (seen 0.0)
    assert np.abs(ours - today).max() <= 1e-12 * line_job.thickness


def test_the_seam_lays_the_target(cell, cell_film):
    (seam,) = cell.split.seams()
    assert [r.zone.robot for r in cell.robots] == ["low", "high"]
    _, rows = seam_rows(cell, cell_film, seam, cell.split.runout)
    # a robot spraying 1 mm past the seam at full rate adds 4 % there (the next test);
    # seen |row − 1| ≤ 5e-5
    assert np.abs(rows - 1).max() <= 5e-3
    th = cell_film[3].thickness / cell.job.thickness
    assert np.abs(th - 1).max() <= 0.05  # the whole panel within ±5 % (seen ±0.5 %)


def test_a_robot_spraying_past_the_seam_shows(robot, act, cell):
    """The check above fails for a layout whose low robot sprays 1 mm past the seam."""
    (seam,) = cell.split.seams()
    s = cell.split
    over = Split(s.axis, (Zone("low", -math.inf, seam + 1e-3), Zone("high", seam, math.inf)),
                 s.runout)
    bad = plan_cell(robot, cell.job, act, cell.speed, split=over, clearance=False)
    _, rows = seam_rows(bad, cell_panel_film(bad), seam, s.runout)
    assert rows.max() - 1 > 5e-3  # the doubled millimetre: seen +4.0 %


def test_each_robot_sprays_only_its_zone(cell):
    """The spot's centre while spraying lies in the robot's zone; the trigger switches at
    samples placed at the seam, a fraction of the trapezoid weight there."""
    from pollard_pin.painting.film.cell import world_gun

    for rp in cell.robots:
        _, p, R, s = world_gun(rp)
        a = R[:, :, 0]  # the spray axis
        aim = (p + rp.plan.job.standoff * a) @ np.asarray(cell.split.axis)
        on = s > 0
        assert aim[on].min() >= rp.zone.lo - 1e-9 and aim[on].max() <= rp.zone.hi + 1e-9
        part = (s > 0) & (s < 1)
        assert part.sum() >= len(rp.plan.offsets)  # a seam sample on every pass
        seam = rp.zone.hi if math.isfinite(rp.zone.hi) else rp.zone.lo
        assert np.abs(aim[part] - seam).max() <= 1e-13  # seen 1e-15


def test_a_rigid_motion_of_the_scene_leaves_the_film(robot, act, cell, cell_film):
    tables = moved(panel_cell(), 30.0, (0.2, -0.1, 0.05))
    other = plan_cell_job(robot, cell_job(tables), act)
    assert other.split.seams() == pytest.approx([s + 0.05 for s in cell.split.seams()],
                                                abs=1e-9)
    U, V, pts, f = cell_panel_film(other)
    # every robot's plan is the same in its base frame: seen 8e-14 of the target
    assert np.abs(f.thickness - cell_film[3].thickness).max() <= 1e-11 * cell.job.thickness
    assert len(U) == len(cell_film[0]) and len(V) == len(cell_film[1])


def test_turned_robots_are_planned_with_their_gravity(robot, act, cell):
    """Gravity Rᵀg in the base frame: the planner's motors see the same loads whatever the
    base's turn about z, and a turned base carries its own into the model."""
    from pollard_pin.painting.cell.frames import robot_model_in_base

    turned = CellRobot("t", (0.0, 0.0, 0.0), (180.0, 0.0, 0.0))
    m = robot_model_in_base(robot, turned)
    assert np.allclose(m.model.gravity.linear, [0.0, 0.0, 9.81], atol=1e-12)
    assert np.allclose(robot.model.gravity.linear, [0.0, 0.0, -9.81])  # shared one untouched


def test_the_policys_seams_and_run_reach_every_robot(robot, act, cell, monkeypatch):
    """PlannerPolicy.seams cut the zones where asked and every robot's program is made with
    the policy (its run past a seam, docs/model.md §26.5): each robot's zone view recorded
    (its program not planned)."""
    import pollard_pin.painting.cell.plan as cell_plan
    from pollard_pin.painting.policy import PlannerPolicy

    seen = []

    def plan_zone(model, act, job_b, view, speed, part_b, policy):
        seen.append((view.zone, view.runout, policy.seam_run))
        return cell.robots[len(seen) - 1].plan

    monkeypatch.setattr(cell_plan, "plan_zone", plan_zone)
    policy = PlannerPolicy(seams=(0.2,), seam_run=0.005)
    got = plan_cell(robot, cell.job, act, clearance=False, policy=policy)
    assert got.split.seams() == [0.2]
    assert sorted(z.hi for z, _, _ in seen) == [0.2, math.inf]
    assert [(r, run) for _, r, run in seen] == [(cell.split.runout, 0.005)] * 2


def test_bases_closer_than_two_footprints_are_refused(robot, act):
    """Two bases 0.1 m apart (each base's joints lie 85 mm from its origin)."""
    from pollard_pin.painting.errors import CellError

    tables = panel_cell([{"name": "low", "base": [0.0, 0.0, 0.0]},
                         {"name": "high", "base": [0.0, 0.1, 0.0]}])
    with pytest.raises(CellError, match="'low' and 'high' stand 100 mm apart, closer than "
                                        "a robot's own base .170 mm."):
        plan_cell_job(robot, cell_job(tables), act)


def test_an_upside_down_robot_paints_from_above(robot, act):
    """A robot hung 0.26 m up, turned 180° about x (gravity +z in its base), paints a 0.2 ×
    0.15 m panel passing under it: planned with its gravity, the film on target."""
    tables = panel_cell([{"name": "under", "base": [0.0, 0.0, 0.26],
                          "rotation": [180.0, 0.0, 0.0]}], speed=0.016)
    tables["panel"].update(height=0.15, center=[0.70, -0.3, 0.16])
    cell = plan_cell_job(robot, cell_job(tables), act)
    p = cell.robots[0].plan
    # the panel's z 0.085…0.235 m is z_b 0.175…0.025 m in the hung base; the strokes run
    # 4σ past both edges at constant speed, the turnarounds (gun open) a little further
    z = p.trajectory.poses[p.spray > 0, 2]
    assert -0.05 < z.min() <= 0.025 - 0.04 + 1e-9
    assert 0.175 + 0.04 - 1e-9 <= z.max() < 0.25
    assert np.allclose(p.direction, [0.0, -1.0, 0.0], atol=1e-15)  # the line in its base
    th = cell_panel_film(cell)[3].thickness / cell.job.thickness
    assert np.abs(th - 1).max() <= 0.05  # seen ±0.5 %


def test_a_slow_line_waits_and_the_seam_holds(robot, act):
    """The two-robot panel cell at 0.004 m/s, a sixth of its speed (docs/model.md §24.1,
    §26): a robot whose program drifts out of its reach waits at its turnarounds, shut (one
    that stays in its window plans as it is), and the seam still lays the target (the
    strokes relative to the part are the same; seen |row − 1| ≤ 5e-5)."""
    from pollard_pin.painting.line.dwell import dwell_time

    slow = plan_cell_job(robot, cell_job(panel_cell(speed=0.004)), act)
    assert max(rp.plan.strokes.dwell for rp in slow.robots) > 0
    for rp in slow.robots:  # the strokes' record is the program's own waits
        assert rp.plan.strokes.dwell == dwell_time(rp.plan.relative)
        assert (rp.plan.relative.kind.count("wait") > 0) is (rp.plan.strokes.dwell > 0)
    film = cell_panel_film(slow)
    (seam,) = slow.split.seams()
    _, rows = seam_rows(slow, film, seam, slow.split.runout)
    assert np.abs(rows - 1).max() <= 5e-3
    assert np.abs(film[3].thickness / slow.job.thickness - 1).max() <= 0.05


def test_just_below_the_pace_a_retry_adds_only_the_time_needed(robot, act, monkeypatch):
    """Where a program as it is fails as too slow just below its pace (forced here: every
    drift < 0 refused), the retry's turns add only the time the line needs (docs/model.md
    §24.1): the turns' rate dips and they wait 0, the drift is 0 (half-paced turns would
    have overshot by n·τ·s), it paints, its waits stated ≥ 0, the seam on target."""
    from pollard_pin.painting.errors import LineSpeedError
    from pollard_pin.painting.line import dwell

    plain, tried = dwell.plan_world, []

    def plan_world(robot_, act_, prog, speed, e, policy, screen=False):
        rel = prog.build(prog.guess)
        tried.append(rel.kind.count("wait"))
        if "wait" not in rel.kind and dwell.drift_along(rel, speed, e) < 0:
            raise LineSpeedError("drifts back out of the reach", False, "drifts back")
        return plain(robot_, act_, prog, speed, e, policy, screen=screen)

    monkeypatch.setattr(dwell, "plan_world", plan_world)
    slow = plan_cell_job(robot, cell_job(panel_cell(speed=0.0189)), act)  # paces ≈ 0.0191
    assert tried.count(0) == 2 and len(tried) == 4  # each robot: as it is, then the retry
    for rp in slow.robots:
        rel, e = rp.plan.relative, rp.plan.direction
        assert rp.plan.strokes.dwell == dwell.dwell_time(rel) >= 0.0
        assert abs(dwell.drift_along(rel, slow.speed, e)) < 1e-9
        base = [d for d, k in zip(rel.program.duration, rel.program.kind) if k == "turn"]
        halves = [d for d, k in zip(rel.duration, rel.kind) if k == "turn"][::2]
        waits = [d for d, k in zip(rel.duration, rel.kind) if k == "wait"]
        assert min(waits) >= 0.0
        # each turn adds the same share x of the time the line needs (2h + w − τ), the
        # short ones stopping and waiting, the rest slowed only (τ/2 < h < τ, no wait)
        added = [2 * h + w - b for h, w, b in zip(halves, waits, base)]
        assert np.ptp(added) < 1e-9 and 0 < added[0] < max(base)
        dipped = [b / 2 < h < b and w == 0 for h, w, b in zip(halves, waits, base)]
        assert sum(dipped) >= len(base) // 2
    film = cell_panel_film(slow)
    (seam,) = slow.split.seams()
    _, rows = seam_rows(slow, film, seam, slow.split.runout)
    assert np.abs(rows - 1).max() <= 5e-3
    assert np.abs(film[3].thickness / slow.job.thickness - 1).max() <= 0.05


def test_strokes_along_in_a_cell_give_each_robot_whole_passes(robot, act):
    """Forced along the travel (docs/model.md §24.2, §26.3): each robot paints the whole
    passes whose level lies in its zone, every pass of the one-robot layout painted by
    exactly one robot, so the seam lies between two passes and lays the target (a pass
    doubled or dropped there would show ±50 % or more; seen 0.995–1.005, the ripple's)."""
    from pollard_pin.painting.plan.layout import panel_layout
    from pollard_pin.painting.policy import PlannerPolicy

    policy = PlannerPolicy(strokes="along")
    cell = plan_cell(robot, cell_job(panel_cell()), act, policy=policy)
    (seam,) = cell.split.seams()
    levels = []
    for rp in cell.robots:
        p = rp.plan
        assert (p.strokes.direction, p.strokes.start, p.strokes.why) == ("along", None, "forced")
        t = p.trajectory.t  # passes along the +y travel, the gun open over the program
        assert p.horizontal and p.spray[(t >= p.times.delay) & (t <= p.times.end)].min() == 1
        z = p.frame.c[2] + rp.robot.base[2] + p.offsets * p.frame.v[2]  # world levels
        assert (z < seam).all() if rp.robot.name == "low" else (z >= seam).all()
        levels += list(z)
    job = replace(cell.job, direction="horizontal")
    frame, offsets = panel_layout(job)[:2]
    assert sorted(levels) == pytest.approx(sorted(frame.c[2] + offsets * frame.v[2]),
                                           abs=1e-12)
    film = cell_panel_film(cell)
    _, rows = seam_rows(cell, film, seam, 3 * cell.job.sigma)
    assert np.abs(rows - 1).max() <= 1e-2
    assert np.abs(film[3].thickness / cell.job.thickness - 1).max() <= 0.05


def test_a_speed_refused_once_is_refused_again_without_planning(robot, act, cell,
                                                               monkeypatch):
    # a refusal names the fastest speed by a search that starts at the refused speed: the
    # planner refuses it again from memory, the same error, and plans every other speed
    from pollard_pin.painting.cell import plan as cell_plan
    from pollard_pin.painting.errors import LineSpeedError

    calls = []

    def plan(robot_, job, act_, speed, *args, **kw):
        calls.append(speed)
        if speed < 0.02:
            raise LineSpeedError(f"at line speed {speed} m/s: too slow", False, "too slow")
        return speed

    monkeypatch.setattr(cell_plan, "plan_cell", plan)
    plan_at = cell_plan.cell_planner(robot, cell.job, act, split=cell.split)
    with pytest.raises(LineSpeedError) as first:
        plan_at(0.01)
    with pytest.raises(LineSpeedError) as again:
        plan_at(0.01)
    assert calls == [0.01] and str(again.value) == str(first.value)
    assert (again.value.too_fast, again.value.why, again.value.hint) == (False, "too slow", None)
    assert plan_at(0.03) == plan_at(0.03) == 0.03 and calls == [0.01, 0.03, 0.03]


def test_a_clearance_stride_sees_the_pair_no_closer_within_its_bound(robot, cell):
    """PlannerPolicy.clearance_stride = 4 (the design study's search, docs/model.md §31.5):
    the robots' least distance over every 4th sample of the clock is never below the one
    over every sample (the plan's own check), and less its bound between samples it is at
    most that."""
    from pollard_pin.painting.cell.plan import cell_clearance_of

    every = cell.clearance
    fourth = cell_clearance_of(robot, cell, 4)
    assert fourth.pair == every.pair and fourth.robots_between > every.robots_between
    assert fourth.between_robots - fourth.robots_between <= every.between_robots <= \
        fourth.between_robots + 1e-12
    assert fourth.to_part - fourth.part_between <= every.to_part + 1e-12


def test_a_remembered_refusal_holds_no_frames_and_is_said_again(robot, act, cell, monkeypatch):
    """A zone's refusal remembered: raised again the same (class, words, the speed search's
    attributes) without planning, and its plan's frames are not kept: the garbage collector
    off, what the refused plan held is freed once the search drops the refusal (a remembered
    exception would hold its traceback's frames in a cycle with the memo: every refused
    count's plans held to the end of a layout search)."""
    import gc
    import weakref

    from pollard_pin.painting.cell import plan as cell_plan
    from pollard_pin.painting.errors import LineSpeedError

    class Held:  # what a refused plan holds in its frames (its samples)
        pass

    held, made = [], []

    def plan_zone(*args):
        samples = Held()
        held.append(weakref.ref(samples))
        made.append(1)
        raise LineSpeedError("drifts out of reach", too_fast=True, why="drifts", hint=0.01)

    monkeypatch.setattr(cell_plan, "plan_zone", plan_zone)
    said = []
    gc.disable()
    try:
        with cell_plan.zone_plans_remembered():
            for _ in range(2):
                try:
                    plan_cell(robot, cell.job, act, split=cell.split, clearance=False)
                except LineSpeedError as exc:
                    said.append((str(exc), exc.too_fast, exc.why, exc.hint))
        assert held and all(ref() is None for ref in held)
    finally:
        gc.enable()
    assert len(made) == 1 and said[0] == said[1] and said[0][1:] == (True, "drifts", 0.01)
