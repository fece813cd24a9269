"""One design judged (synthesis/evaluation.py, docs/model.md §31.3): the screen's verdicts on the
example, and one full evaluation of a small line job shared by the module."""
import math

import pytest

import pollard_pin as pp
from pollard_pin.errors import InputError
from pollard_pin.synthesis import (
    CONSTRAINTS,
    OBJECTIVES,
    SENSES,
    baseline_values,
    evaluate,
    load_catalogue,
    load_space,
    prepare,
    space_from_dict,
)

STRIP = {"panel": {"center": [0.70, -0.5, 0.16], "normal": [-1.0, 0.0, 0.0], "width": 0.30,
                   "height": 0.10},
         "gun": {"standoff": 0.15, "sigma": 0.010, "flow": 1.5e-7},
         "job": {"thickness": 25e-6}, "line": {"speed": 0.03, "direction": [0.0, 1.0, 0.0]}}


@pytest.fixture(scope="module")
def example():
    space = load_space("examples/design/space.toml")
    return space, prepare("examples/design/job.toml", space)


@pytest.fixture(scope="module")
def strip():
    """A 0.30 × 0.10 m strip at 0.03 m/s, one robot with the shipped motors: planned once."""
    cat = load_catalogue("examples/design/motors.toml")
    space = space_from_dict({"robots": 1, "motors": {
        "base": ["theta21", "theta21_1", "theta21_2"],
        "wrist": ["theta1615", "theta1716", "theta1817"]}}, catalogue=cat)
    ctx = prepare(pp.job_from_dict(STRIP), space)
    values = baseline_values(space)
    return space, ctx, values, evaluate(values, ctx)


def test_objectives_documented():
    assert set(SENSES) == set(OBJECTIVES) and set(SENSES.values()) == {"max", "min"}
    assert CONSTRAINTS[0] == "home"


def test_screen_thesis_needs_two_robots(example):
    space, ctx = example
    base = baseline_values(space)
    one = evaluate(base, ctx, "screen")
    assert one.level == "screen" and not one.feasible and one.binding == "reach"
    assert one.constraints["reach"] > 0 and one.figures["robots_needed"] == 2
    two = evaluate({**base, "robots": 2}, ctx, "screen")
    assert two.feasible and two.binding is None and two.objectives["robots"] == 2
    assert two.objectives["moving_mass"] == pytest.approx(2 * one.objectives["moving_mass"])
    assert one.objective_vector() == tuple(one.objectives[k] for k in OBJECTIVES)
    c = one.constraint_vector()
    assert len(c) == len(CONSTRAINTS) and c[CONSTRAINTS.index("reach")] > 0
    assert c[CONSTRAINTS.index("film")] == 0.0  # not computed by the screen
    assert max(two.constraint_vector()) <= 0


def test_the_baseline_is_the_thesis_robot_in_the_cell_it_paints_in(example):
    """The study's first row: with the context, the fewest robots whose screen passes (two for
    the door, as the screen's own count says), not the space's lower bound."""
    space, ctx = example
    assert baseline_values(space)["robots"] == space.robots[0] == 1
    base = baseline_values(space, ctx)
    assert base["robots"] == evaluate(baseline_values(space), ctx, "screen").figures[
        "robots_needed"] == 2
    assert evaluate(base, ctx, "screen").feasible


def test_screen_scaled_design_alone(example):
    """×1.7 standing 0.3 m back paints the door alone (its full plan: one robot), ×1.6 does
    not: its band holds the door and its run-ons, not the turnarounds past them, where the
    planner refuses it."""
    from pollard_pin.synthesis.screen import turn_runon

    space, ctx = example
    v = {**baseline_values(space), "scale.arms": 1.7, "scale.links": 1.7, "place.back": 0.3,
         "motor.base": 2, "robots": 1}
    ev = evaluate(v, ctx, "screen")
    assert ev.feasible and ev.figures["robots_needed"] == 1
    run = turn_runon(ctx.job)
    assert ev.figures["band_m"] >= 0.38 + 2 * 0.04 + 2 * run - 1e-9
    # standing at the origin the longer robot reaches less of the door
    close = evaluate({**v, "place.back": 0.0}, ctx, "screen")
    assert close.binding == "reach" and close.figures["band_m"] < ev.figures["band_m"]
    short = evaluate({**v, "scale.arms": 1.6, "scale.links": 1.6}, ctx, "screen")
    assert short.binding == "reach" and short.figures["robots_needed"] == 2
    assert 0.38 + 2 * 0.04 - 1e-9 <= short.figures["band_m"] < 0.38 + 2 * 0.04 + 2 * run


def test_unreachable_home_is_infeasible_not_raised(example):
    space, ctx = example
    ev = evaluate({**baseline_values(space), "scale.links": 0.5}, ctx, "screen")
    assert not ev.feasible and ev.binding == "home" and "home pose" in ev.message
    with pytest.raises(InputError, match="level = 'fast': expected 'screen', 'search' or "
                                         "'full'"):
        evaluate({}, ctx, "fast")


def test_full_evaluation_of_a_strip(strip):
    space, ctx, values, ev = strip
    assert ev.level == "full" and ev.feasible, ev.message
    assert all(v <= 0 for v in ev.constraints.values())
    o = ev.objectives
    assert set(o) == set(OBJECTIVES) and all(math.isfinite(x) for x in o.values())
    assert o["robots"] == 1 and 0 < o["motor_use"] <= 1 and o["parts_per_hour"] > 0
    # kmin of the shipped drives over the program: the workspace map's order (kN/m)
    assert 1e3 < o["kmin"] < 1e6
    assert ev.figures["film_within_5pct"] >= 0.99
    assert "[[robot]]" in ev.robots_toml and "[chain0]" in ev.params_toml
    # the job by its name, not where it was (the written folder moves)
    assert f"pollard-pin design for {ctx.job.source}" in ev.robots_toml.splitlines()[0]
    assert "/" not in ev.robots_toml.splitlines()[0].split(" for ")[1]
    assert "[theta21]" in ev.actuators_toml


@pytest.fixture(scope="module")
def strip_searched(strip):
    """The strip judged at the search's fidelity (the film at σ/2, every 4th sample's
    clearance, the motor check on the path's own samples): planned once."""
    from dataclasses import replace

    from pollard_pin.synthesis import SearchFidelity

    space, ctx, values, _ = strip
    return evaluate(values, replace(ctx, search=SearchFidelity()), "search")


def test_the_search_judges_the_strip_as_the_full_plan_does(strip, strip_searched):
    """The search's plan is the full level's: the same cycle, kmin and mass; its motor use
    at most the full check's; its film and clearance, on a coarser grid and fewer samples,
    within the bounds docs/model.md §31.5 states (each achieves ~1e-14 here)."""
    exact, ev = strip[3], strip_searched
    assert ev.level == "search" and ev.feasible and exact.level == "full"
    for name in ("parts_per_hour", "robots", "kmin", "moving_mass"):
        assert ev.objectives[name] == exact.objectives[name], name
    assert ev.figures["cycle_s"] == exact.figures["cycle_s"]
    assert exact.objectives["motor_use"] - 0.01 <= ev.objectives["motor_use"] <= \
        exact.objectives["motor_use"] + 1e-12
    assert ev.figures["film_within_5pct"] == pytest.approx(exact.figures["film_within_5pct"],
                                                           abs=0.01)
    for k in ("film_min_um", "film_max_um"):  # the target's 25 µm: 1e-3 µm is 4e-5 of it
        assert ev.figures[k] == pytest.approx(exact.figures[k], abs=1e-3), k
    # fewer samples: never closer than the full check found, and within 1 mm of it
    assert exact.figures["clearance_m"] - 1e-12 <= ev.figures["clearance_m"] <= \
        exact.figures["clearance_m"] + 1e-3
    assert ev.params_toml == exact.params_toml and ev.robots_toml == exact.robots_toml


def test_a_design_refused_at_the_line_speed_keeps_its_binding_without_the_interval(example):
    """The search refuses a design at the job's line speed as that speed's plan failed
    (SearchFidelity.name_speeds False, docs/model.md §31.5): the binding constraint read from
    that refusal, no interval of speeds that paint it sought. Every length ×1.1 with the W10
    base motors, two robots at the origin (a design the default study refused): no
    turnaround keeps the path in reach and the motors within their ratings at 0.012 m/s."""
    from dataclasses import replace

    from pollard_pin.synthesis import SearchFidelity

    space, ctx = example
    values = {"limits.theta21.upper": -35.0, "scale.arms": 1.1, "scale.links": 1.1,
              "motor.base": 5, "ratio.base": 1, "motor.wrist": 4, "ratio.wrist": 0,
              "place.back": 0.0, "robots": 2}
    ev = evaluate(values, replace(ctx, search=SearchFidelity()), "search")
    assert ev.level == "search" and not ev.feasible and ev.binding == "motors"
    assert ev.constraints["plan"] == 1.0 and ev.constraints["motors"] == pytest.approx(0.01)
    assert "at line speed 0.012 m/s no ramp or turnaround" in ev.message
    assert "paints at" not in ev.message and "no line speed paints" not in ev.message
    assert ev.objectives["parts_per_hour"] == 0.0 and ev.objectives["kmin"] == 0.0


def test_full_evaluation_reproduced_by_paint(strip, tmp_path):
    """paint with the design's files and robots gives the evaluation's figures."""
    space, ctx, values, ev = strip
    (tmp_path / "p.toml").write_text(ev.params_toml, encoding="utf-8")
    (tmp_path / "a.toml").write_text(ev.actuators_toml, encoding="utf-8")
    robot = pp.load(pp.load_params(tmp_path / "p.toml"))
    robots = pp.job_from_dict({**STRIP, "robot": [{"name": "robot1", "base": [0, 0, 0]}]})
    assert robots.robots  # the job reader takes [[robot]] tables
    assert robot.params.total_mass == pytest.approx(ev.objectives["moving_mass"])


def test_context_travels_to_workers(example):
    """A Dask or process worker gets the context pickled: it evaluates the same."""
    import pickle

    space, ctx = example
    back = pickle.loads(pickle.dumps(ctx))
    v = {**baseline_values(space), "robots": 2}
    a, b = evaluate(v, ctx, "screen"), evaluate(v, back, "screen")
    assert a.constraints == b.constraints and a.objectives == b.objectives
    assert back.space.fingerprint() == space.fingerprint()


def test_placed_job_is_the_job_the_evaluation_paints(strip):
    """The robots the full evaluation proposes and writes (robots.toml) are placed_job's; a
    job without a line is painted as it is."""
    import tomllib
    from dataclasses import replace

    from pollard_pin.synthesis.concrete import build
    from pollard_pin.synthesis.layout import placed_job

    space, ctx, values, ev = strip
    robot = pp.load(build(values, space).params)
    job = placed_job(values, ctx, robot, 1)
    written = tomllib.loads(ev.robots_toml)["robot"]
    assert [r.name for r in job.robots] == [r["name"] for r in written]
    assert [list(r.base) for r in job.robots] == [r["base"] for r in written]
    still = replace(ctx, job=replace(ctx.job, line=None))
    assert placed_job(values, still, robot, 1) is still.job


def test_the_search_notes_make_the_exact_plan_without_searching(strip, strip_searched,
                                                                 monkeypatch):
    """The strip planned exactly with the notes of its search (Evaluation.notes, plain data:
    the layout, and the line plan's turnarounds, delay and return by the fingerprint of what
    that search read) searches nothing again and is the full evaluation from scratch to the
    bit: objectives, constraints, figures and files (docs/model.md §31.5)."""
    import json

    import pollard_pin.painting.line.search as search
    import pollard_pin.painting.line.world as world

    space, ctx, values, exact = strip
    notes = json.loads(json.dumps(strip_searched.notes))  # as the study stores them
    assert notes == strip_searched.notes and "layout" in notes and len(notes) == 2
    # the search's check passed at the path's own samples: the exact plan skips that screen
    assert all(v[world.SAMPLES_OK] for k, v in notes.items() if k != "layout")
    searched = []
    real = search.searched
    monkeypatch.setattr(world, "searched", lambda *a: searched.append(1) or real(*a))
    ev = evaluate(values, ctx, "full", notes=notes)
    assert not searched and ev.level == "full" and ev.notes is None
    timed = ("screen_s", "full_s")
    assert {k: v for k, v in ev.figures.items() if k not in timed} == \
        {k: v for k, v in exact.figures.items() if k not in timed}
    assert (ev.objectives, ev.constraints, ev.binding, ev.feasible) == \
        (exact.objectives, exact.constraints, exact.binding, exact.feasible)
    assert (ev.params_toml, ev.actuators_toml, ev.robots_toml) == \
        (exact.params_toml, exact.actuators_toml, exact.robots_toml)
    # the notes hold the search, not its verdict: the exact motor check still runs, and
    # where it refuses (here made to, once), the design is refused as from scratch
    refused = []

    def once(worst, speed, too_fast, least=""):
        if not refused:
            refused.append(worst)
            raise world.LineSpeedError(f"at line speed {speed:.4g} m/s a motor needs "
                                        f"{100 * worst:.0f} % of its peak torque or speed",
                                        too_fast, "a motor over its rating")
    monkeypatch.setattr(world, "motors_within", once)
    from dataclasses import replace

    named = replace(ctx, options=replace(ctx.options, policy=replace(
        ctx.options.policy, name_speeds=False)))  # that speed's refusal, no interval sought
    ev = evaluate(values, named, "full", notes=notes)
    assert refused and not searched and not ev.feasible and ev.binding == "motors"
    assert ev.constraints["plan"] == 1.0 and "a motor needs" in ev.message
