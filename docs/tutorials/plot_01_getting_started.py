"""
Getting started: the thesis painting path
=========================================

Load the model, solve the thesis' painting trajectory (docs/model.md §9) through inverse
kinematics and inverse dynamics, and read the result: joint angles, actuator torques, the
closure forces at the two spherical joints, and the singularity margins.
"""

# %%
# Load the robot
# --------------
# :func:`pollard_pin.load` builds the Pinocchio model from the shipped parameter file
# (``models/pollard.toml``): the open tree, its two cut spherical joints as closure
# constraints, and the home pose with the loops closed.
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import pollard_pin as pp

robot = pp.load()
print("actuated joints:", robot.actuated)
print("all joints:", len(robot.joint_names))

# %%
# The thesis trajectory
# ---------------------
# :func:`pollard_pin.thesis_trajectory` is the painting curve of the thesis: the tool tip
# (x, y, z in m) and its ZYZ orientation (psi, theta, phi in rad) with exact first and second
# derivatives. A coarse sampling keeps this page fast.
traj = pp.thesis_trajectory(duration=20.0, samples=401)
print(f"{len(traj)} samples over {traj.t[-1]:.1f} s; first pose {traj.poses[0].round(3)}")

# %%
# Solve kinematics and dynamics
# -----------------------------
# :func:`pollard_pin.run_pipeline` runs the constrained inverse kinematics, checks the
# joint limits, then the inverse dynamics (RNEA on the open tree plus the closure forces).
result = pp.run_pipeline(robot, traj)
ik, dyn = result.ik, result.dynamics
print(f"largest loop-closure residual {ik.closure_residual.max():.1e} m")
print(f"smallest wrist margin |sin θ1716| {ik.wrist_margin.min():.3f}")
for i, name in enumerate(robot.actuated):
    print(f"  {name:10s} peak |tau| {abs(dyn.tau[:, i]).max():.4f} N·m")

# %%
# Every output column by name
# ---------------------------
# :meth:`RunResult.columns` is the layout of the ``pollard-pin run`` CSV: SI units,
# radians. :func:`pollard_pin.write_run_table` writes it (CSV, or Parquet for
# ``*.parquet``) and :func:`pollard_pin.read_result` reads it back with its units.
cols = result.columns()
print(len(cols), "columns, e.g.", list(cols)[:8])
with tempfile.TemporaryDirectory() as tmp:
    pp.write_run_table(result, Path(tmp) / "run.csv")
    table = pp.read_result(Path(tmp) / "run.csv")
    print("read back:", len(table.columns), "columns")

# %%
# Plot the actuator torques and the closure forces
# ------------------------------------------------
fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
for i, name in enumerate(robot.actuated):
    ax1.plot(ik.t, dyn.tau[:, i], label=name)
ax1.set_ylabel("torque [N·m]")
ax1.legend(fontsize=7, ncol=3)
force = np.linalg.norm(dyn.closure_forces, axis=2)
ax2.plot(ik.t, force[:, 0], label="leg 1")
ax2.plot(ik.t, force[:, 1], label="leg 2")
ax2.set_xlabel("t [s]")
ax2.set_ylabel("|closure force| [N]")
ax2.legend()
fig.tight_layout()
plt.show()
