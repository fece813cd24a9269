#!/usr/bin/env python
"""µs per trajectory sample of each pipeline stage, for every path, measured side by side.

Paths: the Pinocchio pipeline (batched, the default), the same pipeline sample by sample
(the pre-batching implementation, kept as reference), the thesis' closed-form IK +
Euler–Lagrange (numpy only) and the MuJoCo peer. Medians over repeats; prints the machine.

    python scripts/benchmark.py [--samples 2001 20001] [--repeats 5] [--no-mujoco] [--no-cli]
"""
from __future__ import annotations

import argparse
import importlib
import os
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import pollard_pin as pp
from pollard_pin.dynamics.inverse import inverse_dynamics
from pollard_pin.kinematics.pipeline import inverse_kinematics_batch, inverse_kinematics_newton

STAGES = ("position", "velocity", "acceleration", "analysis", "dynamics")


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


def pinocchio_batch(robot, traj):
    def run(timings):
        ik = inverse_kinematics_batch(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t,
                                      timings=timings)
        inverse_dynamics(robot, ik, energies=False, timings=timings)
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
    cf = importlib.import_module("pollard_pin.kinematics.closed_form")
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


def cli_time(samples: int) -> float:
    exe = Path(sys.executable).with_name("pollard-pin")
    cmd = [str(exe), "run", "--samples", str(samples), "--out", os.devnull, "--quiet"]
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, nargs="+", default=[2001, 20001])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--no-mujoco", action="store_true")
    ap.add_argument("--no-newton", action="store_true", help="skip the per-sample reference")
    ap.add_argument("--no-cli", action="store_true")
    args = ap.parse_args(argv)

    print(f"machine: {machine()}")
    robot = pp.load()
    for n in args.samples:
        traj = pp.thesis_trajectory(samples=n)
        reps = args.repeats if n <= 5000 else max(1, args.repeats // 2)
        paths = {"pinocchio (batched)": pinocchio_batch(robot, traj)}
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
    if not args.no_cli:
        for n in args.samples:
            wall = min(cli_time(n) for _ in range(3))
            print(f"\n`pollard-pin run --samples {n}` end to end (process start, imports, "
                  f"model load, solve, CSV): {wall:.3f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
