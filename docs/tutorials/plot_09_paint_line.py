"""
Painting a part on a moving line
================================

A part longer than the robot's reach rides a conveyor past it. A job with a ``[line]``
table (speed in m/s, direction in the world) is planned relative to the part, the robot
running that motion plus the line's, every check on the world path (docs/model.md §24).
"""

# %%
# A long strip
# ------------
# A 2 mm sheet 0.90 m long (along y, longer than the reach) and 0.10 m high, bent to a
# cylinder of radius 3 m, convex towards the robot, made with trimesh.
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import trimesh

import pollard_pin as pp

radius = 3.0
strip = trimesh.creation.box(extents=(0.002, 0.90, 0.10)).subdivide_to_size(0.01)
x, y, z = strip.vertices.T
r = radius - (x + 0.001)
strip.vertices = np.column_stack([radius - r * np.cos(y / radius), r * np.sin(y / radius), z])
folder = Path(tempfile.mkdtemp())
strip.export(folder / "strip.stl")

# %%
# The job
# -------
# At t = 0 the part is 0.75 m upstream; the line moves it along +y at 3 cm/s.
(folder / "line.toml").write_text("""
[part]
mesh = "strip.stl"
units = "m"
position = [0.70, -0.75, 0.16]
facing = [-1.0, 0.0, 0.0]
max_angle = 45.0

[gun]
standoff = 0.15
sigma = 0.010
flow = 1.5e-7

[job]
thickness = 25e-6

[line]
speed = 0.03                  # m/s
direction = [0.0, 1.0, 0.0]
""")
robot = pp.load()
job = pp.load_job(folder / "line.toml")
# A film resolution of 8 mm keeps this page quick, and so does leaving out what the drives'
# compliance does to the film (``compliance=False``: a second film integration).
result = pp.paint(robot, job, options=pp.PaintOptions(resolution=0.008, compliance=False))

# %%
# The line's numbers
# ------------------
# ``report.line`` holds the wait before the part arrives, the cycle, the pitch between parts
# and the parts per hour, and the painting-only upper bound on the line speed.
# ``PaintOptions(max_line_speed=True)`` would plan at the fastest speed that paints the part.
rep = result.report
print("timings [s]:", {k: round(v, 2) for k, v in rep.timings.items()})
line = rep.line
print(f"wait {line['start_delay']:.2f} s, cycle {line['cycle']:.2f} s, "
      f"{line['parts_per_hour']:.0f} parts/h, speed upper bound {line['upper_bound']:.3f} m/s")
th = rep.thickness
print(f"film {th['mean'] * 1e6:.2f} µm mean, {th['within_5pct']:.1%} within ±5 %; motors at "
      f"most {max(u['peak_torque'] for u in rep.motors.values()):.0%} of a peak torque, "
      f"{max(u['rms_torque'] for u in rep.motors.values()):.0%} of a continuous one")

# %%
# The program in the world
# ------------------------
# The gun waits (off) until the part is within reach, then paints passes across the travel
# while following the line, and returns to its start pose.
traj = result.plan.trajectory
on = result.plan.spray > 0
fig, ax = plt.subplots(figsize=(8, 3.6))
ax.plot(traj.t, traj.poses[:, 1], color="0.6", lw=1, label="tool y, gun off")
ax.plot(traj.t, np.where(on, traj.poses[:, 1], np.nan), color="C3", label="tool y, gun on")
ax.plot(traj.t, traj.poses[:, 2], color="C0", lw=1, label="tool z")
ax.set_xlabel("t [s]")
ax.set_ylabel("world position [m]")
ax.legend(fontsize=8)
fig.tight_layout()
plt.show()
