"""The line's shared phases (paint/line/phases.py; docs/model.md §24): the
relative program's interface (the speed searches: test_speeds.py); where the job puts the part
at t = 0 sets the wait, not the cycle: the example panel, the small strip and the example
strip moved upstream give the same parts per hour, world program and film (fixtures line_job,
line_plan, line_part_job, line_part_plan, line_part_example_job, line_part_example_plan:
tests/examples_planned.py). The world path of real plans is tested in test_panel.py (a panel)
and test_part.py (a part)."""
from dataclasses import replace

import numpy as np
import pytest

from pollard_pin.painting.film.line import line_film
from pollard_pin.painting.film.part import surface_film
from pollard_pin.painting.film.stats import film_stats
from pollard_pin.painting.line.panel import plan_line
from pollard_pin.painting.line.phases import Relative
from pollard_pin.painting.policy import PlannerPolicy
from pollard_pin.painting.report import line_table


def test_relative_program_interface():
    """Pieces ramp, pass, turn, pass, ramp: the trigger open on the passes only (a part) or
    throughout (a panel), coarse times at piece ends and middles."""
    start, dur = np.array([0.0, 1.0, 3.0, 4.0, 6.0]), np.array([1.0, 2.0, 1.0, 2.0, 1.0])
    kind = ("ramp", "pass", "turn", "pass", "ramp")
    part = Relative(lambda t: (t,), start, dur, kind, passes_only=True)
    panel = Relative(lambda t: (t,), start, dur, kind)
    assert part.total == panel.total == 7.0
    t = np.array([0.5, 1.0, 2.9, 3.5, 4.0, 6.5, 7.0])
    assert list(part.trigger(t)) == [0, 1, 1, 0, 1, 0, 0]
    assert list(panel.trigger(t)) == [1] * 7
    assert list(part.coarse_times()) == [0, 0.5, 1, 2, 3, 3.5, 4, 5, 6, 6.5, 7]
    assert list(part.not_passes()) == [0, 2, 4]


# --- the part placed further upstream ------------------------------------------------------------
UPSTREAM = (0.1, 0.3, 1.0)  # m


@pytest.mark.parametrize("refine", [2, 4, 8])
def test_the_paths_samples_are_the_checks_own(refine):
    """path_times(times, steps) is, bit for bit, every ``refine``-th of path_times(times,
    refine × steps), refine a power of two (plan_world's screen checks the motors there
    first): delays, ends and step counts at random."""
    from pollard_pin.painting.line.phases import LineTimes, path_times

    rng = np.random.default_rng(refine)
    for _ in range(300):
        delay = float(rng.choice([0.0, rng.uniform(0, 100)]))
        end = delay + float(rng.uniform(0.5, 100))
        times = LineTimes(delay, end, float(rng.uniform(0.1, 3)))
        steps = int(rng.integers(1, 50_000))
        t, tf = path_times(times, steps), path_times(times, refine * steps)
        # each of t found in tf where it sorts (np.isin's check, without its sort: 20× faster)
        assert np.array_equal(tf[np.searchsorted(tf, t).clip(max=len(tf) - 1)], t)


@pytest.fixture(scope="module")
def moved(robot, act, line_job, line_part_job, line_part_example_job):
    """(kind, by) ↦ the plan ``by`` m upstream of examples/line.toml (``"panel"``), of the
    small strip across the travel as line_part_plan plans it (``"part"``), or of
    examples/line_part.toml (``"example"``), each planned once."""
    plans = {}

    def plan(kind: str, by: float):
        if (kind, by) not in plans:
            job = {"panel": line_job, "part": line_part_job,
                   "example": line_part_example_job}[kind]
            across = {"policy": PlannerPolicy(strokes="across")} if kind == "part" else {}
            plans[kind, by] = plan_line(robot, upstream(job, by), act, **across)
        return plans[kind, by]

    return plan


def upstream(job, by: float):
    """The job with its part (or panel) ``by`` metres further upstream at t = 0."""
    back = -by * np.asarray(job.line.direction)
    if hasattr(job, "center"):
        return replace(job, center=tuple(np.asarray(job.center) + back))
    return replace(job, position=tuple(np.asarray(job.position) + back))


def sprayed_relative(plan, by: float = 0.0):
    """The sprayed samples as the film sees them: times from the program's start and the
    gun's poses relative to the part, the part's shift ``by`` taken back out."""
    tr, on = plan.trajectory, plan.spray > 0
    p = tr.poses[on].copy()
    p[:, :3] += (by - plan.speed * tr.t[on, None]) * plan.direction
    return tr.t[on] - plan.times.delay, p


def same_cycle(a, b, by: float):
    ta, tb = line_table(a), line_table(b)
    # achieved 2e-16 relative (the shift found on a world grid, the path sampled from the
    # program's start)
    assert tb["parts_per_hour"] == pytest.approx(ta["parts_per_hour"], rel=1e-9)
    assert tb["cycle"] == pytest.approx(ta["cycle"], rel=1e-9)
    # the wait is the only difference: the part's extra way at the line's speed
    assert b.times.delay - a.times.delay == pytest.approx(by / a.speed, rel=1e-9)
    assert tb["window"] == pytest.approx(ta["window"], abs=1e-9)
    sa, sb = sprayed_relative(a), sprayed_relative(b, by)
    assert len(sa[0]) == len(sb[0])
    assert np.abs(sa[0] - sb[0]).max() < 1e-9  # achieved ~1e-14 s
    assert np.abs(sa[1] - sb[1]).max() < 1e-9  # achieved ~1e-15 m
    assert np.abs(a.ratios["rms_torque"] - b.ratios["rms_torque"]).max() < 1e-9


# 0.1 m: slow (~2.5 s of CPU), the same panel planner and checks as 0.3 m and 1.0 m (a whole
# and a fractional number of seconds' wait), which the default suite keeps; the part keeps
# all three (the small strip plans in under half the panel's time)
@pytest.mark.parametrize("by", [pytest.param(UPSTREAM[0], marks=pytest.mark.slow),
                                *UPSTREAM[1:]])
def test_panel_upstream_same_parts_per_hour(line_plan, moved, by):
    same_cycle(line_plan, moved("panel", by), by)


@pytest.mark.parametrize("by", UPSTREAM)
def test_part_upstream_same_parts_per_hour(line_part_plan, moved, by):
    """A part's upstream moves on the small strip (tests/line_parts.py, the session's plan):
    the same part planner (plan_surface's passes, the part's shifts and delay, its trigger on
    the passes only) at a third of the 0.90 m example strip's planning time; the example
    itself is moved 0.3 m in test_same_film_figures_upstream."""
    same_cycle(line_part_plan, moved("part", by), by)


def test_same_film_figures_upstream(line_job, line_plan, line_part_example_job,
                                    line_part_example_plan, moved):
    """The films themselves, 0.3 m upstream, at a coarse film resolution (the comparison,
    not the film, is tested): the same statistics to 1e-9 of the target; the example strip's
    cycle too (:func:`same_cycle`, as the small strip's in test_part_upstream_...)."""
    res = 2 * line_job.sigma / 3
    a, b = line_film(line_plan, res)[3], line_film(moved("panel", 0.3), res)[3]
    assert np.abs(a.thickness - b.thickness).max() < 1e-9 * line_job.thickness  # ~1e-19 m
    same_cycle(line_part_example_plan, moved("example", 0.3), 0.3)
    (pts, fa, pa, ea), (_, fb, pb, eb) = (surface_film(p.in_part_frame(), res)
                                          for p in (line_part_example_plan,
                                                    moved("example", 0.3)))
    assert np.array_equal(pa, pb) and ea == pytest.approx(eb, rel=1e-9)
    sa, sb = (film_stats(f.thickness[pa], line_part_example_job.thickness, pts.areas[pa])
              for f in (fa, fb))
    for key in ("min", "max", "mean", "within_5pct", "within_10pct"):
        assert sb[key] == pytest.approx(sa[key], rel=1e-9), key


def test_world_motion_reusing_takes_known_rows_and_evaluates_the_rest():
    """world_motion_reusing gives world_motion's own arrays at the times asked, bit for bit
    (the hold, catch-up, program, slow-down and return alike), evaluating the program only
    at the times not among the known ones: the path's samples from its 4× finer check, a
    seam's samples inserted among the path's."""
    from pollard_pin.painting.line.phases import (
        LineTimes,
        path_times,
        world_motion,
        world_motion_reusing,
    )

    start, dur = np.array([0.0, 1.0, 3.0, 4.0, 6.0]), np.array([1.0, 2.0, 1.0, 2.0, 1.0])
    kind = ("ramp", "pass", "turn", "pass", "ramp")
    asked = []

    def motion(t):
        asked.append(len(t))
        p = np.column_stack([np.sin(t), np.cos(0.3 * t), t ** 2 / 7, 0.1 * t, np.exp(-t),
                             np.sqrt(1 + t)])
        return p, np.cos(p), np.sin(p)

    rel = Relative(motion, start, dur, kind, passes_only=True)
    e = np.array([0.0, 0.6, 0.8])
    times = LineTimes(3.3, 3.3 + rel.total, 1.7)
    t, tf = path_times(times, 997), path_times(times, 4 * 997)
    fine = world_motion(rel, 0.02, e, times, tf)
    asked.clear()
    got = world_motion_reusing(rel, 0.02, e, times, t, (tf, fine))
    assert asked == []  # the path's samples all known: the program not evaluated
    want = world_motion(rel, 0.02, e, times, t)
    for a, b in zip(got, want):
        assert a.shape == b.shape and a.tobytes() == b.tobytes()
    seams = np.array([4.1234567, 7.5, 9.99])  # new samples among the path's
    t2 = np.unique(np.concatenate([t, seams]))
    asked.clear()
    got = world_motion_reusing(rel, 0.02, e, times, t2, (t, want))
    assert sum(asked) == 2 + len(seams)  # the program's ends and the new samples alone
    for a, b in zip(got, world_motion(rel, 0.02, e, times, t2)):
        assert a.tobytes() == b.tobytes()


def test_world_motion_rows_are_each_times_alone():
    """Each row of world_motion is its time's alone, bit for bit, however many are asked (the
    long wait's rows made once, the reuse and the check's leaving out rely on it): the held
    start pose r0 + s·(D − CATCH/2)·e at rest, the catch-up, program, slow-down and return,
    a direction with a negative component (−0.0 rates stay −0.0)."""
    from pollard_pin.painting.line.phases import CATCH, LineTimes, world_motion

    def motion(t):
        p = np.column_stack([np.sin(t), np.cos(0.3 * t), t ** 2 / 7, 0.1 * t, np.exp(-t),
                             np.sqrt(1 + t)])
        return p, np.cos(p), np.sin(p)

    rel = Relative(motion, np.array([0.0, 1.0, 3.0]), np.array([1.0, 2.0, 1.0]),
                   ("ramp", "pass", "ramp"))
    e, s = np.array([0.0, -0.6, 0.8]), 0.02
    times = LineTimes(30.0, 30.0 + rel.total, 1.7)
    edges = [times.leave, times.delay, times.end, times.end + CATCH, times.total]
    t = np.concatenate([np.linspace(0.0, times.total, 401), edges,
                        np.nextafter(edges, 0.0), np.nextafter(edges, 99.0)])
    got = world_motion(rel, s, e, times, t)
    alone = [world_motion(rel, s, e, times, t[k:k + 1]) for k in range(len(t))]
    for i, a in enumerate(got):
        assert a.tobytes() == np.concatenate([r[i] for r in alone]).tobytes(), i
    held = t < times.leave
    assert held.sum() > 300
    want = motion(np.zeros(1))[0][0] + np.r_[s * (times.delay - CATCH / 2) * e, 0, 0, 0]
    assert np.abs(got[0][held] - want).max() < 1e-15
    assert not got[1][held].any() and not got[2][held].any() and not got[3][held].any()
    assert np.signbit(got[1][held, 1]).all()  # s·0·e, as the catch-up's formula at x = 0
