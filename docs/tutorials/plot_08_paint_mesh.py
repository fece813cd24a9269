"""
Painting a part from its mesh
=============================

A job may give a ``[part]`` (an STL, OBJ or PLY mesh) instead of a flat panel. The planner
lays passes on the surface, keeps the gun at the standoff along the surface normal, and
integrates the film on the faces, with the shadows the part casts on itself (docs/model.md
§23). :func:`pollard_pin.place` first finds where the part fits the robot's reach.
"""

# %%
# A curved part
# -------------
# Any mesh will do; here one made with trimesh: a 2 mm sheet, 0.24 × 0.10 m, bent to a
# cylinder of radius 0.4 m, convex towards the robot, written as a binary STL in metres.
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import trimesh

import pollard_pin as pp

radius = 0.4
sheet = trimesh.creation.box(extents=(0.002, 0.24, 0.10)).subdivide_to_size(0.01)
x, y, z = sheet.vertices.T
a = y / radius                                 # arc length along y → angle
r = radius - (x + 0.001)                      # the front face on the cylinder
sheet.vertices = np.column_stack([radius - r * np.cos(a), r * np.sin(a), z])
folder = Path(tempfile.mkdtemp())
sheet.export(folder / "curved.stl")
print(f"{len(sheet.faces)} faces, watertight {sheet.is_watertight}")

# %%
# The job
# -------
# ``facing`` and ``max_angle`` choose the faces to paint (outward normals within 45° of −x,
# towards the robot). The mesh is about the origin; ``position`` puts it in the world.
(folder / "part.toml").write_text("""
[part]
mesh = "curved.stl"
units = "m"
position = [0.70, 0.0, 0.16]   # m: a first guess, in front of the robot
facing = [-1.0, 0.0, 0.0]
max_angle = 45.0

[gun]
standoff = 0.15
sigma = 0.010
flow = 1.5e-7

[job]
thickness = 25e-6
""")
job = pp.load_job(folder / "part.toml")
robot = pp.load()

# %%
# Place it
# --------
# :func:`pollard_pin.place` tries positions, and turns about the facing axis, and keeps the
# one that puts every gun pose of the passes within reach with the most margin.
placed = pp.place(robot, job, pp.PlaceOptions(max_turn=0.0))
print(f"turn {placed.turn:+.0f}°, margin {placed.margin * 1e3:.0f} mm along every axis, "
      f"{placed.poses} gun poses checked")
placed.write(folder / "placed.toml")
job = pp.load_job(folder / "placed.toml")

# %%
# Paint it
# --------
# A coarser film resolution (4 mm) than the default σ/3 keeps this page quick, and so does
# leaving out what the drives' compliance does to the film (``compliance=False``).
result = pp.paint(robot, job, options=pp.PaintOptions(resolution=0.004, compliance=False))
rep = result.report
th = rep.thickness
print(f"cycle {rep.cycle_time:.2f} s; film {th['mean'] * 1e6:.2f} µm mean, "
      f"{th['within_5pct']:.1%} of the painted area within ±5 %")
print(f"transfer efficiency {result.film.efficiency:.0%}; motors at most "
      f"{max(u['peak_torque'] for u in rep.motors.values()):.0%} of a peak torque")

# %%
# The film on the part, and the gun's yaw
# ---------------------------------------
# Each film point lies on a face of the mesh (coloured by its deviation from the target);
# the gun turns to stay normal to the surface (with θ = 0 the ZYZ angles make a turn about
# z by ψ + φ: the gun's yaw), on only over the passes (``plan.spray``, the
# trigger that ``path.csv`` writes as its ``spray`` column).
pts = result.film.points.points[result.film.painted]
deviation = (result.film.thickness[result.film.painted] / rep.target - 1) * 100
traj = result.plan.trajectory
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.6))
sc = ax1.scatter(pts[:, 1], pts[:, 2], c=deviation, s=3, cmap="RdBu_r", vmin=-2, vmax=2)
fig.colorbar(sc, ax=ax1, label="film − target [%]")
ax1.set_aspect("equal")
ax1.set_xlabel("y [m]")
ax1.set_ylabel("z [m]")
ax1.set_title("film on the painted faces")
yaw = np.degrees(traj.poses[:, 3] + traj.poses[:, 5])
ax2.plot(traj.t, yaw, color="0.6", lw=1, label="gun off")
ax2.plot(traj.t, np.where(result.plan.spray > 0, yaw, np.nan),
         color="C3", label="gun on")
ax2.set_xlabel("t [s]")
ax2.set_ylabel("yaw ψ + φ [deg]")
ax2.legend(fontsize=8)
fig.tight_layout()
plt.show()

# %%
# ``result.write(DIR)`` writes ``film.ply`` (the refined mesh with a per-vertex
# ``thickness``) beside ``path.csv``; ``pollard-pin view --paint DIR --html film.html``
# shows the film on the part while the robot runs the path.
