"""The paint sections of scripts/benchmark.py: a panel (docs/model.md §21), parts' meshes
(§23) and jobs on a moving line (§24), each timed as the CLI runs it, in seconds."""
from __future__ import annotations

import math
import time
from pathlib import Path

import pollard_pin as pp

REPO = Path(__file__).resolve().parents[1]


def paint_section(robot, repeats: int) -> None:
    """Paint planning (docs/model.md §21) of examples/paint.toml and its film map; the issue's
    budget is 10 s for both."""
    from pollard_pin.paint.film import plan_film

    examples = REPO / "examples"
    act = pp.load_actuators(examples / "actuators.toml")
    job = pp.load_job(examples / "paint.toml")
    plans, films = [], []
    for _ in range(repeats):
        t0 = time.perf_counter()
        plan = pp.plan_paint(robot, job, act)
        t1 = time.perf_counter()
        _, _, pts, f = plan_film(plan)
        plans.append(t1 - t0)
        films.append(time.perf_counter() - t1)
    print(f"\npaint planning (examples/paint.toml), best of {repeats} runs [s]")
    print(f"  plan {min(plans):.2f}, film map {min(films):.2f} ({pts.shape[0] * pts.shape[1]} "
          f"points × {len(plan.trajectory)} samples); cycle {plan.cycle_time:.3f} s")


def parts_section(robot, big_faces: int = 195_000) -> None:
    """Painting parts' meshes (docs/model.md §23): plan and film of each shipped example
    (budget 15 s each), and the film of a curved panel tessellated into about ``big_faces``
    triangles (the face budget is 200,000; the time budget 60 s, memory bounded). One run each."""
    import resource

    from pollard_pin.paint.mesh import make_part
    from pollard_pin.paint.shapes import curved_panel
    from pollard_pin.paint.surface_plan import load_job_part, plan_surface, surface_film

    act = pp.load_actuators(REPO / "examples" / "actuators.toml")
    print("\npainting parts (examples/parts/*.toml), one run each [s]")
    for path in sorted((REPO / "examples" / "parts").glob("*.toml")):
        job = pp.load_job(path)
        part = load_job_part(job)
        t0 = time.perf_counter()
        plan = plan_surface(robot, job, act, part)
        t1 = time.perf_counter()
        pts, _, _, _ = surface_film(plan)
        t2 = time.perf_counter()
        print(f"  {path.name:<20s} {len(part.faces):7d} faces: plan {t1 - t0:5.2f}, film "
              f"{t2 - t1:5.2f} ({len(pts.points)} points × {len(plan.trajectory)} samples)")
    job = pp.load_job(REPO / "examples" / "parts" / "curved_panel.toml")
    # 4 faces per grid cell of the extruded sheet (front and back): the step for big_faces
    step = math.sqrt(4 * 0.24 * 0.10 / big_faces)
    mesh = curved_panel(step=step)
    part = make_part(mesh.vertices, mesh.faces, job.facing, job.max_angle or 45.0)
    plan = plan_surface(robot, job, act, part)
    t0 = time.perf_counter()
    pts, _, _, _ = surface_film(plan)
    t1 = time.perf_counter()
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"  curved panel, {len(part.faces)} faces: film {t1 - t0:.1f} s ({len(pts.points)} "
          f"points × {len(plan.trajectory)} samples), peak memory of this process {peak:.0f} MB")


def line_section(robot) -> None:
    """Jobs on a moving line (docs/model.md §24): examples/line.toml (a panel) and
    examples/line_part.toml (a part's mesh), each planned at the job's speed (budget 20 s)
    with its film, and searched for the fastest speed with --max-line-speed (budget 120 s).
    One run each."""
    from pollard_pin.paint.job import PartJob
    from pollard_pin.paint.line import max_line_speed, plan_line_job
    from pollard_pin.paint.line_report import line_film, line_table
    from pollard_pin.paint.surface_plan import surface_film

    act = pp.load_actuators(REPO / "examples" / "actuators.toml")
    print("\npainting on a moving line, one run each [s]")
    for name in ("line.toml", "line_part.toml"):
        job = pp.load_job(REPO / "examples" / name)
        t0 = time.perf_counter()
        plan = plan_line_job(robot, job, act)
        t1 = time.perf_counter()
        if isinstance(job, PartJob):
            surface_film(plan.in_part_frame())
        else:
            line_film(plan, None)
        t2 = time.perf_counter()
        fastest, fast_plan = max_line_speed(robot, job, act)
        t3 = time.perf_counter()
        given, best = line_table(plan), line_table(fast_plan)
        print(f"  {name:<16s} at {given['speed']:.4g} m/s: plan {t1 - t0:5.2f}, film "
              f"{t2 - t1:5.2f}, {given['parts_per_hour']:.1f} parts/h; --max-line-speed "
              f"{t3 - t2:5.1f}: {fastest:.4g} m/s (upper bound {best['upper_bound']:.4g}), "
              f"{best['parts_per_hour']:.1f} parts/h")
