"""
A paint cell: two robots on one line
====================================

One robot reaches a band about 0.255 m tall at the spraying standoff. A panel 0.33 m tall
riding a conveyor needs a cell: several robots along the line, each painting its zone of the
part as it passes, the zones meeting at seams the film must not show (docs/model.md §26).
A job with ``[line]`` and ``[[robot]]`` tables places the robots; without them,
:func:`pollard_pin.propose_layout` proposes bases for N robots and
:func:`pollard_pin.fewest_robots` finds the fewest that paint the part. The command line:
``pollard-pin paint --job cell.toml --out DIR`` (``--robots N|auto`` to propose).
"""

# %%
# The job: a panel taller than one robot reaches
# ----------------------------------------------
# ``examples/cell.toml`` without its ``[[robot]]`` tables: a 0.80 × 0.33 m panel, 0.75 m
# upstream at t = 0, carried along +y at 2 cm/s.
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import pollard_pin as pp

folder = Path(tempfile.mkdtemp())
(folder / "cell.toml").write_text("""
[panel]
center = [0.70, -0.75, 0.18]    # m, world, at t = 0
normal = [-1.0, 0.0, 0.0]       # towards the robots
width = 0.80                    # m, along the line
height = 0.33                   # m

[gun]
standoff = 0.15
sigma = 0.010
flow = 1.5e-7

[job]
thickness = 25e-6

[line]
speed = 0.02                    # m/s
direction = [0.0, 1.0, 0.0]
""")
robot = pp.load()
job = pp.load_job(folder / "cell.toml")

# %%
# A layout for two robots
# -----------------------
# ``propose_layout`` stacks the zones over the part's height, one per robot, and spaces the
# bases along the line so the robots clear each other (§26.5). Each is a ``CellRobot``: the
# ``name`` of its output folder, its ``base`` [m] and ``rotation`` [deg] in the world; what
# ``paint --robots N`` writes as ``[[robot]]`` tables in ``robots.toml``.
for r in pp.propose_layout(robot, job, 2):
    print(f"{r.name}: base {r.base} m, rotation {r.rotation} deg")

# %%
# The fewest robots that paint the part
# -------------------------------------
# ``fewest_robots`` tries the fewest whose reach bands hold the zones, then more if a plan is
# refused, and returns the robots with the cell's :class:`pollard_pin.PaintResult`. An 8 mm
# film resolution keeps this page quick; ``compliance=False`` leaves out the drives'
# springs' effect on the film (a second film integration).
robots, result = pp.fewest_robots(robot, job, options=pp.PaintOptions(
    resolution=0.008, compliance=False))
rep = result.report
print(f"{len(robots)} robots; {rep.kind}")
split = result.plan.split
for zone in split.zones:
    print(f"  {zone.robot} paints z from {zone.lo:g} to {zone.hi:g} m")  # ±inf: the edge
line = rep.line
print(f"line {line['speed']} m/s: cycle {line['cycle']:.1f} s (slowest: "
      f"{line['slowest_robot']}), {line['parts_per_hour']:.0f} parts/h, speed upper bound "
      f"{line['upper_bound']:.3f} m/s")
th = rep.thickness
print(f"film {th['mean'] * 1e6:.2f} µm mean, {th['within_5pct']:.1%} within ±5 %, "
      f"{th['within_10pct']:.1%} within ±10 %")
clear = rep.data["clearance"]
print(f"smallest clearance: {clear['between_robots_m'] * 1e3:.0f} mm between robots "
      f"({' and '.join(clear['pair'])}), {clear['to_part_m'] * 1e3:.0f} mm from a robot to "
      f"the part, {clear['gun_to_part_m'] * 1e3:.0f} mm from the gun's body to it")

# %%
# The seam
# --------
# Where the zones meet, each robot's strokes cross the seam at constant speed and its gun
# switches there, so the two edges of the spray spot add to one (§26.3). The film across the
# seam, relative to the target, over the panel (world coordinates at t = 0):
for seam in rep.data["seams"]:
    print(f"seam at z = {seam['at']} m, ±{seam['band_m']} m: film {seam['min']:.4f} … "
          f"{seam['max']:.4f} of the target")
pts = result.film.points
nv, nu = pts.shape[:2]
deviation = (result.film.thickness.reshape(nv, nu) / rep.target - 1) * 100
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.6), width_ratios=(2, 1))
im = ax1.pcolormesh(pts[..., 1], pts[..., 2], deviation, cmap="RdBu_r", vmin=-1, vmax=1,
                    shading="auto")
for w in split.seams():
    ax1.axhline(w, color="k", ls="--", lw=0.8)
fig.colorbar(im, ax=ax1, label="film − target [%]")
ax1.set_aspect("equal")
ax1.set_xlabel("y [m]")
ax1.set_ylabel("z [m]")
ax1.set_title("film, the seam dashed")
middle = nu // 2
ax2.plot(deviation[:, middle], pts[:, middle, 2])
for w in split.seams():
    ax2.axhline(w, color="k", ls="--", lw=0.8)
ax2.set_xlim(-1, 1)
ax2.set_xlabel("film − target [%]")
ax2.set_title(f"across the seam at y = {pts[0, middle, 1]:.2f} m", fontsize=9)
fig.tight_layout()
plt.show()

# %%
# Each robot's program and motors
# -------------------------------
# ``rep.data["robots"]`` holds, per robot, when its gun may first turn on, its program time
# and each motor's peak and RMS torque as a share of its ratings; ``result.write(DIR)``
# writes ``DIR/<name>/path.csv``, each robot's program in its own base frame on the cell's
# clock, which ``run``, ``size`` and ``simulate`` check as it is.
names = list(rep.motors)
fig, ax = plt.subplots(figsize=(8, 3.2))
width = 0.8 / len(rep.data["robots"])
for i, entry in enumerate(rep.data["robots"]):
    print(f"{entry['name']}: starts at {entry['start']:.1f} s, program {entry['program_time']:.1f}"
          f" s; peak torque at most {max(m['peak_torque'] for m in entry['motors'].values()):.0%}"
          f", RMS at most {max(m['rms_torque'] for m in entry['motors'].values()):.0%}")
    x = np.arange(len(names)) + i * width
    ax.bar(x, [entry["motors"][n]["peak_torque"] * 100 for n in names], width,
           label=f"{entry['name']} peak")
    ax.scatter(x, [entry["motors"][n]["rms_torque"] * 100 for n in names], color="k", s=10,
               zorder=3)
ax.set_xticks(np.arange(len(names)) + width / 2, names, fontsize=8)
ax.set_ylabel("use of the rating [%]")
ax.set_title("peak torque (bars) and RMS torque (dots) per motor", fontsize=9)
ax.legend(fontsize=8)
fig.tight_layout()
plt.show()
print(sorted(p.name for p in result.write(folder / "out").parent.iterdir()))
