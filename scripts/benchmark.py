#!/usr/bin/env python
"""µs per trajectory sample of each pipeline stage, for every path, measured side by side.

Paths: the Pinocchio pipeline (batched, the default), the same pipeline sample by sample
(the pre-batching implementation, kept as reference), the thesis' closed-form IK +
Euler–Lagrange (numpy only) and the MuJoCo peer. Medians over repeats; prints the machine.

    python scripts/benchmark.py [--samples 2001 20001] [--repeats 5] [--no-mujoco] [--no-cli]
                                [--big 1000001]
                                [--no-loads] [--no-simulate] [--no-size]
                                [--no-startup] [--startup-source DIR] [--no-paint]
                                [--no-workspace] [--no-stiffness] [--design-trials N]
"""
from __future__ import annotations

import argparse
import importlib
import math
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from bench_design import design_breakdown
from bench_paint import (  # scripts/, beside this
    cell_section,
    line_section,
    paint_section,
    parts_section,
)
from bench_signals import signal_section

import pollard_pin as pp
from pollard_pin.dynamics.inverse import inverse_dynamics
from pollard_pin.kinematics.ik import inverse_kinematics_batch, inverse_kinematics_newton
from pollard_pin.paths import ThesisTrajectory
from pollard_pin.paths.curves import wait_then_strokes

STAGES = ("position", "velocity", "acceleration", "analysis", "dynamics")
REPO = Path(__file__).resolve().parents[1]


def machine() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    import pinocchio

    return (f"{cpu}, {os.cpu_count()} cores, Python {platform.python_version()}, "
            f"numpy {np.__version__}, pin {pinocchio.__version__}")


def median_stages(fn, repeats: int) -> dict:
    """Run ``fn(timings)`` ``repeats`` times; median seconds per stage and in total."""
    runs = []
    for _ in range(repeats):
        timings: dict = {}
        t0 = time.perf_counter()
        fn(timings)
        timings["total"] = time.perf_counter() - t0
        runs.append(timings)
    keys = {k for r in runs for k in r}
    return {k: statistics.median(r.get(k, 0.0) for r in runs) for k in keys}


def run_times(fn, repeats: int) -> list:
    """``fn()`` once to warm up (imports, compiled kernels), then ``repeats`` timed calls:
    their wall times [s]."""
    fn()
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return times


def pinocchio_batch(robot, traj):
    def run(timings):
        ik = inverse_kinematics_batch(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t,
                                      timings=timings)
        inverse_dynamics(robot, ik, energies=False, timings=timings)
    return run


def pinocchio_threads(robot, traj, workers: int):
    """The pipeline as ``run`` drives it: windows of 4096 samples solved by ``workers`` threads
    (IK, singularity analysis, inverse dynamics with energies, output columns; no writing)."""
    from pollard_pin.run import StreamOptions
    from pollard_pin.run.stream import solve_windows

    def run(timings):
        for _ in solve_windows(robot, traj, StreamOptions(workers=workers)):
            pass
    return run


def pinocchio_newton(robot, traj):
    def run(timings):
        t0 = time.perf_counter()
        ik = inverse_kinematics_newton(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
        timings["ik (all stages, per sample)"] = time.perf_counter() - t0
        ik.constraint_jacobian = None  # the old path recomputed Jc per sample
        inverse_dynamics(robot, ik, energies=False, timings=timings)
    return run


def thesis_path(robot, traj):
    cf = importlib.import_module("pollard_pin.analytic.closed_form")
    lag = importlib.import_module("pollard_pin.crosscheck.euler_lagrange")

    def run(timings):
        t0 = time.perf_counter()
        cf.position_ik(robot.params, traj.poses)
        t1 = time.perf_counter()
        cf.inverse_kinematics(robot.params, traj.poses, traj.d_poses, traj.dd_poses)
        t2 = time.perf_counter()
        lag.inverse_dynamics(robot.params, traj.poses, traj.d_poses, traj.dd_poses)
        t3 = time.perf_counter()
        timings.update({"position": t1 - t0, "velocity+acceleration": (t2 - t1) - (t1 - t0),
                        "dynamics": t3 - t2})
    return run


def mujoco_path(traj, ik):
    peer = importlib.import_module("pollard_pin.crosscheck.mujoco")
    built = peer.build_mujoco()
    if hasattr(peer, "pipeline_mujoco"):
        def run(timings):
            peer.pipeline_mujoco(traj.poses, traj.d_poses, traj.dd_poses, timings=timings)
        return run, "MuJoCo IK + inverse dynamics"

    def run_id(timings):
        t0 = time.perf_counter()
        peer.inverse_dynamics_mujoco(ik.q, ik.v, ik.a, built=built)
        timings["dynamics"] = time.perf_counter() - t0
    return run_id, "MuJoCo inverse dynamics only (no MuJoCo IK available)"


def loads_section(robot, n: int, repeats: int) -> None:
    """Extra cost of the joint loads (docs/model.md §17, ``run --loads``), beside the per-sample
    ``data.f`` reference and the free-body cross-check."""
    from pollard_pin.crosscheck import newton_euler
    from pollard_pin.dynamics.loads import joint_loads, joint_loads_rnea

    traj = pp.thesis_trajectory(samples=n)
    ik = pp.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    dyn = inverse_dynamics(robot, ik)
    paths = {"stacked RNEA (run --loads)": lambda: joint_loads(robot, ik, dyn),
             "per-sample rnea + data.f (reference)": lambda: joint_loads_rnea(robot, ik, dyn),
             "free bodies, closed form (cross-check)": lambda: newton_euler.joint_loads(
                 robot.params, traj.poses, traj.d_poses, traj.dd_poses)}
    print(f"\njoint loads, {n} samples, median of {repeats} runs [µs/sample]")
    for name, fn in paths.items():
        times = run_times(fn, repeats)
        print(f"  {name:<44s} {1e6 * statistics.median(times) / n:8.2f}")


def simulation_section(robot, repeats: int) -> None:
    """Closed-loop simulation (docs/model.md §18): 20 s of the thesis curve at dt = 1 ms (RK4)
    and a 1 ms control period, the built-in controllers, exact and perturbed plant; the wall
    per RK4 step and per control tick behind ``simulate``'s estimate (dynamics/tracking.py)."""
    from pollard_pin.dynamics.control import CONTROLLERS, desired_trajectory
    from pollard_pin.dynamics.plant import ModelMismatch
    from pollard_pin.dynamics.tracking import TrackingOptions, simulate_tracking

    traj = pp.thesis_trajectory()
    t0 = time.perf_counter()
    desired = desired_trajectory(robot, traj)
    print(f"\nclosed-loop simulation, {traj.t[-1]:g} s, dt = control period = 1 ms; desired "
          f"trajectory (batched IK + ID, {len(desired.t)} ticks) {time.perf_counter() - t0:.2f} s")
    for controller in CONTROLLERS:
        for label, errors in (("exact", None),
                              ("payload 0.05 kg + mass +10 %", ModelMismatch(0.05, 0.1))):
            walls = []
            for _ in range(max(1, repeats // 2)):
                t0 = time.perf_counter()
                res = simulate_tracking(robot, traj,
                                        TrackingOptions(controller, errors, desired=desired))
                walls.append(time.perf_counter() - t0)
            print(f"  {controller:<16s} {label:<30s} {min(walls):6.2f} s wall "
                  f"({res.steps} RK4 steps, {traj.t[-1] / min(walls):4.1f}× real time), max tip "
                  f"error {res.tip_position_error.max():.3g} m")
    short = pp.thesis_trajectory(duration=1.0, samples=101)
    walls = {}
    for ratio in (1, 10):  # RK4 steps per control tick
        times = []
        for _ in range(max(1, repeats // 2)):
            res = simulate_tracking(robot, short,
                                    TrackingOptions("computed-torque", dt=1e-3 / ratio))
            times.append(res.wall / res.steps)
        walls[ratio] = min(times)
    tick = (walls[1] - walls[10]) / 0.9  # wall per step = step + tick / (steps per tick)
    print(f"  per RK4 step {1e6 * (walls[1] - tick):.0f} µs, per control tick (sensing and "
          f"computed torque) {1e6 * tick:.0f} µs (min of {max(1, repeats // 2)}): "
          f"{1e6 * walls[1]:.0f} µs of wall per simulated ms, {1e-3 / walls[1]:.1f}× real time "
          "at dt = control period = 1 ms")


def sizing_section(robot, sizes, repeats: int) -> None:
    """Motor sizing (docs/model.md §19, ``pollard-pin size``): path dynamics (3 RNEA passes),
    the exact uniform scaling, TOPP-RA held between the samples (check points doubled until
    the worst use halfway between them is within 1.001), and a 10,751-sample rest-to-rest
    raster (2 ms) as the paint planner gives it."""
    from pollard_pin.dynamics import motors, timeopt
    from pollard_pin.dynamics import path as path_mod
    from pollard_pin.painting.passes.raster import raster_motion, raster_segments
    from pollard_pin.painting.workpiece.panel import PanelFrame

    act = motors.load_actuators(REPO / "examples" / "actuators.toml")
    print(f"\nmotor sizing (examples/actuators.toml), min of {repeats} runs [ms]")

    def row(label, fn, n):
        times = []
        for _ in range(repeats):
            t0 = time.perf_counter()
            out = fn()
            times.append(time.perf_counter() - t0)
        extra = (f"  ({out.iterations} solves, {out.per_interval} check points per "
                 f"interval, worst between samples {out.between:.5f}, {out.duration:.4g} s "
                 "cycle)" if isinstance(out, timeopt.TimeOptimal) else "")
        print(f"  {n:6d} samples  {label:<24s} {1e3 * min(times):9.1f}{extra}")

    for n in sizes:
        traj = pp.thesis_trajectory(samples=n)
        ik = pp.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
        path = path_mod.path_dynamics(robot, ik)
        row("path dynamics", lambda ik=ik: path_mod.path_dynamics(robot, ik), n)
        row("uniform_min_duration", lambda path=path: motors.uniform_min_duration(act, path), n)
        row("time_optimal_path", lambda traj=traj: pp.time_optimal_path(
            robot, act, traj), n)
    # the paint planner's raster: 12 passes 0.26 m long, 0.12 m apart in all, at 0.2 m/s in
    # the plane x = 0.55 m, 0.4 s turnarounds, 0.75 s ramps
    frame = PanelFrame(np.array([0.55, 0.0, 0.16]), np.array([-1.0, 0.0, 0.0]),
                       np.array([0.0, 1.0, 0.0]), np.array([0.0, 0.0, 1.0]), 0.26, 0.12)
    seg = raster_segments(np.linspace(-0.06, 0.06, 12), 0.13, 0.2, 0.4, (0.75, 0.75))
    t = np.linspace(0.0, seg.total, round(seg.total / 2e-3) + 1)
    poses, rates, accelerations = raster_motion(frame, 0.0, seg, t)
    row("raster time_optimal_path", lambda: pp.time_optimal_path(
        robot, act, pp.Trajectory(t, poses, rates, accelerations)), len(t))
    # a line job's shape: a wait (47 % of 100,000 samples at 2 ms), then the thesis curve from
    # rest to rest; the wait is left out of the solve (dynamics/cycle.py)
    wait = wait_then_strokes(100_000)
    row("wait + strokes cycle", lambda: pp.time_optimal_path(robot, act, wait),
        len(wait.t))


def workspace_section(robot, repeats: int) -> None:
    """Workspace maps (docs/model.md §22): a 250,000-point plane at x = 0.55 over the default
    bounds (mostly outside the reach, as a user maps it), and one of the same size over the
    reachable box (mostly reachable: the full per-point work). Best of ``repeats``."""
    from pollard_pin.workspace.grid import map_workspace
    from pollard_pin.workspace.options import WorkspaceOptions

    # warm-up: imports, compiled kernels
    map_workspace(robot, "x=0.55", WorkspaceOptions(resolution=0.02))
    cases = {"default bounds (500 × 500)": {"resolution": 0.00326},
             "reachable box (675 × 372)": {"resolution": 0.00089,
                                           "bounds": {"y": (-0.3, 0.3), "z": (-0.05, 0.28)}}}
    print(f"\nworkspace map, plane x = 0.55, best of {repeats} [µs/point]")
    for label, kw in cases.items():
        times = []
        for _ in range(repeats):
            t0 = time.perf_counter()
            ws = map_workspace(robot, "x=0.55", WorkspaceOptions(**kw))
            times.append(time.perf_counter() - t0)
        n = ws.grid.size
        print(f"  {label:<28s} {n:7d} points, {ws.summary['reachable_points']:7d} reachable "
              f"{1e6 * min(times) / n:8.2f}")


def planner_section(robot, repeats: int) -> None:
    """The line planner's inner stages (docs/model.md §24), best of ``repeats`` [ms]: the scan
    of 400 shifts of a 200-pose pass along the line, stacked (line/shifts.py, one batch) and
    shift by shift (reach() per shift, as first written); motion() of one 48-sample
    turnaround (the turnaround and return searches call it ~30 times per plan); reach() of a
    4000-sample path that first waits 3000 samples (the fine check's), and of the same
    samples with no wait."""
    from pollard_pin.dynamics.motors import load_actuators
    from pollard_pin.painting.checks.motion import motion, reach
    from pollard_pin.painting.errors import ReachError
    from pollard_pin.painting.line.shifts import fits

    act = load_actuators(REPO / "examples" / "actuators.toml")
    e = np.array([0.0, 1.0, 0.0])
    u = np.linspace(0.0, 1.0, 200)[:, None]
    poses = np.hstack([0.5 + 0.0 * u, -0.9 + 0.4 * u, 0.1 - 0.1 * u, 0.2 * u, 0.0 * u,
                       0.0 * u])
    xs = np.arange(400) * 0.005

    def one_by_one():
        for x in xs:
            p = poses.copy()
            p[:, :3] += x * e
            try:
                reach(robot, p)
            except ReachError:
                pass

    tr = pp.thesis_trajectory(samples=4000)
    turn = (tr.poses[:48], tr.d_poses[:48], tr.dd_poses[:48])
    wait = [np.concatenate([np.repeat(a[:1] * (k == 0), 3000, axis=0), a[:1000]])
            for k, a in enumerate((tr.poses, tr.d_poses, tr.dd_poses))]
    cases = {"reach scan, 400 shifts × 200 poses, stacked": lambda: fits(robot, poses, e, xs),
             "reach scan, the same shift by shift": one_by_one,
             "motion of a 48-sample turnaround": lambda: motion(robot, act, *turn),
             "reach of 4000 samples, 3000 of them a wait": lambda: reach(robot, *wait),
             "reach of 4000 samples, no wait": lambda: reach(robot, tr.poses, tr.d_poses,
                                                             tr.dd_poses)}
    print(f"\nline planner stages, best of {repeats} [ms]")
    for label, fn in cases.items():
        print(f"  {label:<50s} {1e3 * min(run_times(fn, repeats)):9.1f}")


def stiffness_section(robot, sizes, repeats: int) -> None:
    """The whole ``stiffness`` run (docs/model.md §27) in process, streamed to a CSV: the IK
    windows, the stiffness of each sample and the writing, one thread (target ≤ 20 µs per
    sample); beside it the IK windows alone. Best of ``repeats``, wall and CPU time."""
    from pollard_pin.run import StreamOptions
    from pollard_pin.run.stiffness import stream_stiffness
    from pollard_pin.run.stream import solve_windows

    drives = pp.load_actuators(REPO / "examples" / "actuators.toml")
    print(f"\nstiffness run, thesis path, one thread, best of {repeats} [µs/sample, wall / CPU]")
    with tempfile.TemporaryDirectory() as tmp:
        for n in sizes:
            traj = ThesisTrajectory(samples=n, home_pose=robot.params.home_pose)
            stages = {
                "IK windows alone": lambda traj=traj: sum(1 for _ in solve_windows(
                    robot, traj, StreamOptions(workers=1), dynamics=False)),
                "stiffness run, CSV": lambda traj=traj: stream_stiffness(
                    robot, traj, drives, Path(tmp) / "s.csv", stream=StreamOptions(workers=1)),
            }
            for label, fn in stages.items():
                fn()  # warm-up
                wall, cpu = [], []
                for _ in range(repeats):
                    t0, c0 = time.perf_counter(), time.process_time()
                    fn()
                    wall.append(time.perf_counter() - t0)
                    cpu.append(time.process_time() - c0)
                print(f"  {n:8d} samples, {label:<22s} {1e6 * min(wall) / n:8.2f} "
                      f"{1e6 * min(cpu) / n:8.2f}")


def cli_run(samples: int, out: str) -> tuple[float, float, str]:
    """``pollard-pin run`` as a user runs it: (wall seconds, peak resident MB, its output)."""
    exe = Path(sys.executable).with_name("pollard-pin")
    cmd = [str(exe), "-v", "run", "--samples", str(samples), "--out", out, "--quiet"]
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    text = proc.stdout.read()
    status = proc.wait()
    wall = time.perf_counter() - t0
    if status:
        raise SystemExit(f"{' '.join(cmd)} failed: {text.strip().splitlines()[-1]}")
    # the process's own high-water mark (run -v logs it; ru_maxrss would include this parent)
    peak = [x for x in text.splitlines() if "peak resident memory" in x]
    mb = float(peak[0].split()[-2]) if peak and peak[0].split()[-2] != "unknown" else math.nan
    return wall, mb, text


def cli_section(sizes: tuple[int, int], repeats: int, big: int) -> None:
    """Whole-process marginal cost per sample of ``run`` (best of repeats), CSV and Parquet."""
    small, large = sizes
    print(f"\n`pollard-pin run`, whole process (start, imports, model, solve, write), best of "
          f"{repeats}; marginal = (T({large}) − T({small})) / {large - small}")
    with tempfile.TemporaryDirectory() as tmp:
        for fmt in ("csv", "parquet"):
            out = str(Path(tmp) / f"run.{fmt}")
            best = {n: min(cli_run(n, out)[0] for _ in range(repeats)) for n in sizes}
            marginal = 1e6 * (best[large] - best[small]) / (large - small)
            print(f"  {fmt:8s} T({small}) = {best[small]:.3f} s, T({large}) = {best[large]:.3f} s"
                  f", marginal {marginal:.2f} µs/sample")
        if big:
            out = str(Path(tmp) / "big.csv")
            wall, rss, text = cli_run(big, out)
            solve = [x for x in text.splitlines() if x.startswith("solved and written")]
            print(f"  {big} samples, CSV: {wall:.1f} s, peak resident {rss:.0f} MB "
                  f"({solve[0] if solve else ''})")
            wall, rss, _ = cli_run(big // 5, out)
            print(f"  {big // 5} samples, CSV: {wall:.1f} s, peak resident {rss:.0f} MB")


def fresh_install(wheel: Path, venv: Path) -> None:
    """A new venv with ``wheel`` installed and byte-compiled, as ``pip install`` leaves it; its
    dependencies come from this environment (after the venv's own site-packages)."""
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    site = next((venv / "lib").glob("python3*/site-packages"))
    deps = {str(Path(m.__file__).resolve().parents[1]) for m in (np, importlib.import_module(
        "pinocchio"))}
    (site / "_deps.pth").write_text("\n".join(sorted(deps)) + "\n")
    subprocess.run([sys.executable, "-m", "pip", "--python", str(venv / "bin" / "python"),
                    "install", "-q", "--no-deps", "--no-index", str(wheel)], check=True)


def startup_section(samples: int, repeats: int, source: Path) -> None:
    """Cold start (the first ``run`` after installing) against a warm one (the next runs),
    whole process, each on a fresh install of a wheel built from ``source``; best of repeats."""
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "VIRTUAL_ENV", "NUMBA_CACHE_DIR")}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        # a copy: building in the checkout would leave (and later package) a stale build/
        src = tmp / "src"
        src.mkdir()
        for name in ("pyproject.toml", "setup.py", "README.md"):
            if (source / name).exists():
                shutil.copy2(source / name, src / name)
        for name in ("pollard_pin", "models", "csrc"):
            if not (source / name).exists():  # (no csrc/ before the C kernels)
                continue
            shutil.copytree(source / name, src / name,
                            ignore=shutil.ignore_patterns("__pycache__", "*.so"))
        subprocess.run([sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", str(src),
                        "-w", str(tmp / "dist")], check=True)
        (wheel,) = (tmp / "dist").glob("pollard_pin-*.whl")
        cold, warm = [], []
        for i in range(repeats):
            venv = tmp / f"venv{i}"
            fresh_install(wheel, venv)
            cmd = [str(venv / "bin" / "pollard-pin"), "run", "--samples", str(samples), "--out",
                   str(tmp / "run.csv"), "--quiet"]
            for times in (cold, warm, warm):
                t0 = time.perf_counter()
                proc = subprocess.run(cmd, env=env, cwd=tmp, capture_output=True, text=True)
                times.append(time.perf_counter() - t0)
                if proc.returncode:
                    raise SystemExit(f"{' '.join(cmd)} failed:\n{proc.stderr.strip()}")
    print(f"\nstart-up, `pollard-pin run --samples {samples}` from a fresh install of "
          f"{source.name}, whole process, best of {repeats} installs: cold (first run) "
          f"{min(cold):.2f} s, warm {min(warm):.2f} s, ratio {min(cold) / min(warm):.2f}")


def mujoco_marginal(sizes: tuple[int, int], repeats: int) -> None:
    """The MuJoCo path (its own IK + closed-loop inverse dynamics) on the same job, in process."""
    try:
        peer = importlib.import_module("pollard_pin.crosscheck.mujoco")
        peer.build_mujoco()
    except ImportError as exc:
        print(f"  mujoco path skipped: {exc}")
        return
    best = {}
    for n in sizes:
        traj = pp.thesis_trajectory(samples=n)
        runs = []
        for _ in range(repeats):
            t0 = time.perf_counter()
            peer.pipeline_mujoco(traj.poses, traj.d_poses, traj.dd_poses)
            runs.append(time.perf_counter() - t0)
        best[n] = min(runs)
    small, large = sizes
    print(f"  MuJoCo path (IK + inverse dynamics, no output), in process: marginal "
          f"{1e6 * (best[large] - best[small]) / (large - small):.2f} µs/sample")


def design_section(trials: int, repeats: int) -> None:
    """The design study (docs/model.md §31) on examples/design/: a screened evaluation [ms]
    (median over ``repeats`` random designs), a ``trials``-evaluation study on every core
    with its counts and its chosen design's figures, a full evaluation's and a search
    evaluation's CPU time (the chosen design, docs/model.md §31.5), the 200-evaluation
    projection on two cores from those, the screen's pass rate and the front planned again in
    full, and the same study on a Dask LocalCluster of one worker, then two: the speed-up;
    first, where an evaluation's time goes for one, two and three robots
    (scripts/bench_design.py)."""
    import random
    import tempfile

    from pollard_pin.synthesis import (
        SearchFidelity,
        baseline_values,
        evaluate,
        load_space,
        prepare,
    )
    from pollard_pin.synthesis.api import design
    from pollard_pin.synthesis.study import DesignOptions

    design_breakdown()
    job = pp.load_job(REPO / "examples" / "design" / "job.toml")
    space = load_space(REPO / "examples" / "design" / "space.toml")
    ctx = prepare(job, space)
    rng = random.Random(0)
    designs = [baseline_values(space)] + [
        {v.name: (rng.randint(0, len(v.choices) - 1) if v.kind == "categorical" else
                  rng.randint(int(v.low), int(v.high)) if v.kind == "int" else
                  rng.uniform(v.low, v.high)) for v in space.variables()}
        for _ in range(max(1, repeats - 1))]
    screen = [min(run_times(lambda d=d: evaluate(d, ctx, "screen"), 1)) for d in designs]
    print(f"\ndesign study, examples/design (job.toml, space.toml)\n"
          f"  screened evaluation, median of {len(screen)} designs [ms]"
          f"{1e3 * statistics.median(screen):12.1f}")

    def study(**options):
        with tempfile.TemporaryDirectory() as tmp:
            t0 = time.perf_counter()
            result = design(job, space, DesignOptions(trials=trials, population=8,
                                                      study=Path(tmp) / "study.db",
                                                      **options))
            return result, time.perf_counter() - t0

    try:
        result, wall = study()
    except pp.PollardError as exc:
        print(f"  study of {trials}: {exc}")
        return
    print(f"  study of {trials} evaluations, {os.cpu_count()} local processes [s]"
          f"{wall:12.1f}  ({result.feasible} feasible, front of {len(result.front)})")
    o = result.design["objectives"]
    print(f"  the chosen design: {o['robots']:.0f} robot(s), {o['parts_per_hour']:.1f} parts/h, "
          f"motor use {o['motor_use']:.3f}, kmin {o['kmin']:.0f} N/m, "
          f"{o['moving_mass']:.2f} kg")
    t0 = time.process_time()
    full = evaluate(result.design["values"], ctx, "full")
    full_cpu = time.process_time() - t0
    print(f"  full evaluation of the chosen design, CPU [s]{full_cpu:12.1f}"
          f"  (feasible: {full.feasible})")
    t0 = time.process_time()
    searched = evaluate(result.design["values"], prepare(job, space, search=SearchFidelity()),
                        "search")
    search_cpu = time.process_time() - t0
    print(f"  search evaluation of the chosen design, CPU [s]{search_cpu:10.1f}"
          f"  (feasible: {searched.feasible})")
    # the 200-evaluation projection (docs/model.md §31.5): the ladder's screens, the screen for
    # every design, the search's plan for the share that passes it, the front (this study's
    # size, a lower estimate) planned again in full, on two cores
    from pollard_pin.synthesis.ladder import ladder

    rungs = len(ladder(space.variables(), baseline_values(space, ctx)))
    passed = sum(r["level"] in ("search", "full") for r in result.trials) / max(
        1, len(result.trials))
    minutes = ((rungs + 200) * statistics.median(screen) + 200 * passed * search_cpu
               + len(result.front) * full_cpu) / 2 / 60
    print(f"  screen pass rate {passed:.2f}; the ladder {rungs} screens; a front of "
          f"{len(result.front)} planned again; 200 evaluations on 2 cores, projected [min]"
          f"{minutes:12.1f}")
    try:
        from distributed import LocalCluster
    except ImportError:
        print("  dask speed-up skipped: no dask.distributed")
        return
    walls = {}
    for n in (1, 2):
        with LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                          dashboard_address=None) as cluster:
            walls[n] = study(dask=cluster.scheduler_address)[1]
        print(f"  the same study on a Dask LocalCluster, {n} worker{'s' * (n > 1)} [s]"
              f"{walls[n]:12.1f}")
    print(f"  Dask speed-up, two workers over one {walls[1] / walls[2]:12.2f}x")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, nargs="+", default=[2001, 20001])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--no-mujoco", action="store_true")
    ap.add_argument("--no-newton", action="store_true", help="skip the per-sample reference")
    ap.add_argument("--no-cli", action="store_true")
    ap.add_argument("--big", type=int, default=0, metavar="N",
                    help="also time `run --samples N` and N/5 and report their peak memory "
                         "(e.g. 1000001)")
    ap.add_argument("--no-loads", action="store_true", help="skip the joint-loads section")
    ap.add_argument("--no-simulate", action="store_true",
                    help="skip the closed-loop simulation section")
    ap.add_argument("--no-size", action="store_true", help="skip the motor-sizing section")
    ap.add_argument("--no-startup", action="store_true",
                    help="skip the cold/warm start section (builds a wheel, fresh installs)")
    ap.add_argument("--startup-source", type=Path, default=REPO, metavar="DIR",
                    help="the project checkout whose start-up is measured (default this one)")
    ap.add_argument("--no-paint", action="store_true", help="skip the paint-planning section")
    ap.add_argument("--no-workspace", action="store_true", help="skip the workspace-map section")
    ap.add_argument("--no-stiffness", action="store_true", help="skip the stiffness section")
    ap.add_argument("--design-trials", type=int, default=24, metavar="N",
                    help="the design section's study size (0: skip the section)")
    args = ap.parse_args(argv)

    print(f"machine: {machine()}")
    if not args.no_startup:
        startup_section(min(args.samples), 3, args.startup_source)
    robot = pp.load()
    for n in args.samples:
        traj = pp.thesis_trajectory(samples=n)
        reps = args.repeats if n <= 5000 else max(1, args.repeats // 2)
        paths = {"pinocchio (batched)": pinocchio_batch(robot, traj)}
        for w in (1, 2):
            paths[f"pinocchio, run, {w} thread{'s' * (w > 1)}"] = \
                pinocchio_threads(robot, traj, w)
        if not args.no_newton:
            paths["pinocchio (per sample)"] = pinocchio_newton(robot, traj)
        paths["thesis (closed form + E-L)"] = thesis_path(robot, traj)
        if not args.no_mujoco:
            try:
                ik = pp.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
                run, label = mujoco_path(traj, ik)
                paths[f"mujoco ({label})"] = run
            except ImportError as exc:
                print(f"  mujoco path skipped: {exc}")
        results = {}
        for name, fn in paths.items():
            fn({})  # warm-up: imports, caches
            results[name] = median_stages(fn, reps)
        print(f"\ndefault trajectory, {n} samples, median of {reps} runs [µs/sample]")
        stages = sorted({k for r in results.values() for k in r if k != "total"},
                        key=lambda k: (STAGES.index(k) if k in STAGES else 99, k))
        width = max(len(s) for s in stages + ["total"]) + 2
        print(" " * width + "".join(f"{name[:30]:>32s}" for name in results))
        for stage in stages + ["total"]:
            row = "".join(f"{1e6 * r[stage] / n:32.2f}" if stage in r else f"{'—':>32s}"
                          for r in results.values())
            print(f"{stage:<{width}s}{row}")
        base = results["pinocchio (batched)"]["total"]
        core = base - results["pinocchio (batched)"].get("analysis", 0.0)
        print("ratios (path total / pinocchio batched total; in brackets / pinocchio without its "
              "singularity analysis, which the other paths do not compute):")
        for name, r in results.items():
            print(f"  {name:<60s} {r['total'] / base:8.2f}x  [{r['total'] / core:6.2f}x]")
    if not args.no_loads:
        for n in args.samples:
            loads_section(robot, n, args.repeats)
    if not args.no_simulate:
        simulation_section(robot, args.repeats)
    if not args.no_size:
        sizing_section(robot, [n for n in args.samples if n <= 5000] or [2001], 3)
        signal_section(wait_then_strokes)
    if not args.no_paint:
        paint_section(robot, 3)
        parts_section(robot)
        line_section(robot)
        cell_section(robot)
        planner_section(robot, 3)
    if not args.no_workspace:
        workspace_section(robot, args.repeats)
    if not args.no_stiffness:
        stiffness_section(robot, args.samples, args.repeats)
    if args.design_trials:
        design_section(args.design_trials, args.repeats)
    if not args.no_cli:
        sizes = (min(args.samples), max(args.samples))
        if sizes[0] == sizes[1]:
            sizes = (sizes[0], 10 * sizes[0])
        cli_section(sizes, 3, args.big)
        if not args.no_mujoco:
            mujoco_marginal(sizes, 3)
    return 0


if __name__ == "__main__":
    sys.exit(main())
