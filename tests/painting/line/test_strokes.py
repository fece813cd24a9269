"""The strokes' direction on a line, a planned choice (paint/line/strokes.py, docs/model.md
§24.2): auto keeps the shortest cycle of those that paint, a forced strategy that cannot
paint is refused naming it; on examples/line.toml's strip and a short one."""
from dataclasses import dataclass, replace
from types import SimpleNamespace

import pytest

from pollard_pin.errors import InputError
from pollard_pin.painting.errors import LineReachError, LineSpeedError, PlanError
from pollard_pin.painting.line.panel import plan_line
from pollard_pin.painting.line.strokes import Strokes, candidates, shortest
from pollard_pin.painting.policy import PlannerPolicy


def test_candidates():
    assert candidates() == (Strokes("across", "leading"), Strokes("along", None))
    assert candidates(PlannerPolicy(strokes="across", step_from="trailing")) == (
        Strokes("across", "trailing"),)
    assert candidates(PlannerPolicy(strokes="along")) == (Strokes("along", None),)


@dataclass(frozen=True)
class _Plan:
    strokes: Strokes
    times: SimpleNamespace
    clearance: object = None


def _plans(cycles: dict):
    def plan_with(s):
        c = cycles[s.direction]
        if isinstance(c, Exception):
            raise c
        return _Plan(s, SimpleNamespace(cycle=c))
    return plan_with


def _clear(refused: set, seen: list):
    """A clearance check refusing the strategies named in ``refused``."""
    from pollard_pin.painting.errors import ClearanceError

    def check(plan):
        seen.append(plan.strokes.direction)
        if plan.strokes.direction in refused:
            raise ClearanceError(f"{plan.strokes.direction}: the gun body 3 mm from the part")
        return replace(plan, clearance="ok")
    return check


def test_auto_chooses_among_the_strategies_that_pass_the_clearance():
    """The shortest cycle refused by the clearance: auto keeps the other, says why; the
    check is run only where the choice depends on it (two planned) unless ``always``."""
    seen = []
    out = shortest(_plans({"across": 30.0, "along": 11.0}), check=_clear({"along"}, seen))
    assert out.strokes.direction == "across" and out.clearance == "ok"
    assert seen == ["along", "across"]
    assert out.strokes.why.startswith("auto: the shortest cycle that paints, 30.00 s; along: "
                                      "along: the gun body 3 mm")
    seen.clear()
    out = shortest(_plans({"across": 30.0, "along": 11.0}), check=_clear(set(), seen))
    assert out.strokes.direction == "along" and seen == ["along"]
    assert out.strokes.why == ("auto: the shortest cycle that paints, 11.00 s; across from the "
                               "leading end: cycle 30.00 s")
    seen.clear()
    out = shortest(_plans({"across": 30.0, "along": PlanError("out of reach")}),
                   check=_clear(set(), seen))
    assert seen == [] and out.clearance is None  # one planned: left to the plan's own check
    assert out.strokes.why.endswith("; along: out of reach")
    from pollard_pin.painting.errors import ClearanceError
    with pytest.raises(ClearanceError, match="^along: the gun"):  # both refused: the shortest's
        shortest(_plans({"across": 30.0, "along": 11.0}),
                 check=_clear({"along", "across"}, []))
    forced = shortest(_plans({"across": 30.0}), PlannerPolicy(strokes="across"),
                      check=_clear(set(), seen), always=True)
    assert forced.clearance == "ok" and forced.strokes.why == "forced"


def test_auto_keeps_the_shortest_cycle_that_paints():
    assert shortest(_plans({"across": 30.0, "along": 11.0})).strokes.direction == "along"
    assert shortest(_plans({"across": 10.0, "along": 11.0})).strokes.direction == "across"
    out = shortest(_plans({"across": 30.0, "along": PlanError("out of reach")}))
    assert out.strokes.direction == "across"
    out = shortest(_plans({"across": 30.0, "along": InputError("no layout that way")}))
    assert out.strokes.direction == "across"  # a later strategy's bad input: no candidate
    with pytest.raises(InputError):  # the first one's is the job's
        shortest(_plans({"across": InputError("bad"), "along": 3.0}))
    with pytest.raises(LineSpeedError, match="^drifts$"):  # none: the first one's error
        shortest(_plans({"across": LineSpeedError("drifts", True), "along": PlanError("x")}))


def test_a_forced_strategy_is_named_and_keeps_its_sense():
    with pytest.raises(LineSpeedError, match=r"^strokes across the travel, stepping from the "
                       r"trailing end \(forced\): drifts") as info:
        shortest(_plans({"across": LineSpeedError("drifts", False, "why", 0.3)}),
                 PlannerPolicy(strokes="across", step_from="trailing"))
    assert (info.value.too_fast, info.value.why, info.value.hint) == (False, "why", 0.3)


def test_along_a_part_longer_than_the_reach_is_refused(robot, line_job, act):
    """examples/line.toml's 0.90 m strip: strokes along it are longer than the reach."""
    with pytest.raises(LineReachError, match=r"^strokes along the travel \(forced\): .*out "
                       "of reach"):
        plan_line(robot, line_job, act, clearance=False, policy=PlannerPolicy(strokes="along"))


def test_auto_picks_the_shorter_cycle(robot, line_job, act, monkeypatch):
    """A 0.30 m strip at 0.01 m/s: across it the program waits for the line (≈ 34 s), along
    it the strokes are done as it passes (≈ 11 s); auto keeps along. The plan across is the
    one auto made (what --strokes across plans: the same call), not made twice."""
    from pollard_pin.painting.line import panel

    made = []
    plan_panel = panel._plan_panel
    monkeypatch.setattr(panel, "_plan_panel", lambda *a: made.append(plan_panel(*a)) or made[-1])
    job = replace(line_job, width=0.3)
    auto = plan_line(robot, job, act, 0.01, clearance=False)
    (across,) = [p for p in made if p.strokes.direction == "across"]
    assert across.strokes.direction == "across" and across.strokes.dwell > 0
    assert replace(auto.strokes, why="") == Strokes("along", None, 0.0)
    assert auto.strokes.why == ("auto: the shortest cycle that paints, "
                                f"{auto.times.cycle:.2f} s; across from the leading end: "
                                f"cycle {across.times.cycle:.2f} s")
    assert auto.times.cycle < 0.5 * across.times.cycle


def test_a_forced_refusal_drops_the_jobs_source():
    """A refusal that leads with the job's file (the sample budget's) keeps its words after
    the forced strategy's name, not the file's name alone (seen: "… (forced): j.toml")."""
    from pollard_pin.painting.errors import BudgetError

    words = ("line.speed = 1e-05 m/s carries the part 0.005 m in the longest path the budget "
             "allows (250000 samples, 500 s): give at least 1e-05 m/s, in m/s, or no [line] "
             "for a still part")
    with pytest.raises(BudgetError) as info:
        shortest(_plans({"across": BudgetError(f"j.toml: {words}")}),
                 PlannerPolicy(strokes="across", step_from="trailing"), source="j.toml")
    said = str(info.value)
    assert said.startswith("strokes across the travel, stepping from the trailing end "
                           "(forced): line.speed = 1e-05 m/s carries the part 0.005 m")
    assert "j.toml" not in said and len(said) <= 250
