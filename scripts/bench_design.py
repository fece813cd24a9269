#!/usr/bin/env python
"""Where a design evaluation's CPU time goes (docs/model.md §31.5), for the example's designs
of one, two and three robots: the search's and the full evaluation, the full one made with the
search's notes (as the study plans its front again: the layout and the line plans' searches
taken, only the checks made), and the full one's parts timed alone — the layout, the plan (at
the search's motor check and at the full one's), the clearances (every 4th sample, every
sample), the film (σ/2, σ/3) — and whether the search's plan is the full one's; then the
200-evaluation study projected on two cores from them; and a design the planner refuses at
the job's line speed, searched with and without the interval of speeds that paint it.

    python scripts/bench_design.py            (benchmark.py's design section prints it too)
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

import pollard_pin as pp

REPO = Path(__file__).resolve().parents[1]

#: The example's designs by robot count (examples/design/): one robot, the study's choice
#: (×1.7, S200 base motors, 0.3 m back); two: the thesis robot; three: a front design of a
#: 200-evaluation study (×1.35 arms, ×1.47 links, S200 base and W10 wrist motors, 0.1 m back).
DESIGNS = {
    1: {"limits.theta21.upper": -35.0, "scale.arms": 1.7, "scale.links": 1.7, "motor.base": 3,
        "ratio.base": 1, "motor.wrist": 4, "ratio.wrist": 0, "place.back": 0.3, "robots": 1},
    2: None,  # the thesis robot: baseline_values
    3: {"limits.theta21.upper": -21.122299070355538, "scale.arms": 1.3451347483471792,
        "scale.links": 1.465018298108687, "motor.base": 3, "ratio.base": 0, "motor.wrist": 5,
        "ratio.wrist": 0, "place.back": 0.10276665747466765, "robots": 3},
}
#: A design the planner refuses at the job's line speed (one robot, every length ×1.8, S200
#: base motors behind 50:1, S40 wrist motors, 0.32 m back): a motor needs 100 % of its rating
#: at 0.012 m/s; the interval that paints, 0.01238–0.01295 m/s, searched only when named.
REFUSED = {"limits.theta21.upper": -6.902538076137084, "scale.arms": 1.798908373153903,
           "scale.links": 1.798908373153903, "motor.base": 3, "ratio.base": 0, "motor.wrist": 1,
           "ratio.wrist": 1, "place.back": 0.3205250242071094, "robots": 1}
#: A 200-evaluation study of the example (the default, docs/model.md §31.5; its exact front in
#: tests/data/design/front_200.csv): the designs the search planned, feasible or not, and
#: those planned again, by robot count: its ε-front at the default FrontResolution (19) and
#: the thesis robot (the baseline); EXACT_FRONT: its exact Pareto front (47) and the baseline,
#: as the study planned again before the ε-front.
SEARCHED = {1: 6, 2: 44, 3: 85}
FRONT = {1: 3, 2: 6, 3: 11}
EXACT_FRONT = {1: 5, 2: 15, 3: 28}
SCREENS = 200 + 495  # the study's screens and the ladder's
SCREEN_CPU = 0.04  # [s] a screen (docs/model.md §31.4)


def _cpu(fn):
    t0 = time.process_time()
    out = fn()
    return out, time.process_time() - t0


def breakdown(n: int, values: dict, ctx, search_ctx) -> dict:
    """CPU seconds of design ``values`` (``n`` robots): ``search`` and ``full`` evaluations,
    ``noted`` (the full one with the search's notes) and the full one's parts, each alone;
    ``same``: the search's plan is the full one's, and the noted evaluation the full one's."""
    from pollard_pin.painting.api import film_spacing_of
    from pollard_pin.painting.cell.frames import robot_model_in_base
    from pollard_pin.painting.cell.plan import cell_clearance_of, cell_planner
    from pollard_pin.painting.film.cell import cell_panel_film
    from pollard_pin.painting.line.panel import line_clearance
    from pollard_pin.synthesis import evaluate
    from pollard_pin.synthesis.concrete import build
    from pollard_pin.synthesis.layout import placed_job

    out = {}
    searched, out["search"] = _cpu(lambda: evaluate(values, search_ctx, "search"))
    full, out["full"] = _cpu(lambda: evaluate(values, ctx, "full"))
    noted, out["noted"] = _cpu(lambda: evaluate(values, ctx, "full", notes=searched.notes))
    out["feasible"] = searched.feasible and full.feasible
    design = build(values, ctx.space)
    robot = pp.load(design.params)
    job, out["layout"] = _cpu(lambda: placed_job(values, ctx, robot, n))
    plans = {}
    for name, options in (("search", search_ctx.search.options(ctx.options, ctx.job.sigma)),
                          ("full", ctx.options)):
        policy = options.policy
        plan, out[f"plan_{name}"] = _cpu(lambda p=policy: cell_planner(
            robot, job, design.actuators, None, None, p)(job.line.speed))
        _, out[f"clearance_{name}"] = _cpu(lambda p=policy, c=plan: (
            [line_clearance(robot_model_in_base(robot, r.robot), r.plan, p.clearance_stride)
             for r in c.robots], cell_clearance_of(robot, c, p.clearance_stride)))
        res = film_spacing_of(job, options.resolution)
        _, out[f"film_{name}"] = _cpu(lambda c=plan, r=res: cell_panel_film(c, r))
        plans[name] = plan
    out["same"] = all(np.array_equal(a.plan.trajectory.t, b.plan.trajectory.t)
                      and np.array_equal(a.plan.trajectory.poses, b.plan.trajectory.poses)
                      for a, b in zip(plans["search"].robots, plans["full"].robots))
    out["same"] = out["same"] and (noted.objectives, noted.constraints) == (
        full.objectives, full.constraints)
    out["motor_use"] = (searched.objectives["motor_use"], full.objectives["motor_use"])
    return out


def refused_breakdown(ctx, search_ctx) -> dict:
    """CPU seconds of the search's evaluation of :data:`REFUSED` without the interval of
    line speeds that paint it (the search's own, ``SearchFidelity.name_speeds`` False) and
    with it (``True``, as before), and their binding constraints."""
    from pollard_pin.synthesis import SearchFidelity, evaluate, prepare

    named_ctx = prepare(ctx.job, ctx.space, search=SearchFidelity(name_speeds=True))
    out = {}
    for name, c in (("search", search_ctx), ("named", named_ctx)):
        ev, out[name] = _cpu(lambda c=c: evaluate(REFUSED, c, "search"))
        out[f"binding_{name}"] = ev.binding
        out[f"constraints_{name}"] = ev.constraints
    print(f"  a design refused at the line speed (one robot): search {out['search']:.1f} s, "
          f"{out['named']:.1f} s with the interval of speeds that paint it named (binding "
          f"{out['binding_search']}, {out['binding_named']}; the same constraints: "
          f"{out['constraints_search'] == out['constraints_named']})")
    return out


def design_breakdown() -> dict:
    """Print the breakdown of :data:`DESIGNS`, the 200-evaluation projection and the refused
    design's search; the rows by robot count, and ``"refused"``."""
    from pollard_pin.synthesis import SearchFidelity, baseline_values, load_space, prepare

    job = pp.load_job(REPO / "examples" / "design" / "job.toml")
    space = load_space(REPO / "examples" / "design" / "space.toml")
    ctx = prepare(job, space)
    search_ctx = prepare(job, space, search=SearchFidelity())
    from pollard_pin.synthesis import evaluate

    evaluate(DESIGNS[1], search_ctx, "search")  # warm-up: the planner's imports and caches
    rows = {}
    print("\ndesign evaluation, CPU [s] (examples/design; plan: the cell's programs with their "
          "motor check, no clearance; the search's at its fidelity, the full one's exact)")
    head = ("robots", "search", "full", "noted", "layout", "plan s", "plan f", "clear s",
            "clear f", "film s", "film f", "same plan")
    print("  " + "".join(f"{h:>10s}" for h in head))
    for n, values in DESIGNS.items():
        values = baseline_values(space, ctx) if values is None else values
        b = breakdown(n, values, ctx, search_ctx)
        rows[n] = b
        cells = [b[k] for k in ("search", "full", "noted", "layout", "plan_search", "plan_full",
                                "clearance_search", "clearance_full", "film_search",
                                "film_full")]
        print(f"  {n:>10d}" + "".join(f"{c:10.1f}" for c in cells) + f"{b['same']!s:>10s}")
    print("  the full evaluation's share that is planning (layout and the plan at the "
          "search's motor check): " + ", ".join(
              f"{n} robot{'s' * (n > 1)} {(r['layout'] + r['plan_search']) / r['full']:.0%}"
              for n, r in rows.items()))
    # the 200-evaluation study on two cores: the screens, the search's plans, the front
    # planned again in full from scratch — or with the search's notes, as the study does
    screens = SCREENS * SCREEN_CPU
    search = sum(k * rows[n]["search"] for n, k in SEARCHED.items())
    for what, front in (("ε-front", FRONT), ("exact front", EXACT_FRONT)):
        replan = sum(k * rows[n]["full"] for n, k in front.items())
        noted = sum(k * rows[n]["noted"] for n, k in front.items())
        print(f"  a 200-evaluation study on 2 cores, projected [min], its {what} of "
              f"{sum(front.values()) - 1} and the baseline planned again: the search "
              f"{(screens + search) / 120:.1f}, the front from scratch {replan / 120:.1f} "
              f"(total {(screens + search + replan) / 120:.1f}), with the search's notes "
              f"{noted / 120:.1f} (total {(screens + search + noted) / 120:.1f}; CPU "
              f"{screens + search + noted:.0f} s)")
    rows["refused"] = refused_breakdown(ctx, search_ctx)
    return rows


if __name__ == "__main__":
    design_breakdown()
    sys.exit(0)
