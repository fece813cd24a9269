"""
Your own trajectory from a CSV file
===================================

Write a tool path as a CSV (``t,x,y,z,psi,theta,phi`` in s, m and rad), read it with
:func:`pollard_pin.from_csv`, and solve it. The same file works on the command line:
``pollard-pin run --trajectory circle.csv`` (and ``view``, ``plot``, ``report``, ``size``,
``simulate``).
"""

# %%
# Write a circle on the wall
# --------------------------
# The gun keeps spraying along +x (psi = theta = phi = 0) at the wall x = 0.55 m, in front of
# the robot's home pose. Only the poses are given: the reader fits a quintic spline for the
# velocities and accelerations (optional ``d_*`` and ``dd_*`` columns give them exactly).
import tempfile
import warnings
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import pollard_pin as pp

period, radius = 8.0, 0.06
t = np.linspace(0.0, period, 401)
a = 2 * np.pi * t / period
zeros = np.zeros_like(t)
rows = np.column_stack([t, 0.55 + zeros, radius * np.cos(a), 0.16 + radius * np.sin(a),
                        zeros, zeros, zeros])
tmp = Path(tempfile.mkdtemp())
csv_path = tmp / "circle.csv"
np.savetxt(csv_path, rows, fmt="%.9g", delimiter=",", header="t,x,y,z,psi,theta,phi", comments="")
print(csv_path.read_text().splitlines()[:3])

# %%
# Read it back
# ------------
# :func:`pollard_pin.from_csv` validates the file (one line naming the row and column of a
# bad value) and says where the derivatives come from in a warning, which we silence here.
with warnings.catch_warnings():
    warnings.simplefilter("ignore", UserWarning)
    traj = pp.from_csv(csv_path)
print(f"{len(traj)} samples, derivatives from a {traj.derivatives}")

# %%
# Solve it
# --------
robot = pp.load()
result = pp.run_pipeline(robot, traj)
tau = result.dynamics.tau
peaks = abs(tau).max(axis=0)
print("peak |tau| [N·m]:", {n: round(float(p), 4) for n, p in zip(robot.actuated, peaks)})
print(f"wrist margin >= {result.ik.wrist_margin.min():.3f}, "
      f"closure residual <= {result.ik.closure_residual.max():.1e} m")

# %%
# Write a trajectory from Python
# ------------------------------
# :func:`pollard_pin.to_csv` writes any :class:`pollard_pin.Trajectory` with its derivatives,
# so reading it back needs no spline.
exact = tmp / "circle_exact.csv"
pp.to_csv(traj, exact)
again = pp.from_csv(exact)
print(f"round trip: derivatives from {again.derivatives!r}, "
      f"max pose difference {abs(again.poses - traj.poses).max():.1e}")

# %%
# The path and the torques
# ------------------------
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.8))
ax1.plot(traj.poses[:, 1], traj.poses[:, 2])
ax1.set_aspect("equal")
ax1.set_xlabel("y [m]")
ax1.set_ylabel("z [m]")
ax1.set_title("tool tip on the wall x = 0.55 m")
for i, name in enumerate(robot.actuated[:3]):
    ax2.plot(traj.t, tau[:, i], label=name)
ax2.set_xlabel("t [s]")
ax2.set_ylabel("torque [N·m]")
ax2.legend(fontsize=8)
fig.tight_layout()
plt.show()
