"""The line speeds that paint a job (paint/line/speeds.py, docs/model.md §24.3): the fastest
(--max-line-speed), the interval about the job's speed and the refusal naming it, against
stand-in planners whose answers are known (runs of speeds set here, a gap, a budget's floor,
two strategies), and the interval of examples/line.toml checked by plans just outside it."""
from types import SimpleNamespace

import pytest

from pollard_pin.painting.errors import BudgetError, LineSpeedError, PlanError
from pollard_pin.painting.line.dwell import dwell_time, waiting_floor
from pollard_pin.painting.line.panel import line_planner, plan_line
from pollard_pin.painting.line.speeds import (
    BUDGET_FLOOR,
    constraint,
    fastest_line_speed,
    line_speed_interval,
    plan_or_name_fastest,
    waits_bound,
)


def planner(slowest: float, fastest: float, calls: list):
    """Plans between ``slowest`` and ``fastest`` [m/s]; outside, the side's LineSpeedError."""

    def plan_at(s):
        calls.append(s)
        if s > fastest:
            raise LineSpeedError(f"{s} too fast", True, f"drifts at {s}")
        if s < slowest:
            raise LineSpeedError(f"{s} too slow", False, f"turns at {s}")
        return SimpleNamespace(speed=s)

    return plan_at


@pytest.mark.parametrize("start", [0.001, 0.02, 0.0371, 0.5, 1.9])
def test_fastest_speed_is_found_to_the_resolution(start):
    calls = []
    s, plan = fastest_line_speed(planner(0.01, 0.0371, calls), start, "j", resolution=0.01)
    assert plan.speed == s and s <= 0.0371 and s >= 0.0371 / 1.01
    assert len(calls) < 40


def test_too_slow_goes_to_the_speed_of_no_drift():
    """A too-slow failure that names the speed of no drift is followed there, not doubled
    towards it (from 1e-5 m/s: 12 doublings before)."""
    calls = []

    def plan_at(s):
        calls.append(s)
        if s < 0.03:
            raise LineSpeedError(f"{s} too slow", False, "drifts back", hint=0.031)
        if s > 0.0371:
            raise LineSpeedError(f"{s} too fast", True)
        return SimpleNamespace(speed=s)

    s, plan = fastest_line_speed(plan_at, 1e-5, "j", resolution=0.01)
    assert calls[:2] == [1e-5, 0.031] and 0.0371 / 1.01 <= s <= 0.0371
    assert len(calls) < 12


def test_no_speed_paints_it():
    calls = []
    with pytest.raises(PlanError, match="no line speed paints the part") as info:
        fastest_line_speed(planner(0.05, 0.04, calls), 0.03, "j.toml")
    # each side says why, the reason of the speed it names
    msg = str(info.value)
    assert msg.startswith("j.toml: no line speed paints the part: too slow at ")
    for side, why in (("too slow at ", "turns at "), ("too fast at ", "drifts at ")):
        named = msg.split(side)[1].split(" m/s")[0]
        assert f"{named} m/s ({why}" in msg and float(named) in [float(f"{c:.4g}")
                                                                  for c in calls]


def test_a_speed_too_fast_names_the_fastest():
    """The refusal names the interval, its fast end the fastest to 1 %."""
    calls = []
    with pytest.raises(PlanError) as info:
        plan_or_name_fastest(planner(0.01, 0.0371, calls), 0.2, "j.toml")
    msg = str(info.value)
    assert msg.startswith("j.toml: 0.2 too fast; it paints at ")  # the file; the fast end:
    named = float(msg.split("–")[1].split()[0])
    assert 0.0371 / 1.01 <= named <= 0.0371
    assert not isinstance(info.value, LineSpeedError)  # not to be searched again
    calls.clear()
    assert plan_or_name_fastest(planner(0.01, 0.0371, calls), 0.03, "j").speed == 0.03
    assert calls == [0.03]


@pytest.mark.parametrize("speed, why", [(0.2, "drifts at 0.2"), (0.001, "turns at 0.001")])
def test_a_refusal_not_naming_the_interval_plans_no_other_speed(speed, why):
    """name=False (PlannerPolicy.name_speeds, the design study's search): the speed's own
    LineSpeedError, its side and why kept, and no other speed planned."""
    calls = []
    with pytest.raises(LineSpeedError) as info:
        plan_or_name_fastest(planner(0.01, 0.0371, calls), speed, "j.toml", name=False)
    assert calls == [speed] and info.value.why == why
    assert info.value.too_fast == (speed > 0.0371) and "paints at" not in str(info.value)
    assert plan_or_name_fastest(planner(0.01, 0.0371, calls), 0.03, "j", name=False).speed \
        == 0.03


# --- the interval --------------------------------------------------------------------------------
def runs(spans, calls: list, floor: float = 0.0, slow_why="the program drifts -0.2 m, out of "
         "the reach", fast_why="a motor at 104 % of its rating"):
    """Plans inside any of ``spans`` [(lo, hi)] m/s; below ``floor`` the budget's
    BudgetError; elsewhere too slow under the first span's lo, too fast otherwise."""

    def plan_at(s):
        calls.append(s)
        if s < floor:
            raise BudgetError(f"{s} past the budget")
        if any(lo <= s <= hi for lo, hi in spans):
            return SimpleNamespace(speed=s)
        if s < spans[0][0]:
            raise LineSpeedError(f"{s} too slow", False, slow_why)
        raise LineSpeedError(f"{s} too fast", True, fast_why)

    return plan_at


def within(found: float, true: float, resolution: float, inside: bool = True):
    """``found`` is inside the run and within ``resolution`` (relative) of its end ``true``."""
    return found == pytest.approx(true, rel=resolution) and (found >= true if inside else
                                                             found <= true)


@pytest.mark.parametrize("start", [0.0005, 0.004, 0.02, 0.0371, 0.3])
@pytest.mark.parametrize("resolution", [0.05, 0.01])
def test_interval_found_to_the_resolution(start, resolution):
    """From inside, below and above the run [0.0031, 0.0371] m/s: both ends within the
    resolution, each end's plan at that speed, each bound the failure beyond it."""
    calls = []
    got = line_speed_interval(runs([(0.0031, 0.0371)], calls), start, "j", resolution)
    assert within(got.low, 0.0031, resolution) and within(got.high, 0.0371, resolution,
                                                          inside=False)
    assert got.low_plan.speed == got.low and got.high_plan.speed == got.high
    assert got.low_bound == "too slow: the program drifts -0.2 m, out of the reach", start
    assert got.high_bound == "too fast: a motor at 104 % of its rating"
    assert got.resolution == resolution and len(calls) < 60
    assert got.said() == f"{got.low:.4g}–{got.high:.4g} m/s"
    assert got.table() == {"min": got.low, "max": got.high, "resolution": resolution,
                           "min_bound": got.low_bound, "max_bound": got.high_bound}


def test_slow_end_bounded_by_the_first_failure():
    """From 0.00995 m/s, just too slow: doubled to 0.0199, every speed bisected down paints,
    so the slow end's bound is the first failure's, said as the others."""
    got = line_speed_interval(runs([(0.01, 0.0371)], []), 0.00995, "j", 0.05)
    assert within(got.low, 0.01, 0.05)
    assert got.low_bound == "too slow: the program drifts -0.2 m, out of the reach"


def test_interval_floored_by_the_budget():
    """Every slower speed paints until the path's samples break the budget at 0.0004 m/s:
    the slow end is that floor, said so."""
    calls = []
    got = line_speed_interval(runs([(0.0, 0.0371)], calls, floor=0.0004), 0.02, "j", 0.05)
    assert within(got.low, 0.0004, 0.05) and got.low_bound == BUDGET_FLOOR
    assert within(got.high, 0.0371, 0.05, inside=False)


def held(calls: list, hold: float = 0.4, rest: int = 4300, wait_below: float = 0.0,
         budget: int = 250_000, dt: float = 0.002):
    """A part held upstream ``hold`` m: its path's samples rest + (hold/s − 3 s)/dt, the
    hold not quite 1/s (as the line's delay); past ``budget`` a BudgetError; below
    ``wait_below`` its plans wait; above 0.068 m/s too fast."""

    def plan_at(s):
        calls.append(s)
        n = rest + max(0.0, hold / s - 3.0) / dt
        if n > budget:
            raise BudgetError(f"{s} past the budget")
        if s > 0.068:
            raise LineSpeedError(f"{s} too fast", True, "drifts")
        return SimpleNamespace(speed=s, n=int(n), waits=s < wait_below)

    return plan_at


def test_the_budget_guides_the_slow_end():
    """The slow end is the budget's floor (where the samples reach it): halved and bisected
    down to it unguided; guided by the plans' samples (budget_floor), the same floor to the
    resolution with fewer plans."""
    floor = 0.4 / ((250_000 - 4300) * 0.002 + 3.0)  # where the samples reach the budget
    slow, fast = [], []
    unguided = line_speed_interval(held(slow), 0.2, "j", 0.05)
    guided = line_speed_interval(held(fast), 0.2, "j", 0.05,
                                 budget=lambda p: (p.n, 250_000))
    for got in (unguided, guided):
        assert within(got.low, floor, 0.05) and got.low_bound == BUDGET_FLOOR
        assert got.low_plan.speed == got.low and got.high == unguided.high
    assert len(fast) <= len(slow) - 6, (slow, fast)


def test_the_budget_guide_stops_where_waits_begin_as_unguided():
    """Plans below 0.005 m/s wait: the slow end is the first halving that waits, guided or
    not (the guide's jump lands among the waits and goes back to halving)."""
    got = [line_speed_interval(held([], wait_below=0.005), 0.05, "j", 0.05,
                               floor=lambda p: 0.0001 if p.waits else None, budget=b)
           for b in (None, lambda p: (p.n, 250_000))]
    assert got[0].low == got[1].low == 0.05 / 16 and got[1].low_bound.startswith("waits")


def test_budget_floor_of_two_plans():
    """samples = a + b/s through two points: the speed where they reach the budget."""
    from pollard_pin.painting.line.speeds import budget_floor

    a, b = 1000.0, 20.0
    pts = [(s, a + b / s) for s in (0.05, 0.01)]
    assert budget_floor(pts, 5000.0) == pytest.approx(b / 4000.0, rel=1e-12)
    assert budget_floor(pts[:1], 5000.0) is None and budget_floor(pts, 900.0) is None


def test_interval_is_the_run_about_the_jobs_speed():
    """Two runs, [0.003, 0.007] and [0.011, 0.04] m/s: from 0.02 the run about it (the
    halving meets the gap at 0.01); from 0.005 the other; from a speed too slow for both,
    the first run it doubles into (0.004; 0.008 in the gap). Only the speeds tried are
    planned: a gap the doubling or halving steps over is not seen (docs/model.md §24.3)."""
    spans = [(0.003, 0.007), (0.011, 0.04)]
    about = line_speed_interval(runs(spans, []), 0.02, "j", 0.01)
    assert within(about.low, 0.011, 0.01) and within(about.high, 0.04, 0.01, inside=False)
    assert about.low_bound.startswith("too fast: ")  # the gap's own failure, as it came
    for start in (0.005, 0.001):
        other = line_speed_interval(runs(spans, []), start, "j", 0.01)
        assert within(other.low, 0.003, 0.01) and within(other.high, 0.007, 0.01, False)


def test_interval_over_strategies_is_their_union():
    """A plan_at that tries two stroke strategies, each painting its own run, plans where
    either does: the interval spans both, the fastest is the faster one's."""
    along, across = runs([(0.02, 0.03)], []), runs([(0.004, 0.024)], [])

    def either(s):
        try:
            return along(s)
        except LineSpeedError:
            return across(s)

    got = line_speed_interval(either, 0.012, "j", 0.01)
    assert within(got.low, 0.004, 0.01) and within(got.high, 0.03, 0.01, inside=False)
    fastest, plan = fastest_line_speed(either, 0.012, "j")
    assert within(fastest, 0.03, 0.01, inside=False) and plan.speed == fastest


def test_slow_end_to_its_own_resolution():
    got = line_speed_interval(runs([(0.0031, 0.0371)], []), 0.02, "j", 0.01,
                              slow_resolution=0.2)
    assert within(got.low, 0.0031, 0.2) and within(got.high, 0.0371, 0.01, inside=False)
    assert got.resolution == 0.2  # the coarser stated


def test_both_ends_checked_in_full():
    seen = []
    got = line_speed_interval(runs([(0.01, 0.02)], []), 0.015, "j", 0.05,
                              check=lambda p: seen.append(p.speed) or "checked")
    assert seen == [got.low, got.high] and got.low_plan == got.high_plan == "checked"


def test_no_speed_names_the_binding_constraints():
    calls = []
    with pytest.raises(PlanError) as info:
        line_speed_interval(runs([(0.05, 0.04)], calls), 0.03, "j.toml")
    msg = str(info.value)
    assert msg.startswith("j.toml: no line speed paints the part: too slow at ")
    assert msg.endswith("; binding: slow (reach), fast (motors)") and len(msg) <= 250


def test_the_same_binding_on_both_sides_is_said_once():
    """A motor over its rating whether too slow or too fast (a drawer's program): no line
    speed moves it off, and the refusal says so."""
    with pytest.raises(PlanError) as info:
        line_speed_interval(runs([(0.05, 0.04)], [], slow_why="a motor at 304 % of its rating",
                                 fast_why="a motor at 304 % of its rating"), 0.03, "j.toml")
    msg = str(info.value)
    assert msg.startswith("j.toml: no line speed paints the part: too slow at ")
    assert msg.endswith("; binding: motors on both sides") and len(msg) <= 250


@pytest.mark.parametrize("why, named", [
    ("the program drifts -0.349 m, out of the reach", "reach"),
    ("the path leaves the workspace at t = 3.000 s", "reach"),
    ("a motor at 106 % of its rating", "motors"),
    ("no turnaround keeps the path in reach and the motors within ratings",
     "reach and motors"),
    ("turns at 0.01", "")])
def test_constraint_named(why, named):
    assert constraint(why) == named


@pytest.mark.parametrize("speed", [0.2, 0.001])
def test_a_speed_outside_names_the_interval(speed):
    """Too fast or too slow: the refusal names the run that paints (its fast end within
    1 %, its slow end within 5 %), in one line of at most 250 characters however long the
    planner's own message."""
    def plan_at(s):
        try:
            return runs([(0.0031, 0.0371)], [])(s)
        except LineSpeedError as exc:
            raise LineSpeedError(f"{exc} " + "figures " * 40, exc.too_fast, exc.why) from None

    with pytest.raises(PlanError) as info:
        plan_or_name_fastest(plan_at, speed, "j.toml")
    msg = str(info.value)
    assert len(msg) <= 250 and "\n" not in msg, msg
    assert not isinstance(info.value, LineSpeedError)
    low, high = msg.split("it paints at ")[1].split(" m/s")[0].split("–")
    assert within(float(low), 0.0031, 0.05) and within(float(high), 0.0371, 0.01, False)
    assert msg.endswith("m/s (--max-line-speed)")


def test_no_speed_at_all_refuses_with_both_sides():
    with pytest.raises(PlanError) as info:
        plan_or_name_fastest(runs([(0.05, 0.04)], []), 0.03, "j.toml")
    msg = str(info.value)
    assert "no line speed paints the part" in msg and "binding: " in msg and len(msg) <= 250
    assert msg.startswith("j.toml: 0.03 too slow; no line speed paints the part: too slow "
                          "at "), msg
    assert not isinstance(info.value, LineSpeedError)



def test_too_fast_down_to_the_budget_floor_says_so():
    """Every speed too fast (strokes stepping from the trailing end drift s·T + L > 0):
    halved down to the sample budget's floor, the refusal keeps the job's speed's failure and
    says no slower line paints it (it read the floor's own words, as if to go faster)."""
    def plan_at(s):
        if s < 1e-4:
            raise BudgetError(f"j.toml: line.speed = {s:.3g} m/s carries the part too little")
        raise LineSpeedError(f"at line speed {s:.4g} m/s the program drifts +1.985 m", True,
                             "the program drifts +1.985 m")

    with pytest.raises(PlanError) as info:
        plan_or_name_fastest(plan_at, 0.03, "j.toml")
    assert str(info.value) == ("j.toml: at line speed 0.03 m/s the program drifts +1.985 m; "
                               "no slower line paints it, down to the sample budget's floor")
    assert not isinstance(info.value, (LineSpeedError, BudgetError))

# --- a real job ----------------------------------------------------------------------------------
def test_example_line_interval(robot, act, line_job, line_plan, slow_plan):
    """examples/line.toml: its speed 0.03 m/s inside the interval (to 10 %, its plan there
    the fixture's). Just past the fast end plan_line itself refuses as too fast; the slow end
    is the first plan that waits at its turnarounds (docs/model.md §24.1), its bound naming
    the budget's floor below it, and a slower line (0.01 m/s, the package's ``slow_plan``,
    tests/examples_planned.py) paints too, waiting longer."""
    planner = line_planner(robot, line_job, act)
    got = line_speed_interval(lambda s: line_plan if s == line_plan.speed else planner(s),
                              line_job.line.speed, line_job.source, 0.1,
                              floor=waiting_floor)
    assert got.low < line_job.line.speed < got.high
    assert got.low_plan.speed == got.low and got.high_plan.speed == got.high
    assert got.low_bound.startswith("waits: ") and got.high_bound.startswith("too fast: ")
    assert dwell_time(got.low_plan.relative) > 0 and dwell_time(line_plan.relative) == 0
    floor = waiting_floor(got.low_plan)
    assert f"≈ {floor:.2g} m/s" in got.low_bound and 0 < floor < got.low
    slower = slow_plan
    assert floor < slower.speed < 0.8 * got.low
    assert dwell_time(slower.relative) > dwell_time(got.low_plan.relative)
    with pytest.raises(LineSpeedError) as fast:
        plan_line(robot, line_job, act, got.high * 1.11, clearance=False)
    assert fast.value.too_fast


def test_a_plan_that_waits_ends_the_slow_search():
    """The slow side stops at the first plan the floor callback says waits: no slower speed
    is tried, and the bound names the floor it gave."""
    tried = []

    class Plan:
        def __init__(self, s):
            self.speed = s

    def plan_at(s):
        tried.append(s)
        if s > 0.04:
            raise LineSpeedError("too fast", True, "a motor at 104 % of its rating")
        return Plan(s)

    got = line_speed_interval(plan_at, 0.03, "j.toml", 0.05,
                              floor=lambda p: 0.001 if p.speed < 0.02 else None)
    assert got.low == 0.015 and min(tried) == 0.015
    assert got.low_bound == waits_bound(0.001) and "0.001 m/s" in got.low_bound


def test_a_refused_speed_is_refused_again_without_planning():
    """remembering: a speed refused once is refused again in the same words (message,
    side, why, hint) without a second plan; a speed that plans is planned every time."""
    from pollard_pin.painting.errors import LineSpeedError
    from pollard_pin.painting.line.speeds import remembering

    calls = []

    def plan_at(speed):
        calls.append(speed)
        if speed > 1.0:
            raise LineSpeedError(f"too fast at {speed}", True, "the reach", 0.5)
        return speed

    memo = remembering(plan_at)
    said = []
    for _ in range(2):
        with pytest.raises(LineSpeedError) as exc:
            memo(2.0)
        said.append((str(exc.value), exc.value.too_fast, exc.value.why, exc.value.hint))
    assert calls == [2.0] and said[0] == said[1] == ("too fast at 2.0", True, "the reach", 0.5)
    assert memo(0.5) == memo(0.5) == 0.5 and calls == [2.0, 0.5, 0.5]
