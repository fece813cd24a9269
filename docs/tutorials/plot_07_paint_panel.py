"""
Painting a panel
================

Plan a raster spray program over a flat panel, integrate the film it leaves, and check the
motors (docs/model.md §20–§21). A job is a small TOML file; the command line runs it with
``pollard-pin paint --job paint.toml --out DIR``.
"""

# %%
# The job
# -------
# A 0.26 × 0.12 m panel 0.70 m in front of the robot, facing it; the gun 0.15 m from the
# panel with a spray spot of σ = 10 mm and a film flow of 1.5e-7 m³/s; a 25 µm target film.
# SI units throughout. Without an ``actuators`` key the package's motor ratings are used.
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt

import pollard_pin as pp

job_text = """
[panel]
center = [0.70, 0.0, 0.16]   # m, world
normal = [-1.0, 0.0, 0.0]    # towards the robot
width = 0.26                 # m, along u = normal × v
height = 0.12                # m, along v = world z projected onto the panel

[gun]
standoff = 0.15              # m, nozzle to panel
sigma = 0.010                # m, spray spot spread
flow = 1.5e-7                # m³/s of film volume deposited

[job]
thickness = 25e-6            # m
"""
folder = Path(tempfile.mkdtemp())
(folder / "paint.toml").write_text(job_text)
job = pp.load_job(folder / "paint.toml")

# %%
# Plan, film and report
# ---------------------
# :func:`pollard_pin.paint` plans the passes at the constant speed the target film needs,
# makes every turnaround as short as the motors allow, integrates the film on a grid over the
# panel and fills the report (what ``paint.json`` holds).
robot = pp.load()
result = pp.paint(robot, job)
rep = result.report
th = rep.thickness
print(f"{rep.data['passes']} passes at {rep.data['speed']:.3f} m/s, cycle {rep.cycle_time:.2f} s "
      f"(painting-only lower bound {rep.data['lower_bound']:.2f} s)")
print(f"film {th['mean'] * 1e6:.2f} µm mean, {th['deviation_min']:+.2%} / "
      f"{th['deviation_max']:+.2%} of the target, {th['within_5pct']:.0%} within ±5 %")
print(f"gun body at least {rep.data['min_clearance_m'] * 1e3:.1f} mm from the panel")
for name, use in rep.motors.items():
    print(f"  {name:10s} " + ", ".join(f"{k} {v:.0%}" for k, v in use.items()))

# %%
# The film and the program
# ------------------------
# ``result.film`` holds the grid over the panel (edges included) and the thickness on it;
# ``result.plan.trajectory`` is the program, a :class:`pollard_pin.Trajectory` (on a
# still panel the gun sprays throughout; a part's program adds a ``spray`` trigger column).
nv, nu = result.film.points.shape[:2]
deviation = (result.film.thickness.reshape(nv, nu) / rep.target - 1) * 100
pts = result.film.points
traj = result.plan.trajectory
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.6))
im = ax1.pcolormesh(pts[..., 1], pts[..., 2], deviation, cmap="RdBu_r",
                    vmin=-1, vmax=1, shading="auto")
fig.colorbar(im, ax=ax1, label="film − target [%]")
ax1.set_aspect("equal")
ax1.set_xlabel("y [m]")
ax1.set_ylabel("z [m]")
ax1.set_title("film on the panel, edges included")
sc = ax2.scatter(traj.poses[:, 1], traj.poses[:, 2], c=traj.t, s=2, cmap="viridis")
fig.colorbar(sc, ax=ax2, label="t [s]")
ax2.set_aspect("equal")
ax2.set_xlabel("y [m]")
ax2.set_title("tool-tip path")
fig.tight_layout()
plt.show()

# %%
# Write the outputs
# -----------------
# :meth:`PaintResult.write` writes what ``pollard-pin paint`` writes: ``path.csv`` (a
# trajectory that ``run``, ``size``, ``simulate`` and ``view`` take as it is), the film table,
# ``film.ply``, ``paint.json`` and ``thickness.png``.
out = folder / "out"
result.write(out, "csv")
print(sorted(p.name for p in out.iterdir()))
again = pp.from_csv(out / "path.csv")
print(f"path.csv: {len(again)} samples over {again.t[-1]:.2f} s")
