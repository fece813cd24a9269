"""
A cell of two robots painting a curved part
===========================================

A part taller than one robot's band and longer than its reach, and curved: a cylinder
section of radius 1.5 m, 0.80 m of arc along the line and 0.33 m high, convex towards the
robots, riding the line at 1.5 cm/s past two robots, one raised 0.15 m and 0.75 m further
down the line (``examples/cell_curved.toml``, docs/model.md §26). Each robot paints its zone
of the part's strokes as the part passes; the strokes run across the travel, yawing with the
surface, and where the zones meet the two guns switch at the same point of the same
constant-speed stroke, so the seam lays the target. The command line:
``pollard-pin paint --job examples/cell_curved.toml --out DIR``.
"""

# %%
# The part and the job
# --------------------
# ``examples/parts/make_parts.py`` writes the part in mm; here the same shape is made in m
# with the package's own shapes (a 2 mm sheet, one face towards the robots), and the job
# names it with two ``[[robot]]`` tables.
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt

import pollard_pin as pp
from pollard_pin.painting.workpiece import shapes

folder = Path(tempfile.mkdtemp())
shapes.curved_panel(radius=1.5, width=0.80, height=0.33, step=0.02,
                    z0=0.18).export(folder / "curved_tall.stl")
(folder / "cell_curved.toml").write_text("""
[part]
mesh = "curved_tall.stl"
position = [0.0, -0.75, 0.0]    # m: where the part is at t = 0 (upstream)
facing = [-1.0, 0.0, 0.0]       # paint the faces towards the robots
max_angle = 45.0

[gun]
standoff = 0.15
sigma = 0.010
flow = 1.5e-7

[job]
thickness = 25e-6

[line]
speed = 0.015                   # m/s
direction = [0.0, 1.0, 0.0]

[[robot]]
name = "low"
base = [0.0, 0.0, 0.0]

[[robot]]
name = "high"
base = [0.0, 0.75, 0.15]        # raised 0.15 m, 0.75 m down the line
""")
robot = pp.load()
job = pp.load_job(folder / "cell_curved.toml")

# %%
# Plan and paint
# --------------
# A 1 cm film resolution and ``compliance=False`` (no second film of the drives' springs)
# keep this page quick; the planning itself is the command's (a minute or so of CPU).
result = pp.paint(robot, job, options=pp.PaintOptions(resolution=0.01, compliance=False))
rep = result.report
line = rep.line
print(f"line {line['speed']} m/s: cycle {line['cycle']:.1f} s (slowest: "
      f"{line['slowest_robot']}), {line['parts_per_hour']:.0f} parts/h")
th = rep.thickness
print(f"film {th['min'] * 1e6:.2f}–{th['max'] * 1e6:.2f} µm, {th['within_5pct']:.1%} of the "
      f"area within ±5 %")
for seam in rep.data["seams"]:
    print(f"seam at z = {seam['at']:.3f} m, ±{seam['band_m']} m: film {seam['min']:.4f} … "
          f"{seam['max']:.4f} of the target")
for entry in rep.data["robots"]:
    use = max(max(m["peak_torque"], m["speed"]) for m in entry["motors"].values())
    print(f"{entry['name']}: strokes {entry['strokes']['direction']} the travel, starts at "
          f"{entry['start']:.1f} s, program {entry['program_time']:.1f} s, motors at most "
          f"{use:.0%} of their ratings")

# %%
# The film over the part
# ----------------------
# The film points lie on the part's faces at its t = 0 pose (world coordinates); seen from
# the robots (y along the line, z up), coloured by their deviation from the target, the seam
# dashed.
film = result.film
on = film.painted
xyz = film.points.points[on]
deviation = (film.thickness[on] / rep.target - 1) * 100
split = result.plan.split
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.6), width_ratios=(2, 1))
sc = ax1.scatter(xyz[:, 1], xyz[:, 2], c=deviation, cmap="RdBu_r", vmin=-2, vmax=2, s=9)
for w in split.seams():
    ax1.axhline(w, color="k", ls="--", lw=0.8)
fig.colorbar(sc, ax=ax1, label="film − target [%]")
ax1.set_aspect("equal")
ax1.set_xlabel("y [m]")
ax1.set_ylabel("z [m]")
ax1.set_title("film on the curved part, the seam dashed")
# the surface bows towards the robots: its depth x along the line
ax2.scatter(xyz[:, 1], xyz[:, 0], s=2, c="0.4")
ax2.set_xlabel("y [m]")
ax2.set_ylabel("x [m] (depth)")
ax2.set_title("the part's depth along the line", fontsize=9)
fig.tight_layout()
plt.show()

# %%
# Each robot's strokes
# --------------------
# Each robot's program is in its own base frame on the cell's clock; its gun's aim point
# while spraying, seen from the part at t = 0 (``world_gun`` takes the line's travel off),
# covers its zone up to the seam.
from pollard_pin.painting.film.cell import world_gun  # noqa: E402

fig, ax = plt.subplots(figsize=(8, 3.4))
for rp, colour in zip(result.plan.robots, ("tab:blue", "tab:orange")):
    _, tip, frames, spray = world_gun(rp)  # frames[:, :, 0]: the spray axis
    aim = tip + job.standoff * frames[:, :, 0]
    open_ = spray > 0
    ax.plot(aim[open_, 1], aim[open_, 2], ".", ms=1, color=colour,
            label=f"{rp.robot.name} (zone {rp.zone.lo:.3g} … {rp.zone.hi:.3g} m)")
for w in split.seams():
    ax.axhline(w, color="k", ls="--", lw=0.8)
ax.set_xlabel("y on the part [m]")
ax.set_ylabel("z [m]")
ax.set_title("the sprayed aim points, per robot", fontsize=9)
ax.legend(fontsize=8, markerscale=8)
fig.tight_layout()
plt.show()
