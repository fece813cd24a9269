#!/usr/bin/env python
"""Forward-dynamics replay of the inverse-dynamics torques along the default trajectory.

Integrates Pinocchio's constrained forward dynamics (proximal, μ = 0, Baumgarte) with RK4 and
the torques of the inverse dynamics evaluated exactly at every stage, then reports the tool-tip
drift from the prescribed curve:

* open loop, until the drift passes a limit (the mechanism is gravity-unstable under constant
  torques: the growth rate is printed from the linearisation at home);
* with a weak PD on the actuators around the same feedforward torques, whose peak torque shows
  how little correction the feedforward needs.

    python scripts/replay.py [--duration 20] [--dt 1e-3] [--bandwidth 20]
"""
from __future__ import annotations

import argparse
import time

import numpy as np

import pollard_pin as pp
from pollard_pin.dynamics.forward import replay_open_loop, trajectory_torques
from pollard_pin.dynamics.inverse import inverse_dynamics_sample, reduced_mass_matrix
from pollard_pin.kinematics import solve_closure, tool_pose
from pollard_pin.paths.curves import THESIS_DURATION, thesis_curve


def gravity_instability(robot) -> np.ndarray:
    """Growth rates [1/s] of the linearisation at home under constant actuator torques.

    M_red δθ̈ = −H δθ with H = ∂τ_static/∂θ_act (central differences along the closed loop).
    """
    q0 = robot.home()
    act = q0[robot.actuated_v]
    h = 1e-6
    H = np.empty((6, 6))
    for j in range(6):
        taus = []
        for s in (1, -1):
            a = act.copy()
            a[j] += s * h
            q = solve_closure(robot, a, q_guess=q0)
            taus.append(inverse_dynamics_sample(robot, q, np.zeros(12), np.zeros(12))[0])
        H[:, j] = (taus[0] - taus[1]) / (2 * h)
    lam2 = np.linalg.eigvals(-np.linalg.solve(reduced_mass_matrix(robot, q0), H))
    return np.sqrt(lam2.real[lam2.real > 1e-9])


def drift(robot, sim, curve) -> np.ndarray:
    ref = curve(sim.t)[0][:, :3]
    out = np.full(len(sim.t), np.nan)
    for k, q in enumerate(sim.q):
        if not np.all(np.isfinite(q)):
            break
        out[k] = np.linalg.norm(tool_pose(robot, q).translation - ref[k])
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=THESIS_DURATION)
    ap.add_argument("--dt", type=float, default=1e-3)
    ap.add_argument("--bandwidth", type=float, default=20.0, help="PD bandwidth [rad/s]")
    ap.add_argument("--open-loop-horizon", type=float, default=4.0,
                    help="open-loop replay length [s] (it diverges: see the growth rate)")
    args = ap.parse_args(argv)

    robot = pp.load()
    home = robot.params.home_pose

    def curve(t):
        return thesis_curve(t, THESIS_DURATION, home)

    start = pp.inverse_kinematics(robot, *curve(np.array([0.0])), np.array([0.0]))
    q0, v0 = start.q[0], start.v[0]
    rates = gravity_instability(robot)
    print(f"linearisation at home, constant torques: unstable growth rates {np.round(rates, 3)} "
          f"1/s (error ×10 every {np.log(10) / rates.max():.2f} s)")

    horizon = min(args.open_loop_horizon, args.duration)
    t0 = time.perf_counter()
    sim = replay_open_loop(robot, trajectory_torques(robot, curve, q0), q0, v0, horizon, args.dt)
    d = drift(robot, sim, curve)
    over = np.flatnonzero(~(d <= 1e-3))
    when = f"passes 1 mm at t = {sim.t[over[0]]:.2f} s" if len(over) else "stays below 1 mm"
    print(f"open loop, {horizon:g} s at dt = {args.dt:g} s: drift {np.nanmax(d[:len(d) // 2]):.3g}"
          f" m over the first {horizon / 2:g} s, {when} "
          f"[{time.perf_counter() - t0:.1f} s wall]")

    t0 = time.perf_counter()
    fn = trajectory_torques(robot, curve, q0, bandwidth=args.bandwidth)
    sim = replay_open_loop(robot, fn, q0, v0, args.duration, args.dt)
    d = drift(robot, sim, curve)
    print(f"with PD (bandwidth {args.bandwidth:g} rad/s) around the feedforward, "
          f"{args.duration:g} s: max tool-tip drift {np.nanmax(d):.3g} m, max closure residual "
          f"{sim.closure_residual.max():.3g} m, peak PD torque {fn.state['feedback']:.3g} N·m "
          f"[{time.perf_counter() - t0:.1f} s wall]")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
