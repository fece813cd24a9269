"""The line's shared phases (paint/line/phases.py, docs/model.md §24): the relative program's
interface and the fastest-speed search, against stand-in planners whose answers are known;
the world path of real plans is tested in test_line.py (a panel) and test_line_part.py (a
part)."""
from types import SimpleNamespace

import numpy as np
import pytest

from pollard_pin.paint.errors import PlanError
from pollard_pin.paint.line.phases import (
    LineSpeedError,
    Relative,
    fastest_line_speed,
    plan_or_name_fastest,
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
    calls = []
    with pytest.raises(PlanError) as info:
        plan_or_name_fastest(planner(0.01, 0.0371, calls), 0.2, "j.toml")
    msg = str(info.value)
    assert msg.startswith("0.2 too fast; the fastest line speed that paints it is ")
    named = float(msg.split(" is ")[1].split()[0])
    assert 0.0371 / 1.01 <= named <= 0.0371
    assert not isinstance(info.value, LineSpeedError)  # not to be searched again
    calls.clear()
    assert plan_or_name_fastest(planner(0.01, 0.0371, calls), 0.03, "j").speed == 0.03
    assert calls == [0.03]


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
