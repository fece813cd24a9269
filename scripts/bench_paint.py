#!/usr/bin/env python
"""The paint sections of scripts/benchmark.py: a panel (docs/model.md §21), parts' meshes
(§23) and jobs on a moving line (§24), each timed as the CLI runs it, in seconds, through
the public painting API (``pollard_pin.paint``).

Run alone it times the paint cases against their targets, each ``pollard-pin paint`` in a
subprocess of its own (wall and CPU seconds, peak memory); figures only, no asserts:

    python scripts/bench_paint.py [--quick] [--case a|b|c|d]

(a) examples/cell_part.toml, the two-robot line case, planned and filmed at its own speed
(target 30 s for the plan and the film, paint.json's ``plan`` + ``film``; the whole command,
with its compliance check and files, is printed beside); (b) the same with --max-line-speed
(60 s); (c) its part with --robots auto (90 s); (d) examples/parts/ribbed_plate.toml's film
at 1 mm with compliance (30 s: 65k film points when the target was set, 50k since faces not
painted take points σ apart, docs/model.md §23); memory 2 GB for any. ``--quick``: (d) alone
at 5 mm (seconds; the test's run); ``--case``: that case alone.
"""
from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import pollard_pin as pp

REPO = Path(__file__).resolve().parents[1]


def paint_section(robot, repeats: int) -> None:
    """Paint planning (docs/model.md §21) of examples/paint.toml and its film map; the
    budget is 10 s for both."""
    examples = REPO / "examples"
    act = pp.load_actuators(examples / "actuators.toml")
    job = pp.load_job(examples / "paint.toml")
    plans, films = [], []
    for _ in range(repeats):
        result = pp.paint(robot, job, act)
        plans.append(result.report.timings["plan"])
        films.append(result.report.timings["film"])
    pts = result.film.points
    print(f"\npaint planning (examples/paint.toml), best of {repeats} runs [s]")
    print(f"  plan {min(plans):.2f}, film map {min(films):.2f} ({pts.shape[0] * pts.shape[1]} "
          f"points × {len(result.plan.trajectory)} samples); cycle "
          f"{result.report.cycle_time:.3f} s")


def parts_section(robot, big_faces: int = 195_000) -> None:
    """Painting parts' meshes (docs/model.md §23): plan and film of each shipped example
    (budget 15 s each), and the film of a curved panel tessellated into about ``big_faces``
    triangles (the face budget is 200,000; the time budget 60 s, memory bounded). One run each."""
    import resource

    from pollard_pin.painting.workpiece.shapes import curved_panel  # the example parts' generator

    act = pp.load_actuators(REPO / "examples" / "actuators.toml")
    print("\npainting parts (examples/parts/*.toml), one run each [s]")
    for path in sorted((REPO / "examples" / "parts").glob("*.toml")):
        r = pp.paint(robot, pp.load_job(path), act)
        t = r.report.timings
        print(f"  {path.name:<20s} {r.report.data['part']['faces']:7d} faces: plan "
              f"{t['plan']:5.2f}, film {t['film']:5.2f} ({len(r.film.points.points)} points × "
              f"{len(r.plan.trajectory)} samples)")
    job = pp.load_job(REPO / "examples" / "parts" / "curved_panel.toml")
    # 4 faces per grid cell of the extruded sheet (front and back): the step for big_faces
    step = math.sqrt(4 * 0.24 * 0.10 / big_faces)
    with tempfile.TemporaryDirectory() as tmp:
        mesh = Path(tmp) / "curved_panel.stl"
        curved_panel(step=step).export(mesh)
        r = pp.paint(robot, replace(job, mesh=str(mesh)), act)
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"  curved panel, {r.report.data['part']['faces']} faces: film "
          f"{r.report.timings['film']:.1f} s ({len(r.film.points.points)} points × "
          f"{len(r.plan.trajectory)} samples), peak memory of this process {peak:.0f} MB")


def line_section(robot) -> None:
    """Jobs on a moving line (docs/model.md §24): examples/line.toml (a panel) and
    examples/line_part.toml (a part's mesh), each planned at the job's speed (budget 20 s)
    with its film, and searched for the fastest speed with --max-line-speed (budget 120 s;
    timed with the film at that speed, as the CLI runs it), and the time --speeds adds (the
    interval of speeds that paint, docs/model.md §24.3). One run each."""
    act = pp.load_actuators(REPO / "examples" / "actuators.toml")
    print("\npainting on a moving line, one run each [s]")
    for name in ("line.toml", "line_part.toml"):
        job = pp.load_job(REPO / "examples" / name)
        given = pp.paint(robot, job, act)
        t0 = time.perf_counter()
        fast = pp.paint(robot, job, act, pp.PaintOptions(max_line_speed=True))
        search = time.perf_counter() - t0
        g, best, t = given.report.line, fast.report.line, given.report.timings
        print(f"  {name:<16s} at {g['speed']:.4g} m/s: plan {t['plan']:5.2f}, film "
              f"{t['film']:5.2f}, {g['parts_per_hour']:.1f} parts/h; --max-line-speed "
              f"{search:5.1f}: {best['speed']:.4g} m/s (upper bound {best['upper_bound']:.4g}), "
              f"{best['parts_per_hour']:.1f} parts/h")
        stated = pp.paint(robot, job, act, pp.PaintOptions(speeds=True, compliance=False))
        sp = stated.report.line["speeds"]
        print(f"  {name:<16s} --speeds {stated.report.timings['speeds']:5.1f} more: "
              f"{sp['min']:.4g}–{sp['max']:.4g} m/s (each end to {100 * sp['resolution']:g} %)")


def cell_section(robot) -> None:
    """Paint cells (docs/model.md §26): examples/cell.toml (two robots, budget 60 s to plan)
    and examples/cell3.toml (three) at the job's speed with the film, and --max-line-speed
    on the two-robot cell (budget 300 s, with the film at that speed). One run each."""
    act = pp.load_actuators(REPO / "examples" / "actuators.toml")
    print("\npaint cells, one run each [s]")
    for name in ("cell.toml", "cell3.toml"):
        job = pp.load_job(REPO / "examples" / name)
        r = pp.paint(robot, job, act)
        rep, t = r.report.data, r.report.timings
        seams = ", ".join(f"{s['at']:.4f} m film {s['min']:.4f}-{s['max']:.4f}"
                          for s in rep["seams"])
        print(f"  {name:<11s} at {rep['line']['speed']:.4g} m/s: plan {t['plan']:5.1f}, film "
              f"{t['film']:5.1f}, {rep['line']['parts_per_hour']:.1f} parts/h; seams {seams}; "
              f"film within ±5 % {100 * rep['thickness']['within_5pct']:.2f} %")
        if name == "cell.toml":
            t0 = time.perf_counter()
            fast = pp.paint(robot, job, act, pp.PaintOptions(max_line_speed=True))
            best = fast.report.line
            print(f"  {name:<11s} --max-line-speed {time.perf_counter() - t0:5.1f}: "
                  f"{best['speed']:.4g} m/s, {best['parts_per_hour']:.1f} parts/h")


# the paint cases: (name, job, extra arguments, target [s], what the target times: the
# command's wall, or the sum of those paint.json timings)
WALL = ()
CASES = (
    ("(a) two-robot line case at its speed", "cell_part.toml", [], 30.0, ("plan", "film")),
    ("(b) its --max-line-speed", "cell_part.toml", ["--max-line-speed"], 60.0, WALL),
    ("(c) its part with --robots auto", "cell_part.toml", ["--robots", "auto"], 90.0, WALL),
    ("(d) ribbed plate film at 1 mm, compliance on", "parts/ribbed_plate.toml",
     ["--resolution", "0.001"], 30.0, WALL),
)
QUICK = (("(d) ribbed plate film at 5 mm, compliance on (quick)", "parts/ribbed_plate.toml",
          ["--resolution", "0.005"], 30.0, WALL),)
MEMORY_TARGET_GB = 2.0


def _without_robots(job: Path, folder: Path) -> Path:
    """A copy of the job in ``folder`` without its [[robot]] tables (what --robots auto asks
    for), its mesh named by its absolute path."""
    import re

    text = job.read_text()
    cut = text.find("[[robot]]")
    text = text if cut < 0 else text[:cut]
    text = re.sub(r'(?m)^(mesh\s*=\s*)"([^"]+)"',
                  lambda m: f'{m.group(1)}"{(job.parent / m.group(2)).resolve()}"', text)
    out = folder / f"auto_{job.name}"
    out.write_text(text)
    return out


def run_case(name: str, job: str, extra: list, target: float, timed=WALL) -> None:
    """``pollard-pin paint`` on one case in a subprocess: its wall and CPU seconds, peak
    memory and the timings paint.json gives, or why it was refused; judged against
    ``target`` by its wall, or by the sum of the paint.json timings ``timed``."""
    import json

    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        path = REPO / "examples" / job
        if "--robots" in extra:
            path = _without_robots(path, tmp)
        args = [sys.executable, "-m", "pollard_pin.cli", "paint", "--job", str(path),
                "--out", str(tmp / "out"), *extra]
        env = {**os.environ, "PYTHONPATH": str(REPO)}
        t0 = time.perf_counter()
        with open(tmp / "stdout", "w") as out, open(tmp / "stderr", "w") as err:
            proc = subprocess.Popen(args, stdout=out, stderr=err, env=env, cwd=tmp)
            _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - t0
        cpu = usage.ru_utime + usage.ru_stime
        peak = usage.ru_maxrss / 1024 ** 2  # kB -> GB
        code = os.waitstatus_to_exitcode(status)
        report = tmp / "out" / "paint.json"
        times, judged = "", wall
        if code == 0 and report.is_file():
            t = json.loads(report.read_text()).get("timings", {})
            times = ", ".join(f"{k} {v:.1f}" for k, v in t.items())
            if timed:
                judged = sum(t[k] for k in timed)
                times = f"{' + '.join(timed)} {judged:.1f} s; {times}"
        else:
            lines = (tmp / "stderr").read_text().strip().splitlines()
            times = f"exit {code}: {lines[-1] if lines else ''}"
    verdict = "within" if judged <= target else "over"
    by = " + ".join(timed) if timed else "wall"
    print(f"  {name}: wall {wall:.1f} s, CPU {cpu:.1f} s ({verdict} the target {target:g} s "
          f"by {by}), peak memory {peak:.2f} GB (target {MEMORY_TARGET_GB:g}); {times}")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="(d) alone at 5 mm: seconds")
    ap.add_argument("--case", choices=list("abcd"), help="that case alone")
    args = ap.parse_args(argv)
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"the paint targets on {os.cpu_count()} cores, load average {load:.1f} at the "
          "start (wall times grow with the load; the CPU seconds less so)")
    cases = QUICK if args.quick else CASES
    for case in cases if args.case is None else [c for c in cases if c[0][1] == args.case]:
        run_case(*case)


if __name__ == "__main__":
    main()
